#pragma once
// The range of a tensor B-spline over each knot-span cell, from the B-spline convex-hull
// property: inside the cell of spans (s0, s1, s2) the spline is a convex combination of the
// (p+1)^3 control points P(s0-p0.., s1-p1.., s2-p2..), so it lies between their minimum and
// maximum. Empty-space skipping classifies cells by these bounds (render/EmptySpaceGrid.h).
//
// The per-cell bounds are not kept: SpanRangeScanner computes them a plane of cells at a time
// from p+1 planes of control points, for the flags' build to classify and drop. Keeping them
// would cost a renderer 4 to 8 bytes per cell, as much as the model itself, to save a
// transfer-function edit the scan (docs/benchmarks.md, "Large volumes"). SpanRanges holds what
// is kept: the whole spline's range and the kernel's rounding bound.
#include <cstdint>
#include <vector>

#include "core/spline/SplineView.h"

namespace mfadvr {

struct SpanRanges {
  int cells[3] = {0, 0, 0};  // count - degree per axis; cell (c0, c1, c2) is spans (c + p)
  // The least and the greatest control point: the spline's range over the whole domain (NaN
  // control points make them NaN).
  float lowest = 0.0f, highest = 0.0f;
  // Bound on the relative error of the evaluation kernel's float arithmetic: a computed value
  // in a cell lies within [lo - r M, hi + r M], M = max(|lo|, |hi|) of that cell's bounds.
  double relativeRounding = 0.0;

  std::int64_t cellCount() const { return std::int64_t(cells[0]) * cells[1] * cells[2]; }

  // One pass over the control points.
  static SpanRanges compute(const SplineView& spline);
};

// The bounds of every cell of a plane z of cells, planes taken in increasing z: the control
// planes are slid along x and y (separable sliding-window minimum and maximum, (p+1)
// comparisons per control point and axis) into a ring of p+1 planes, which each cell plane
// then slides along z. One scanner per task; a task that starts at plane z0 reads control
// planes from z0 on.
class SpanRangeScanner {
 public:
  explicit SpanRangeScanner(const SplineView& spline);

  // lo[q] <= every control point of cell (q % X, q / X, z) <= hi[q], x fastest over the plane's
  // X * Y cells. A cell with a control point that is not finite gets lo = -inf and hi = +inf.
  void plane(std::int64_t z, float* lo, float* hi);

 private:
  void addControlPlane(std::int64_t k);

  SplineView v_;
  std::int64_t n_[3], cells_[3];
  int w_[3];
  std::int64_t next_ = -1;  // the next control plane to enter the ring (-1: none yet)
  std::vector<float> rowLo_, rowHi_, lx_, hx_, ringLo_, ringHi_;
};

}  // namespace mfadvr
