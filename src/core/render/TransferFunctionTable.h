#pragma once
// The transfer function sampled once per render, as VTK's ray casters do: colour, opacity and
// step-corrected opacity at 4096 evenly spaced values over the span of the TF's points, read
// back with linear interpolation. Evaluating the piecewise-linear maps and the opacity correction
// directly cost about a third of a trilinear render.
//
// Between its points a transfer function is linear, so the table reproduces it up to rounding
// except within one entry of a point that does not fall on an entry (there the error is at most
// the slope change times 1/4095 of the span); a jump (a step at an isovalue) becomes a ramp one
// entry wide. Outside the span the end values hold, as in the TF itself. NaN maps to transparent.
#include <cmath>
#include <vector>

#include "core/render/OpacityCorrection.h"
#include "core/render/TransferFunction.h"

namespace mfadvr {

struct Classification {
  Vec3f rgb;
  float alpha;      // opacity per unit distance, from the TF
  float alphaStep;  // opacity of a full step (corrected for the sample distance)
};

class TransferFunctionTable {
 public:
  static constexpr int kEntries = 4096;

  // tf must be resolved to data values.
  TransferFunctionTable(const TransferFunction& tf, const OpacityCorrection& correction);

  [[gnu::always_inline]] inline Classification classify(float value) const {
    float x = (value - lo_) * scale_;
    if (!(x > 0.0f)) x = std::isnan(value) ? -1.0f : 0.0f;
    if (x < 0.0f) return {Vec3f::Zero(), 0.0f, 0.0f};
    if (x > float(kEntries - 1)) x = float(kEntries - 1);
    int i = static_cast<int>(x);
    if (i > kEntries - 2) i = kEntries - 2;
    const float t = x - static_cast<float>(i);
    const Entry& a = entries_[i];
    const Entry& b = entries_[i + 1];
    return {Vec3f(a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b)),
            a.alpha + t * (b.alpha - a.alpha), a.alphaStep + t * (b.alphaStep - a.alphaStep)};
  }

 private:
  struct Entry {
    float r, g, b, alpha, alphaStep;
  };
  float lo_ = 0.0f, scale_ = 0.0f;
  std::vector<Entry> entries_;
};

}  // namespace mfadvr
