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

struct TransferFunctionView {
  const TfEntry* entries = nullptr;
  int count = 0;                  // >= 2
  float lo = 0.0f, scale = 0.0f;  // entry index = (value - lo) * scale

  // Where `value` falls: entry i and the weight t of entry i+1. False for NaN (transparent).
  // Values below and above the table take its end entries. Monotone in value, so that the
  // entries a value range touches are those between its ends' (EmptySpaceGrid relies on it).
  MFADVR_HD MFADVR_INLINE bool locate(float value, int& i, float& t) const {
    float x = (value - lo) * scale;
    if (!(x > 0.0f)) {
      if (value != value) return false;  // NaN
      x = 0.0f;
    }
    const float last = static_cast<float>(count - 1);
    if (x > last) x = last;
    i = static_cast<int>(x);
    if (i > count - 2) i = count - 2;
    t = x - static_cast<float>(i);
    return true;
  }

  MFADVR_HD MFADVR_INLINE TfEntry classify(float value) const {
    int i;
    float t;
    if (!locate(value, i, t)) return {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, {}};
    const TfEntry& a = entries[i];
    const TfEntry& b = entries[i + 1];
    return {a.r + t * (b.r - a.r),
            a.g + t * (b.g - a.g),
            a.b + t * (b.b - a.b),
            a.alpha + t * (b.alpha - a.alpha),
            a.alphaStep + t * (b.alphaStep - a.alphaStep),
            {}};
  }
};

}  // namespace mfadvr
