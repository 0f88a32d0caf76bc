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
// and inherits stage / evaluate / gradient, which keep each lane's point and gradient.
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

 private:
  double points_[K][3];
  float gradients_[Shade ? K : 1][3];
};

}  // namespace mfadvr
