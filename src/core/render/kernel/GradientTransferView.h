#pragma once
// Classification by the gradient magnitude |grad f| as well as the value (host and device):
// VTK's gradient opacity (the sample's step opacity times a function of |grad f|, as VTK's
// mappers apply it) and a 2-D transfer function over (value, |grad f|) that replaces the 1-D
// one's colour and opacity. |grad f| is the field's exact (or the filter's own) physical
// gradient, in data units per world unit. ClassificationTables.h builds the tables; the 1-D table
// of such a render is then the 2-D one's envelope over the gradient axis, so that the samples
// and cells it makes invisible stay invisible here (visibility and empty-space skipping).
#include <cmath>

#include "core/render/kernel/TransferFunctionView.h"

namespace mfadvr {

// Where x falls in a table of `count` (>= 2) evenly spaced entries: entry i and the weight t of
// entry i + 1; clamped to the ends (NaN: entry 0).
MFADVR_HD MFADVR_INLINE void tableCell(float x, float lo, float scale, int count, int& i,
                                       float& t) {
  float u = (x - lo) * scale;
  u = u > 0.0f ? u : 0.0f;
  const float last = static_cast<float>(count - 1);
  u = u > last ? last : u;
  i = static_cast<int>(u);
  i = i > count - 2 ? count - 2 : i;
  t = u - static_cast<float>(i);
}

struct GradientTransferView {
  // Gradient opacity: `opacityCount` factors at evenly spaced |grad f|, index (|g| - lo) * scale.
  const float* opacity = nullptr;
  int opacityCount = 0;
  float opacityLo = 0.0f, opacityScale = 0.0f;
  // 2-D transfer function: width x height entries, entry (i, j) at value index i and gradient
  // index j, row j at entries + j * width; alpha per unit distance and alphaStep as TfEntry's.
  const TfEntry* table = nullptr;
  int width = 0, height = 0;
  float valueLo = 0.0f, valueScale = 0.0f, gradientLo = 0.0f, gradientScale = 0.0f;

  MFADVR_HD MFADVR_INLINE bool active() const { return opacity != nullptr || table != nullptr; }

  // Reclassifies a visible sample (tf: its 1-D classification) from its physical gradient g;
  // factor: what its step opacity is multiplied by (the gradient opacity; 1 without one).
  MFADVR_HD MFADVR_INLINE void apply(float value, const float g[3], TfEntry& tf,
                                     float& factor) const {
    const float magnitude = sqrtf(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (table) {
      int i, j;
      float s, t;
      tableCell(value, valueLo, valueScale, width, i, s);
      tableCell(magnitude, gradientLo, gradientScale, height, j, t);
      const TfEntry* row0 = table + j * width;
      const TfEntry* row1 = row0 + width;
      auto bilinear = [&](float TfEntry::*channel) {
        return interpolate(interpolate(row0[i].*channel, row0[i + 1].*channel, s),
                           interpolate(row1[i].*channel, row1[i + 1].*channel, s), t);
      };
      tf = {bilinear(&TfEntry::r),     bilinear(&TfEntry::g),         bilinear(&TfEntry::b),
            bilinear(&TfEntry::alpha), bilinear(&TfEntry::alphaStep), {}};
    }
    factor = 1.0f;
    if (opacity) {
      int i;
      float t;
      tableCell(magnitude, opacityLo, opacityScale, opacityCount, i, t);
      factor = interpolate(opacity[i], opacity[i + 1], t);
    }
  }
};

}  // namespace mfadvr
