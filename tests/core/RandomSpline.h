#pragma once
// Test support: a tensor B-spline on clamped uniform knots with control points drawn uniformly
// from [-1, 1], reproducible from its seed.
#include <random>
#include <vector>

#include "core/spline/TensorBSpline.h"

namespace mfadvr {

inline TensorBSpline randomSpline(Degree3 p, Index3 n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
  std::vector<float> ctrl(static_cast<size_t>(n[0] * n[1] * n[2]));
  for (float& c : ctrl) c = uni(rng);
  return TensorBSpline({KnotVector::clampedUniform(p[0], static_cast<int>(n[0])),
                        KnotVector::clampedUniform(p[1], static_cast<int>(n[1])),
                        KnotVector::clampedUniform(p[2], static_cast<int>(n[2]))},
                       std::move(ctrl));
}

}  // namespace mfadvr
