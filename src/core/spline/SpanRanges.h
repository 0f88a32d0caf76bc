#pragma once
// The range of a tensor B-spline over each knot-span cell, from the B-spline convex-hull
// property: inside the cell of spans (s0, s1, s2) the spline is a convex combination of the
// (p+1)^3 control points P(s0-p0.., s1-p1.., s2-p2..), so it lies between their minimum and
// maximum. Empty-space skipping reads these bounds (render/EmptySpaceGrid.h).
#include <cstdint>
#include <vector>

#include "core/spline/SplineView.h"

namespace mfadvr {

struct SpanRanges {
  int cells[3] = {0, 0, 0};     // count - degree per axis; cell (c0, c1, c2) is spans (c + p)
  std::vector<float> min, max;  // x fastest
  // The least of `min` and the greatest of `max`: the spline's range over the whole domain
  // (NaN control points make them NaN).
  float lowest = 0.0f, highest = 0.0f;
  // Bound on the relative error of the evaluation kernel's float arithmetic: a computed value
  // in a cell lies within [min - r M, max + r M], M = max(|min|, |max|) of that cell.
  double relativeRounding = 0.0;

  // Separable sliding-window minimum and maximum: (p+1) comparisons per control point and axis.
  static SpanRanges compute(const SplineView& spline);
};

}  // namespace mfadvr
