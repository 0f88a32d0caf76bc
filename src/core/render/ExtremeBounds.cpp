#include "core/render/ExtremeBounds.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/render/EmptySpaceGrid.h"  // skippingRange, skippingMargin
#include "core/spline/BezierRangeScanner.h"

namespace mfadvr {

void ExtremeBounds::attachTo(ModelView& view) const {
  if (upper.empty()) return;
  view.extremeUpper = upper.data();
  view.extremeLower = lower.data();
  view.extremeUpperPyramid = upperPyramid.bytes.data();
  view.extremeLowerPyramid = lowerPyramid.bytes.data();
  view.extremeUpperLevels = upperLevels.data();
  view.extremeLowerLevels = lowerLevels.data();
  view.extremeLevels = upperPyramid.levels;
  for (int l = 0; l < upperPyramid.levels; ++l) view.extremeLevel[l] = upperPyramid.level[l];
}

ExtremeBounds buildExtremeBounds(const SplineView& spline, const SpanRanges& r, bool bezierRanges) {
  ExtremeBounds out;
  const std::int64_t n = r.cellCount();
  // Every cell's widened range lies within the whole spline's, widened by at least as much.
  const float wholePad = skippingMargin(r, r.lowest, r.highest);
  const float lo = r.lowest - wholePad, hi = r.highest + wholePad;
  // A spline with a value that is not finite: no bounds, nothing is skipped.
  if (n <= 0 || !(std::isfinite(lo) && std::isfinite(hi))) return out;
  // The levels: kExtremeLevels - 1 steps over [lo, hi] and one infinite level at the far end,
  // which stands for "no bound".
  constexpr int L = kExtremeLevels;
  out.upperLevels.resize(L);
  out.lowerLevels.resize(L);
  for (int i = 0; i < L - 1; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(L - 2);
    const float v = i == L - 2 ? hi : std::max(lo, std::min(hi, lo + t * (hi - lo)));
    out.upperLevels[i] = i > 0 ? std::max(v, out.upperLevels[i - 1]) : lo;
  }
  out.upperLevels[L - 1] = INFINITY;
  out.lowerLevels[0] = -INFINITY;
  for (int i = 1; i < L; ++i) out.lowerLevels[i] = out.upperLevels[i - 1];
  out.upper.resize(static_cast<size_t>(n));
  out.lower.resize(static_cast<size_t>(n));

  const std::int64_t plane = std::int64_t(r.cells[0]) * r.cells[1], Z = r.cells[2];
  const std::int64_t slab = std::max<std::int64_t>(16, (Z + 15) / 16);
  tbb::enumerable_thread_specific<CellRangeScanners> perThread(
      [&] { return CellRangeScanners(spline, plane); });
  const double bezierRounding = perThread.local().bezier.relativeRounding();
  const float* upperLevels = out.upperLevels.data();
  const float* lowerLevels = out.lowerLevels.data();
  tbb::parallel_for(std::int64_t(0), (Z + slab - 1) / slab, [&](std::int64_t task) {
    CellRangeScanners& t = perThread.local();
    for (std::int64_t z = task * slab; z < std::min(Z, (task + 1) * slab); ++z) {
      t.scan.plane(z, t.lo.data(), t.hi.data());
      if (bezierRanges) t.bezier.plane(z, t.bezierLo.data(), t.bezierHi.data());
      std::uint8_t* up = out.upper.data() + z * plane;
      std::uint8_t* down = out.lower.data() + z * plane;
      for (std::int64_t q = 0; q < plane; ++q) {
        const size_t i = static_cast<size_t>(q);
        float l, h;
        // Without Bezier ranges, NaN ones: skippingRange keeps the control points' range.
        const bool finite =
            skippingRange(r, bezierRounding, t.lo[i], t.hi[i], bezierRanges ? t.bezierLo[i] : NAN,
                          bezierRanges ? t.bezierHi[i] : NAN, l, h);
        if (!finite) {
          up[q] = L - 1;
          down[q] = 0;
          continue;
        }
        // The first level at or above h; the last at or below l.
        up[q] = static_cast<std::uint8_t>(std::lower_bound(upperLevels, upperLevels + L, h) -
                                          upperLevels);
        down[q] = static_cast<std::uint8_t>(std::upper_bound(lowerLevels, lowerLevels + L, l) -
                                            lowerLevels - 1);
      }
    }
  });
  out.upperPyramid = buildCellPyramid(r.cells, out.upper.data(), /*greatest=*/true);
  out.lowerPyramid = buildCellPyramid(r.cells, out.lower.data(), /*greatest=*/false);
  return out;
}

}  // namespace mfadvr
