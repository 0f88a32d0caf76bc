#pragma once
// The MFA model as a Field: exact spline value and analytic gradient at every sample, and the
// model's domain mask (the ray caster skips samples outside it).
//
// renderVolume() renders a ModelField through the spline kernel directly (ModelRenderer.cpp);
// the Sampler below serves fields built on top of a model (DerivedFields.h) and point queries.
// A caller that renders many frames of one model (a viewer) passes an EmptySpaceCache, so that
// the empty-space flags are rebuilt only when the transfer function changes.
#include "core/field/Field.h"
#include "core/model/Model.h"

namespace mfadvr {

class EmptySpaceCache;

class ModelField {
 public:
  explicit ModelField(const Model& model, EmptySpaceCache* cache = nullptr)
      : model_(&model), cache_(cache) {}
  const Model& model() const { return *model_; }
  EmptySpaceCache* emptySpaceCache() const { return cache_; }
  Vec3d boxMin() const { return model_->domain().min; }
  Vec3d boxMax() const { return model_->domain().max; }

  class Sampler {
   public:
    explicit Sampler(const Model& m)
        : model_(&m), masked_(!m.mask().empty() || m.boundary() != nullptr) {}
    float value(const Vec3d& x) const { return model_->value(x); }
    ValueGradient valueGradient(const Vec3d& x) const { return model_->valueGradient(x); }
    // False outside the model's domain (its exact boundary, else its mask). masked() is false for
    // a model without either (every model of a grid): the ray caster then skips the inside() calls.
    bool masked() const { return masked_; }
    bool inside(const Vec3d& x) const { return !masked_ || model_->inside(x); }

   private:
    const Model* model_;
    bool masked_;
  };
  Sampler sampler() const { return Sampler(*model_); }

 private:
  const Model* model_;
  EmptySpaceCache* cache_;
};

}  // namespace mfadvr
