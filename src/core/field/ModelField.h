#pragma once
// The MFA model as a Field: exact spline value and analytic gradient at every sample.
#include "core/field/Field.h"
#include "core/model/Model.h"

namespace mfadvr {

class ModelField {
 public:
  explicit ModelField(const Model& model) : model_(&model) {}
  Vec3d boxMin() const { return model_->domain().min; }
  Vec3d boxMax() const { return model_->domain().max; }

  class Sampler {
   public:
    explicit Sampler(const Model& m) : model_(&m) {}
    float value(const Vec3d& x) const { return model_->value(x); }
    ValueGradient valueGradient(const Vec3d& x) const { return model_->valueGradient(x); }

   private:
    const Model* model_;
  };
  Sampler sampler() const { return Sampler(*model_); }

 private:
  const Model* model_;
};

}  // namespace mfadvr
