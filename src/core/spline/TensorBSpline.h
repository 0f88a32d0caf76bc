#pragma once
// A scalar tensor-product B-spline over the unit cube [0,1]^3.
//
// Per-axis degree (1..7) and control-point count; control points are float32, x fastest:
// P(i,j,k) = ctrl[i + n0 * (j + n1 * k)]. Queries take parametric coordinates (clamped to
// [0,1]) and return parametric derivatives; Model maps physical coordinates onto these.
// A const spline is safe to query from any number of threads.
//
// The spline owns its knots; its control points it owns too, or shares with whatever holds
// them (the bytes of a model file read in place, ModelFile.h), and hands out a SplineView for the
// header-only evaluation kernel (SplineKernel.h); value(), valueGradient() and
// valueGradientHessian() are that kernel with the degree chosen at run time, for single queries.
// Loops over many points (Model::evaluate, the ray caster) choose the degree once and call the
// kernel directly.
#include <array>
#include <memory>
#include <span>
#include <vector>

#include "core/spline/KnotVector.h"
#include "core/spline/SpanRanges.h"
#include "core/spline/SplineView.h"
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
  // Control points held by `owner` (kept alive by the spline and its copies), not copied.
  TensorBSpline(std::array<KnotVector, 3> knots, std::shared_ptr<const void> owner,
                std::span<const float> ctrl);

  const KnotVector& knots(int axis) const { return knots_[axis]; }
  const std::array<KnotVector, 3>& allKnots() const { return knots_; }
  Degree3 degrees() const;
  Index3 counts() const;
  std::span<const float> controlPoints() const { return ctrl_; }

  // Parametric coordinates, clamped to [0,1]^3; derivatives are parametric.
  float value(const Vec3d& u) const;
  ValueGradient valueGradient(const Vec3d& u) const;
  ValueGradientHessian valueGradientHessian(const Vec3d& u) const;

  // Raw view for the kernel; valid while this spline lives and is not assigned to.
  SplineView view() const;

  // The control-point range of every knot-span cell (empty-space skipping), computed on first
  // use and kept; safe to call from several threads. Copies of a spline share it.
  std::shared_ptr<const SpanRanges> spanRanges() const;
  // What this spline and its copies share, to tell one spline from another without computing
  // anything (caches keyed on a spline hold it: the key stays unique while held).
  std::shared_ptr<const void> identity() const { return derived_; }

  // The same function with one more knot at `u` on `axis` (Boehm's algorithm, in double).
  TensorBSpline withInsertedKnot(int axis, double u) const;

 private:
  struct Derived;
  void checkShape() const;

  std::array<KnotVector, 3> knots_;
  std::shared_ptr<const void> ctrlOwner_;  // what keeps ctrl_ alive; copies share it
  std::span<const float> ctrl_;
  std::shared_ptr<Derived> derived_;
};

}  // namespace mfadvr
