#pragma once
// Exact skipping for maximum and minimum intensity projection: per knot-span cell, an upper and a
// lower bound of every value the spline can take there, coded as one byte each.
//
// A maximum intensity ray need not evaluate a cell whose values cannot exceed the largest value
// it has seen (nor a value that the transfer function makes transparent: such a maximum leaves
// the pixel empty whatever it is); a minimum intensity ray, one whose values cannot go below its
// least. The bounds are those of empty-space skipping (EmptySpaceGrid.h: the control points'
// range narrowed to the Bezier coefficients' and widened by the rounding bounds), so a skipped
// sample would not have changed the ray's extreme and the image is bit-identical to one that
// samples every step.
//
// A byte b stands for a level of a fixed ascending table over the spline's range: a cell's upper
// byte is the first level at or above its upper bound (255: +inf, a cell with a control point
// that is not finite), its lower byte the last level at or below its lower bound (0: -inf). A ray
// turns its running extreme into a byte once (upperLevelAtMost / lowerLevelAtLeast) and compares
// bytes; pyramids of the greatest upper and the least lower byte per aligned block of 2^l cells
// (CellPyramid.h) let it leave a large region in one jump. Two bytes per cell, unlike the per-cell
// float ranges that empty-space skipping does not keep (SpanRanges.h): a quarter of a
// float per control point twice. They do not depend on the transfer function, so a cache keeps
// them for as long as the model (EmptySpaceCache::extremeBounds).
#include <cstdint>
#include <vector>

#include "core/render/CellPyramid.h"
#include "core/render/kernel/SplineRaySampler.h"
#include "core/spline/SpanRanges.h"

namespace mfadvr {

struct ExtremeBounds {
  std::vector<float> upperLevels, lowerLevels;  // kExtremeLevels each, ascending
  std::vector<std::uint8_t> upper, lower;       // per cell, x fastest over SpanRanges::cells
  CellPyramid upperPyramid, lowerPyramid;

  // Points `view`'s maximum and minimum intensity skipping at these bounds (which must outlive
  // its use).
  void attachTo(ModelView& view) const;
};

// From the control points' and (with bezierRanges) the Bezier coefficients' range of each cell.
ExtremeBounds buildExtremeBounds(const SplineView& spline, const SpanRanges& ranges,
                                 bool bezierRanges = true);

}  // namespace mfadvr
