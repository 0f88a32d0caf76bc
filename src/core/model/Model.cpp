#include "core/model/Model.h"

#include <tbb/parallel_for.h>
#include <algorithm>

#include "core/spline/SplineKernel.h"
#include "core/util/Error.h"

namespace mfadvr {

Model::Model(TensorBSpline spline, DomainBox domain, double valueMin, double valueMax,
             Provenance provenance)
    : spline_(std::move(spline)),
      domain_(domain),
      valueMin_(valueMin),
      valueMax_(valueMax),
      provenance_(std::move(provenance)) {
  const Vec3d e = domain_.extent();
  if (!((e.array() > 0.0).all() && e.allFinite()))
    throw Error("model domain box must have positive, finite extent on every axis");
  invExtent_ = e.cwiseInverse().cast<float>();
}

ValueGradient Model::valueGradient(const Vec3d& x) const {
  ValueGradient r = spline_.valueGradient(domain_.toParameter(x));
  r.gradient = r.gradient.cwiseProduct(invExtent_);
  return r;
}

ValueGradientHessian Model::valueGradientHessian(const Vec3d& x) const {
  ValueGradientHessian r = spline_.valueGradientHessian(domain_.toParameter(x));
  r.gradient = r.gradient.cwiseProduct(invExtent_);
  const Vec3f s = invExtent_;
  const float scale[6] = {s[0] * s[0], s[0] * s[1], s[0] * s[2],
                          s[1] * s[1], s[1] * s[2], s[2] * s[2]};
  for (int i = 0; i < 6; ++i) r.hessian[i] *= scale[i];
  return r;
}

void Model::evaluate(std::span<const Vec3d> points, std::span<float> values,
                     std::span<Vec3f> gradients, std::span<Sym3f> hessians) const {
  const size_t n = points.size();
  if (values.size() != n || (!gradients.empty() && gradients.size() != n) ||
      (!hessians.empty() && hessians.size() != n))
    throw Error("batched query: output sizes do not match the number of points");
  if (!hessians.empty()) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const auto& range) {
      for (size_t i = range.begin(); i < range.end(); ++i) {
        const ValueGradientHessian r = valueGradientHessian(points[i]);
        values[i] = r.value;
        if (!gradients.empty()) gradients[i] = r.gradient;
        hessians[i] = r.hessian;
      }
    });
    return;
  }
  // The value and gradient paths pick the degree once for the whole batch.
  const SplineView v = spline_.view();
  const Vec3d lo = domain_.min;
  const Vec3d inv = domain_.extent().cwiseInverse();
  splineDegreeSwitch(v, [&]<int P>() {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const auto& range) {
      for (size_t i = range.begin(); i < range.end(); ++i) {
        const Vec3d& x = points[i];
        const double u[3] = {(x[0] - lo[0]) * inv[0], (x[1] - lo[1]) * inv[1],
                             (x[2] - lo[2]) * inv[2]};
        if (gradients.empty()) {
          values[i] = splineValue<P>(v, u);
        } else {
          float out[4];
          splineValueGradient<P>(v, u, out);
          values[i] = out[0];
          gradients[i] =
              Vec3f(out[1] * invExtent_[0], out[2] * invExtent_[1], out[3] * invExtent_[2]);
        }
      }
    });
  });
}

Vec3d Model::dataSpacing() const {
  const Index3 counts = spline_.counts();
  Vec3d spacing;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t n = provenance_.sampleDims[a] > 1 ? provenance_.sampleDims[a]
                                                         : std::max(counts[a], mask_.dims()[a]);
    spacing[a] = domain_.extent()[a] / double(std::max<std::int64_t>(n - 1, 1));
  }
  return spacing;
}

}  // namespace mfadvr
