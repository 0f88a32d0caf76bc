#pragma once
// The levels of the extreme bounds (ExtremeBounds.h) as a ray reads them, host and device: a
// byte per bound is the index of one of kExtremeLevels ascending levels, and a maximum or
// minimum intensity ray turns its running extreme into the byte a cell's bound must pass.
#include "core/util/HostDevice.h"

namespace mfadvr {

// The levels of ModelView's extreme bounds (one byte each).
inline constexpr int kExtremeLevels = 256;

// A maximum intensity ray whose largest value so far is v passes over every cell whose upper byte
// is at most the last level at or below v: -1 when there is none.
MFADVR_HD MFADVR_INLINE int upperByteAtMost(const float* levels, float v) {
  int lo = -1, hi = kExtremeLevels - 1;  // levels[lo] <= v (or lo = -1), levels[hi + 1] > v
  if (!(levels[hi] > v)) return hi;
  --hi;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (levels[mid] <= v)
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

// A minimum intensity ray whose least value so far is v passes over every cell whose lower byte
// is at least the first level at or above v: kExtremeLevels when there is none.
MFADVR_HD MFADVR_INLINE int lowerByteAtLeast(const float* levels, float v) {
  int lo = 0, hi = kExtremeLevels;  // levels[hi] >= v (or hi = kExtremeLevels), levels[lo - 1] < v
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (levels[mid] >= v)
      hi = mid;
    else
      lo = mid + 1;
  }
  return hi;
}

}  // namespace mfadvr
