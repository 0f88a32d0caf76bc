#pragma once
// VTK's opacity correction for a step of length dt: a' = 1 - (1 - a)^(dt / unit distance),
// exponent = dt / unit distance (host and device).
#include <cmath>

#include "core/util/HostDevice.h"

namespace mfadvr {

MFADVR_HD MFADVR_INLINE float correctOpacity(float a, double exponent) {
  if (!(a > 0.0f)) return 0.0f;
  if (a >= 1.0f) return 1.0f;
  return static_cast<float>(1.0 - pow(1.0 - double(a), exponent));
}

}  // namespace mfadvr
