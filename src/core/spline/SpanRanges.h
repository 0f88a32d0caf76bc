#pragma once
// The range of a tensor B-spline over each knot-span cell, from the B-spline convex-hull
// property: inside the cell of spans (s0, s1, s2) the spline is a convex combination of the
// (p+1)^3 control points P(s0-p0.., s1-p1.., s2-p2..), so it lies between their minimum and
// maximum. Empty-space skipping reads these bounds (render/EmptySpaceGrid.h).
//
// A renderer holds them for every cell of the model, as many as its control points: they are
// kept as 16-bit levels of the model's whole range, rounded outwards (the lower bound down, the
// upper up), 4 bytes a cell instead of 8. Bounds that are a little wider still hold every value
// of the cell, so skipping stays exact; they are 1/65535 of the range wider at most, 16 times
// finer than the transfer-function table (TransferFunctionTable::kEntries).
#include <cstdint>
#include <vector>

#include "core/spline/SplineView.h"

namespace mfadvr {

struct SpanRanges {
  static constexpr int kTop = 65535;  // the highest level

  int cells[3] = {0, 0, 0};  // count - degree per axis; cell (c0, c1, c2) is spans (c + p)
  // Per cell, x fastest: the levels of its bounds (lowerBound / upperBound); a cell with a
  // control point that is not finite has low kTop and high 0: no bounds.
  std::vector<std::uint16_t> low, high;
  // The least and the greatest control point: the spline's range over the whole domain (NaN
  // control points make them NaN).
  float lowest = 0.0f, highest = 0.0f;
  // Bound on the relative error of the evaluation kernel's float arithmetic: a computed value
  // in a cell lies within [lo - r M, hi + r M], M = max(|lo|, |hi|) of that cell's bounds.
  double relativeRounding = 0.0;

  std::int64_t cellCount() const { return static_cast<std::int64_t>(low.size()); }
  // False for a cell without bounds; else lo <= every control point of the cell <= hi.
  bool bounds(std::int64_t cell, float& lo, float& hi) const {
    if (low[static_cast<size_t>(cell)] > high[static_cast<size_t>(cell)]) return false;
    lo = level(low[static_cast<size_t>(cell)]);
    hi = level(high[static_cast<size_t>(cell)]);
    return true;
  }
  // The value of level q: levelBase at 0, levelTop at kTop.
  float level(int q) const {
    return q == kTop ? levelTop : static_cast<float>(levelBase + q * levelStep);
  }

  // Separable sliding-window minimum and maximum: (p+1) comparisons per control point and
  // axis, a slab of cells at a time (the working set is (p+1) planes of control points per
  // task, not the whole grid in floats).
  static SpanRanges compute(const SplineView& spline);

  // The levels' scale: the finite control points' range.
  float levelBase = 0.0f, levelTop = 0.0f;
  double levelStep = 0.0;
};

}  // namespace mfadvr
