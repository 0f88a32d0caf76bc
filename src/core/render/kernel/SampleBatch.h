#pragma once
// Batches of samples for the ray integration (RayIntegrator.h): a ray's next few sample points
// are staged into lanes, evaluated together, then classified and composited in ray order.
//
// On the host a batch lets the processor overlap the evaluations of neighbouring samples, whose
// dependency chains (span lookup, basis, contraction, table lookup) are longer than its
// instruction window holds for one sample at a time. On a GPU each thread already is one of
// many in flight, and per-lane arrays would only cost registers: batches there have one lane.
#include "core/util/HostDevice.h"

namespace mfadvr {

#if defined(__CUDACC__)
inline constexpr int kSampleBatch = 1;
#else
inline constexpr int kSampleBatch = 8;
#endif

// The batch interface for samplers that evaluate one point at a time. Derived provides
//   float pointValue(const double p[3])
//   float pointValueGradient(const double p[3], float g[3])   (shaded renders)
//   double differenceStep(int axis) const     (curvature renders: hessian's step, world units)
// and inherits stage / evaluate / gradient / hessian, which keep each lane's point and gradient.
template <class Derived, int K, bool Shade>
class PointwiseBatch {
 public:
  static constexpr int kBatch = K;

  MFADVR_HD MFADVR_INLINE void stage(int lane, const double p[3]) {
    for (int a = 0; a < 3; ++a) points_[lane][a] = p[a];
  }

  MFADVR_HD MFADVR_INLINE void evaluate(int n, float v[]) {
    Derived& self = static_cast<Derived&>(*this);
    for (int i = 0; i < n; ++i) {
      if constexpr (Shade)
        v[i] = self.pointValueGradient(points_[i], gradients_[i]);
      else
        v[i] = self.pointValue(points_[i]);
    }
  }

  MFADVR_HD MFADVR_INLINE void gradient(int lane, float g[3]) const {
    for (int a = 0; a < 3; ++a) g[a] = gradients_[lane][a];
  }

  // The Hessian at p (xx, xy, xz, yy, yz, zz): central differences of the sampler's own
  // gradient at p +- Derived::differenceStep(axis) along each axis, symmetrized: the filter's own
  // second derivatives where its gradient is smooth around p (for a polynomial cell, within
  // step^2 / 6 of the gradient's third derivative).
  MFADVR_HD MFADVR_INLINE void hessian(int, const double p[3], float h[6]) {
    Derived& self = static_cast<Derived&>(*this);
    double dg[3][3];  // dg[b][a]: d g_a / d x_b
    for (int b = 0; b < 3; ++b) {
      const double step = self.differenceStep(b);
      double q[3] = {p[0], p[1], p[2]};
      float up[3], down[3];
      q[b] = p[b] + step;
      self.pointValueGradient(q, up);
      q[b] = p[b] - step;
      self.pointValueGradient(q, down);
      for (int a = 0; a < 3; ++a) dg[b][a] = (double(up[a]) - double(down[a])) / (2.0 * step);
    }
    h[0] = static_cast<float>(dg[0][0]);
    h[1] = static_cast<float>(0.5 * (dg[1][0] + dg[0][1]));
    h[2] = static_cast<float>(0.5 * (dg[2][0] + dg[0][2]));
    h[3] = static_cast<float>(dg[1][1]);
    h[4] = static_cast<float>(0.5 * (dg[2][1] + dg[1][2]));
    h[5] = static_cast<float>(dg[2][2]);
  }

 private:
  double points_[K][3];
  float gradients_[Shade ? K : 1][3];
};

}  // namespace mfadvr
