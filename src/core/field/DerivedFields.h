#pragma once
// Fields built from other fields: a central-difference gradient of any field's values, and the
// gradient-only test of the paper's Table 1 (value from one field, gradient from another).
#include <algorithm>

#include "core/field/Field.h"

namespace mfadvr {

// The gradient of `Inner` by central differences of its values with step h per axis (typically
// one grid spacing). Near the box faces the stencil is clipped to the box, so it becomes
// one-sided there.
template <Field Inner>
class CentralDifferenceField {
 public:
  CentralDifferenceField(Inner inner, const Vec3d& h) : inner_(std::move(inner)), h_(h) {}
  Vec3d boxMin() const { return inner_.boxMin(); }
  Vec3d boxMax() const { return inner_.boxMax(); }

  using InnerSampler = decltype(std::declval<const Inner&>().sampler());

  class Sampler {
   public:
    Sampler(const CentralDifferenceField& f)
        : s_(f.inner_.sampler()), h_(f.h_), lo_(f.boxMin()), hi_(f.boxMax()) {}
    float value(const Vec3d& x) { return s_.value(x); }
    // The inner field's domain, where it has one (a masked model).
    bool inside(const Vec3d& x) requires requires(InnerSampler& s, const Vec3d& y) { s.inside(y); }
    { return s_.inside(x); }
    bool masked() const requires requires(const InnerSampler& s) { s.masked(); }
    { return s_.masked(); }
    ValueGradient valueGradient(const Vec3d& x) {
      ValueGradient r;
      r.value = s_.value(x);
      for (int a = 0; a < 3; ++a) {
        Vec3d p = x, m = x;
        p[a] = std::min(x[a] + h_[a], hi_[a]);
        m[a] = std::max(x[a] - h_[a], lo_[a]);
        const double d = p[a] - m[a];
        r.gradient[a] = d > 0.0 ? static_cast<float>((s_.value(p) - s_.value(m)) / d) : 0.0f;
      }
      return r;
    }

   private:
    InnerSampler s_;
    Vec3d h_, lo_, hi_;
  };
  Sampler sampler() const { return Sampler(*this); }

 private:
  Inner inner_;
  Vec3d h_;
};

// Value from `ValueField` (the truth, in the paper's gradient test), gradient from
// `GradientField` (the method under test).
template <Field ValueField, Field GradientField>
class GradientFromField {
 public:
  GradientFromField(ValueField v, GradientField g) : v_(std::move(v)), g_(std::move(g)) {}
  Vec3d boxMin() const { return v_.boxMin(); }
  Vec3d boxMax() const { return v_.boxMax(); }

  class Sampler {
   public:
    Sampler(const GradientFromField& f) : v_(f.v_.sampler()), g_(f.g_.sampler()) {}
    float value(const Vec3d& x) { return v_.value(x); }
    ValueGradient valueGradient(const Vec3d& x) {
      ValueGradient r = g_.valueGradient(x);
      r.value = v_.value(x);
      return r;
    }

   private:
    decltype(std::declval<const ValueField&>().sampler()) v_;
    decltype(std::declval<const GradientField&>().sampler()) g_;
  };
  Sampler sampler() const { return Sampler(*this); }

 private:
  ValueField v_;
  GradientField g_;
};

}  // namespace mfadvr
