#include "core/spline/TensorBSpline.h"

#include <algorithm>
#include <mutex>
#include <string>

#include "core/spline/SplineKernel.h"
#include "core/util/Error.h"

namespace mfadvr {

struct TensorBSpline::Derived {
  std::once_flag once;
  std::shared_ptr<const SpanRanges> ranges;
};

TensorBSpline::TensorBSpline(std::array<KnotVector, 3> knots, std::vector<float> ctrl)
    : knots_(std::move(knots)), derived_(std::make_shared<Derived>()) {
  auto owned = std::make_shared<const std::vector<float>>(std::move(ctrl));
  ctrl_ = *owned;
  ctrlOwner_ = std::move(owned);
  checkShape();
}

TensorBSpline::TensorBSpline(std::array<KnotVector, 3> knots, std::shared_ptr<const void> owner,
                             std::span<const float> ctrl)
    : knots_(std::move(knots)),
      ctrlOwner_(std::move(owner)),
      ctrl_(ctrl),
      derived_(std::make_shared<Derived>()) {
  checkShape();
}

void TensorBSpline::checkShape() const {
  const Index3 n = counts();
  for (int a = 0; a < 3; ++a) {
    if (knots_[a].degree() < 1) throw Error("spline axis " + std::to_string(a) + " has no knots");
  }
  if (static_cast<std::int64_t>(ctrl_.size()) != n[0] * n[1] * n[2])
    throw Error("control point array has " + std::to_string(ctrl_.size()) + " entries, expected " +
                std::to_string(n[0] * n[1] * n[2]));
}

Degree3 TensorBSpline::degrees() const {
  return {knots_[0].degree(), knots_[1].degree(), knots_[2].degree()};
}

Index3 TensorBSpline::counts() const {
  return {knots_[0].controlCount(), knots_[1].controlCount(), knots_[2].controlCount()};
}

SplineView TensorBSpline::view() const {
  SplineView v;
  v.ctrl = ctrl_.data();
  for (int a = 0; a < 3; ++a) v.axis[a] = knots_[a].view();
  return v;
}

std::shared_ptr<const SpanRanges> TensorBSpline::spanRanges() const {
  if (!derived_) throw Error("internal: span ranges of an empty spline");
  std::call_once(derived_->once, [&] {
    derived_->ranges = std::make_shared<const SpanRanges>(SpanRanges::compute(view()));
  });
  return derived_->ranges;
}

float TensorBSpline::value(const Vec3d& u) const {
  const SplineView v = view();
  const double x[3] = {u[0], u[1], u[2]};
  return splineDegreeSwitch(v, [&]<int P>() { return splineValue<P>(v, x); });
}

ValueGradient TensorBSpline::valueGradient(const Vec3d& u) const {
  const SplineView v = view();
  const double x[3] = {u[0], u[1], u[2]};
  float out[4];
  splineDegreeSwitch(v, [&]<int P>() { splineValueGradient<P>(v, x, out); });
  return {out[0], Vec3f(out[1], out[2], out[3])};
}

ValueGradientHessian TensorBSpline::valueGradientHessian(const Vec3d& u) const {
  const SplineView v = view();
  const double x[3] = {u[0], u[1], u[2]};
  float out[10];
  splineDegreeSwitch(v, [&]<int P>() { splineValueGradientHessian<P>(v, x, out); });
  ValueGradientHessian r;
  r.value = out[0];
  r.gradient = Vec3f(out[1], out[2], out[3]);
  for (int i = 0; i < 6; ++i) r.hessian[i] = out[4 + i];
  return r;
}

TensorBSpline TensorBSpline::withInsertedKnot(int axis, double u) const {
  if (axis < 0 || axis > 2) throw Error("axis must be 0, 1 or 2");
  const KnotVector& kv = knots_[axis];
  const std::vector<double>& U = kv.knots();
  const int p = kv.degree();
  const int k = kv.findSpan(u);
  const int mult = static_cast<int>(std::count(U.begin(), U.end(), u));
  if (mult >= p) throw Error("knot multiplicity would exceed the degree");

  const Index3 n = counts();
  Index3 m = n;
  m[axis] += 1;
  // alpha[i] for the control points that blend; indices k-p+1 .. k-mult.
  std::vector<double> alpha(static_cast<size_t>(n[axis] + 1), 0.0);
  for (int i = k - p + 1; i <= k - mult; ++i) alpha[i] = (u - U[i]) / (U[i + p] - U[i]);

  const std::int64_t strideIn[3] = {1, n[0], n[0] * n[1]};
  const std::int64_t strideOut[3] = {1, m[0], m[0] * m[1]};
  std::vector<float> out(static_cast<size_t>(m[0] * m[1] * m[2]));
  // Iterate over all lines parallel to `axis`.
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  for (std::int64_t y = 0; y < n[a2]; ++y) {
    for (std::int64_t x = 0; x < n[a1]; ++x) {
      const float* in = ctrl_.data() + x * strideIn[a1] + y * strideIn[a2];
      float* o = out.data() + x * strideOut[a1] + y * strideOut[a2];
      const std::int64_t si = strideIn[axis], so = strideOut[axis];
      for (std::int64_t i = 0; i <= m[axis] - 1; ++i) {
        double q;
        if (i <= k - p)
          q = in[i * si];
        else if (i >= k - mult + 1)
          q = in[(i - 1) * si];
        else
          q = alpha[i] * in[i * si] + (1.0 - alpha[i]) * in[(i - 1) * si];
        o[i * so] = static_cast<float>(q);
      }
    }
  }
  std::array<KnotVector, 3> knots = knots_;
  knots[axis] = kv.withInsertedKnot(u);
  return TensorBSpline(std::move(knots), std::move(out));
}

}  // namespace mfadvr
