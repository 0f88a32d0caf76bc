#pragma once
// Exact empty-space skipping for MFA models: per knot-span cell, whether the transfer function
// makes every value the spline can take there transparent.
//
// A cell's values lie within its control points' range (SpanRangeScanner: the B-spline
// convex-hull property) and within the tighter range of its Bezier coefficients
// (BezierRangeScanner), widened by bounds on the float rounding of both. The table classifies a
// value by interpolating two neighbouring entries, and which entries a value touches is monotone in
// the value, so a range whose touched entries all have opacity 0 yields opacity exactly 0 for every
// sample in the cell: skipping such cells leaves the image bit-identical.
//
// The flags depend on the model and on which table entries are transparent; the cache rebuilds
// them only when either changes (a colour change or an opacity change that keeps the zero set
// keeps them), so an interactive session pays once per transfer-function edit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "core/model/ControlEnvelope.h"
#include "core/render/ExtremeBounds.h"
#include "core/render/TransferFunctionTable.h"
#include "core/render/kernel/SplineRaySampler.h"  // EmptyLevelView
#include "core/spline/BezierRangeScanner.h"
#include "core/spline/TensorBSpline.h"

namespace mfadvr {

// One flag per cell, x fastest over SpanRanges::cells (non-zero: skip; the value is 1 + the
// level of the largest all-empty block of the pyramid around the cell, which a ray leaves in one
// step; ModelView::empty), and a pyramid over them: level l (1..levels) has one flag per
// aligned block of 2^l cells per axis (clipped at the far faces), set when all of the block's
// cells are empty; its flags start at pyramid[level[l - 1].offset], x fastest over
// level[l - 1].count. Levels go up until one block covers the grid (at most kMaxEmptyLevels).
// When the transfer function leaves every value of the whole spline visible, no cell can be
// empty: emptyCells is 0 and no flags are made.
struct EmptySpaceFlags {
  std::vector<std::uint8_t> cells;
  std::vector<std::uint8_t> pyramid;
  int levels = 0;
  EmptyLevelView level[kMaxEmptyLevels];
  std::int64_t emptyCells = 0;

  // Points `view`'s skipping information at these flags (which must outlive its use).
  void attachTo(ModelView& view) const {
    view.empty = cells.data();
    view.emptyPyramid = pyramid.data();
    view.emptyLevels = levels;
    for (int l = 0; l < levels; ++l) view.emptyLevel[l] = level[l];
  }
};

// How far a range [lo, hi] of computed values is widened before the table is asked: twice the
// kernel's rounding bound (SpanRanges::relativeRounding), for safety. Equal control points of 0
// give exactly 0 and no margin.
inline float skippingMargin(const SpanRanges& r, float lo, float hi) {
  return static_cast<float>(r.relativeRounding) * std::max(std::abs(lo), std::abs(hi)) * 2.0f;
}

// The range of values a transfer function must make transparent for a cell to be skipped:
// the cell's control-point range [lo, hi] (SpanRangeScanner) narrowed to its Bezier range
// [bezierLo, bezierHi] (BezierRangeScanner, whose float error is at most bezierRounding times
// the largest |control point|), then widened by the kernel's rounding margin, which is
// relative to the control points since the kernel sums them. False when a control point of
// the cell is not finite: such a cell is never skipped.
inline bool skippingRange(const SpanRanges& r, double bezierRounding, float lo, float hi,
                          float bezierLo, float bezierHi, float& outLo, float& outHi) {
  if (!(std::isfinite(lo) && std::isfinite(hi))) return false;
  const float pad = skippingMargin(r, lo, hi);
  const float magnitude = std::max(std::abs(lo), std::abs(hi));
  float l = lo, h = hi;
  if (magnitude <= kBezierMagnitudeLimit) {
    // 2^-22 more covers the rounding of the subtraction and addition below.
    const float slack = static_cast<float>((bezierRounding + 0x1p-22) * magnitude);
    const float bl = bezierLo - slack, bh = bezierHi + slack;
    if (bl > l) l = bl;  // comparisons with NaN keep the control points' range
    if (bh < h) h = bh;
    if (!(l <= h)) l = lo, h = hi;
  }
  outLo = l - pad;
  outHi = h + pad;
  return true;
}

// One task's scanners of a build over the cells (the flags here, ExtremeBounds.h), with buffers
// for a plane of cells: made once per thread, not per slab of planes (their allocations, zeroing
// and first touches measured a third of the flags' build).
struct CellRangeScanners {
  SpanRangeScanner scan;
  BezierRangeScanner bezier;
  std::vector<float> lo, hi, bezierLo, bezierHi;
  CellRangeScanners(const SplineView& spline, std::int64_t planeCells)
      : scan(spline),
        bezier(spline),
        lo(static_cast<size_t>(planeCells)),
        hi(lo.size()),
        bezierLo(lo.size()),
        bezierHi(lo.size()) {}
};

// `ranges`: spline's (SpanRanges::compute). The cells' bounds are computed here, a slab of cells
// per task, and not kept. Without `bezierRanges` a cell is classified by its control points
// alone: fewer empty cells, a faster build (for flags that serve few samples per cell).
// With `upper`, `spline` and `upper` are the two ends of an envelope (ControlEnvelope.h): a
// cell's range is the least of `spline`'s control points to the greatest of `upper`'s, and
// `ranges` spans both (envelopeRanges); Bezier ranges do not apply then.
EmptySpaceFlags buildEmptySpaceFlags(const SplineView& spline, const SpanRanges& ranges,
                                     const TransferFunctionTable& table, bool bezierRanges = true,
                                     const SplineView* upper = nullptr);

// The ranges of an envelope: the lower end's, up to the upper end's highest control point.
SpanRanges envelopeRanges(const ControlEnvelope& envelope);

// Flags made for one render serve its samples once: below this many samples per cell (of the
// rays over the model, at the render's step), the Bezier ranges cost more than the samples
// they save, and the cells are classified by their control points only. Measured on streamed
// frames of 1024^3 and 2048^3 models (docs/benchmarks.md, "Bezier ranges").
inline constexpr double kBezierRangesMinSamplesPerCell = 3.0;

class EmptySpaceCache {
 public:
  // Flags for `spline` under `table`; the object stays valid as long as the pointer is held.
  // With `envelope` (an instant of a time-varying model: Model::controlEnvelope), an instant
  // asked for the first time gets the envelope's flags, which serve every instant (built once
  // per envelope and zero set: changing the time costs no build); asked again in a row (the time
  // stays), it gets its own, which skip more.
  std::shared_ptr<const EmptySpaceFlags> flags(const TensorBSpline& spline,
                                               const TransferFunctionTable& table,
                                               const ControlEnvelope* envelope = nullptr);
  // The extreme bounds of `spline` for maximum and minimum intensity skipping (ExtremeBounds.h):
  // built on the first call for a spline, then kept while it is the same.
  std::shared_ptr<const ExtremeBounds> extremeBounds(const TensorBSpline& spline);
  // The flags the last call of flags() returned, or null before the first call.
  std::shared_ptr<const EmptySpaceFlags> current() {
    std::lock_guard lock(mutex_);
    return current_;
  }

 private:
  std::mutex mutex_;
  std::shared_ptr<const void> spline_;  // flags_' spline (TensorBSpline::identity)
  std::vector<std::uint64_t> key_;      // the table's zero-opacity entries, lo and scale
  std::shared_ptr<const EmptySpaceFlags> flags_;
  // The spline of the previous flags() call; an instant seen first is not worth its span ranges.
  std::shared_ptr<const void> lastSpline_;
  std::shared_ptr<const void> envelopeSpline_;  // the envelope's lower end's identity
  std::vector<std::uint64_t> envelopeKey_;
  std::shared_ptr<const EmptySpaceFlags> envelopeFlags_;
  std::shared_ptr<const EmptySpaceFlags> current_;
  std::shared_ptr<const SpanRanges> extremeRanges_;  // identifies extremes_' spline
  std::shared_ptr<const ExtremeBounds> extremes_;
};

}  // namespace mfadvr
