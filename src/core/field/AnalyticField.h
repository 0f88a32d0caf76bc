#pragma once
// A built-in function evaluated analytically: the ground truth of every comparison.
#include "core/analytic/BuiltinFunction.h"
#include "core/field/Field.h"

namespace mfadvr {

class AnalyticField {
 public:
  explicit AnalyticField(const BuiltinFunction& f) : f_(&f) {}
  Vec3d boxMin() const { return BuiltinFunction::domainMin(); }
  Vec3d boxMax() const { return BuiltinFunction::domainMax(); }

  class Sampler {
   public:
    explicit Sampler(const BuiltinFunction& f) : f_(&f) {}
    float value(const Vec3d& x) const { return static_cast<float>(f_->value(x)); }
    ValueGradient valueGradient(const Vec3d& x) const {
      Vec3d g;
      ValueGradient r;
      r.value = static_cast<float>(f_->valueGradient(x, g));
      r.gradient = g.cast<float>();
      return r;
    }

   private:
    const BuiltinFunction* f_;
  };
  Sampler sampler() const { return Sampler(*f_); }

 private:
  const BuiltinFunction* f_;
};

}  // namespace mfadvr
