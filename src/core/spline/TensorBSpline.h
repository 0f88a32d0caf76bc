#pragma once
// A scalar tensor-product B-spline over the unit cube [0,1]^3.
//
// Per-axis degree (1..7) and control-point count; control points are float32, x fastest:
// P(i,j,k) = ctrl[i + n0 * (j + n1 * k)]. Queries take parametric coordinates (clamped to
// [0,1]) and return parametric derivatives; Model maps physical coordinates onto these.
// A const spline is safe to query from any number of threads.
#include <array>
#include <vector>

#include "core/spline/KnotVector.h"
#include "core/util/Vec.h"

namespace mfadvr {

struct ValueGradient {
  float value = 0.0f;
  Vec3f gradient = Vec3f::Zero();
};

struct ValueGradientHessian {
  float value = 0.0f;
  Vec3f gradient = Vec3f::Zero();
  Sym3f hessian{};  // xx, xy, xz, yy, yz, zz
};

class TensorBSpline {
 public:
  TensorBSpline() = default;
  // Throws mfadvr::Error when ctrl.size() != n0*n1*n2.
  TensorBSpline(std::array<KnotVector, 3> knots, std::vector<float> ctrl);

  const KnotVector& knots(int axis) const { return knots_[axis]; }
  const std::array<KnotVector, 3>& allKnots() const { return knots_; }
  Degree3 degrees() const;
  Index3 counts() const;
  const std::vector<float>& controlPoints() const { return ctrl_; }

  float value(const Vec3d& u) const { return valueFn_(*this, u); }
  ValueGradient valueGradient(const Vec3d& u) const { return gradientFn_(*this, u); }
  ValueGradientHessian valueGradientHessian(const Vec3d& u) const;

  // The same function with one more knot at `u` on `axis` (Boehm's algorithm, in double).
  TensorBSpline withInsertedKnot(int axis, double u) const;

  // Hot-path entry points, selected once per spline: degree-specialized when all three degrees
  // are equal, generic otherwise.
  using ValueFn = float (*)(const TensorBSpline&, const Vec3d&);
  using GradientFn = ValueGradient (*)(const TensorBSpline&, const Vec3d&);

 private:
  std::array<KnotVector, 3> knots_;
  std::vector<float> ctrl_;
  ValueFn valueFn_ = nullptr;
  GradientFn gradientFn_ = nullptr;
};

}  // namespace mfadvr
