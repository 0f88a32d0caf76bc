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
#include <algorithm>
#include <vector>

#include "core/render/OpacityCorrection.h"
#include "core/render/TransferFunction.h"
#include "core/render/TransferFunction2D.h"
#include "core/render/kernel/TransferFunctionView.h"

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

  // The envelope of a 2-D transfer function over its gradient axis, on its value axis: each
  // entry's opacity is the greatest of the 2-D table's columns that values interpolating from
  // the entry read, so a value this table makes transparent is transparent at every |grad f|
  // (the 2-D table is then the one that classifies; GradientTransferView.h). Colours: white.
  TransferFunctionTable(const TransferFunction2D& tf, const OpacityCorrection& correction);

  // The plain view the ray integration reads; valid while this table lives.
  TransferFunctionView view() const { return {entries_.data(), kEntries, lo_, scale_}; }

  Classification classify(float value) const {
    const TfEntry e = view().classify(value);
    return {Vec3f(e.r, e.g, e.b), e.alpha, e.alphaStep};
  }

  // True when every value in [lo, hi] classifies to opacity exactly 0 (empty-space skipping):
  // the entries such values interpolate between are all transparent. O(1).
  bool transparentOver(float lo, float hi) const;
  // True when some value in [lo, hi] may classify to opacity exactly 0: [lo, hi] touches a
  // transparent entry (NaN ends: true). O(1).
  bool mayBeTransparentOver(float lo, float hi) const;
  // The greatest value v such that every value at or below it classifies to opacity exactly 0
  // (-inf: none; +inf: every value), and the least value such that every value at or above it
  // does (+inf: none; -inf: every value). Maximum and minimum intensity skipping start there.
  float transparentUpTo() const;
  float transparentFrom() const;
  // Both at once: every value of [lo, hi] transparent, some may be, or none is. Inline: the
  // empty-space flags' build asks it once per cell.
  enum class RangeOpacity { Transparent, Mixed, Visible };
  RangeOpacity rangeOpacity(float lo, float hi) const {
    int first, last;
    if (!touchedEntries(lo, hi, first, last)) return RangeOpacity::Mixed;
    const int visible = visibleBefore_[last + 1] - visibleBefore_[first];
    return visible == 0                 ? RangeOpacity::Transparent
           : visible < last + 1 - first ? RangeOpacity::Mixed
                                        : RangeOpacity::Visible;
  }

 private:
  // The entries first .. last that values in [lo, hi] interpolate between; false for a NaN end.
  bool touchedEntries(float lo, float hi, int& first, int& last) const {
    const TransferFunctionView v = view();
    int i1;
    float t;
    // locate() is monotone in the value, so [lo, hi] touches entries first .. i1 + 1 only.
    if (!v.locate(lo, first, t) || !v.locate(hi, i1, t)) return false;
    last = std::min(i1 + 1, kEntries - 1);
    return true;
  }

  void countVisible();

  float lo_ = 0.0f, scale_ = 0.0f;
  std::vector<TfEntry> entries_;
  std::vector<int> visibleBefore_;  // [i]: entries before i with non-zero opacity
};

}  // namespace mfadvr
