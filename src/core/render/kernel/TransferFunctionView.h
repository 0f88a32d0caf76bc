#pragma once
// The transfer-function table as a plain view (host and device): colour, opacity and
// step-corrected opacity at evenly spaced values, read back with linear interpolation
// (TransferFunctionTable owns the entries and explains the sampling).
#include "core/util/HostDevice.h"

namespace mfadvr {

// Padded to 8 floats and aligned to them: an entry is one aligned 32-byte block. Per MFA sample
// this was 1.14x faster than 20-byte entries; spelling the interpolation out as 8-float vectors
// gained at most 2% more, so host and device share the per-channel formula below.
struct alignas(32) TfEntry {
  float r, g, b;
  float alpha;      // opacity per unit distance, from the TF
  float alphaStep;  // opacity of a full step (corrected for the sample distance)
  float unused[3];
};
static_assert(sizeof(TfEntry) == 8 * sizeof(float));

// Between two entries' values (or, on the host, vectors of them: ray packets): weight t of b.
template <class F>
MFADVR_HD MFADVR_INLINE F interpolate(F a, F b, float t) {
  return a + t * (b - a);
}

struct TransferFunctionView {
  const TfEntry* entries = nullptr;
  int count = 0;                  // >= 2
  float lo = 0.0f, scale = 0.0f;  // entry index = (value - lo) * scale

  // Where `value` falls: entry i and the weight t of entry i+1. False for NaN (transparent).
  // Values below and above the table take its end entries. Monotone in value, so that the
  // entries a value range touches are those between its ends' (EmptySpaceGrid relies on it).
  MFADVR_HD MFADVR_INLINE bool locate(float value, int& i, float& t) const {
    if (value != value) return false;  // NaN
    position(value, i, t);
    return true;
  }

  // The same for a float or, on the host, a vector of floats (F) with integers I to match
  // (ray packets); NaN takes entry 0.
  template <class F, class I>
  MFADVR_HD MFADVR_INLINE void position(F value, I& i, F& t) const {
    F x = (value - lo) * scale;
    x = x > 0.0f ? x : 0.0f;  // also NaN
    const float last = static_cast<float>(count - 1);
    x = x > last ? last : x;
    i = convertLanes<I>(x);
    i = i > count - 2 ? count - 2 : i;
    t = x - convertLanes<F>(i);
  }

  MFADVR_HD MFADVR_INLINE TfEntry classify(float value) const {
    int i;
    float t;
    if (!locate(value, i, t)) return {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, {}};
    const TfEntry& a = entries[i];
    const TfEntry& b = entries[i + 1];
    return {interpolate(a.r, b.r, t),
            interpolate(a.g, b.g, t),
            interpolate(a.b, b.b, t),
            interpolate(a.alpha, b.alpha, t),
            interpolate(a.alphaStep, b.alphaStep, t),
            {}};
  }
};

}  // namespace mfadvr
