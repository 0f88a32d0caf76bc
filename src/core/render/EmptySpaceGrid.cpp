#include "core/render/EmptySpaceGrid.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include "core/render/CellPyramid.h"

namespace mfadvr {

SpanRanges envelopeRanges(const ControlEnvelope& envelope) {
  SpanRanges r = *envelope.lower.spanRanges();
  const SpanRanges& upper = *envelope.upper.spanRanges();
  r.highest = upper.highest;
  // NaN anywhere: the whole range is NaN, as for one spline.
  if (std::isnan(upper.lowest) || std::isnan(upper.highest)) r.lowest = r.highest = upper.highest;
  return r;
}

EmptySpaceFlags buildEmptySpaceFlags(const SplineView& spline, const SpanRanges& r,
                                     const TransferFunctionTable& table, bool bezierRanges,
                                     const SplineView* upper) {
  if (upper) bezierRanges = false;
  const std::int64_t n = r.cellCount();
  EmptySpaceFlags out;
  // A cell's widened range lies within the whole spline's, widened by at least as much, and
  // the entries a range touches grow with it: when the whole range touches no transparent
  // entry, no cell is empty, and the per-cell pass (a sizeable part of a frame) is not needed.
  const float wholePad = skippingMargin(r, r.lowest, r.highest);
  if (n <= 0 || !table.mayBeTransparentOver(r.lowest - wholePad, r.highest + wholePad)) return out;
  std::vector<std::uint8_t>& flags = out.cells;
  flags.resize(static_cast<size_t>(n));
  // Slabs of cell planes; a slab's first planes read p more control planes than its cells
  // need, so slabs are not thin. The scanners and plane buffers are made once per thread, not
  // per slab (their allocations, zeroing and first touches measured a third of the build).
  const std::int64_t plane = std::int64_t(r.cells[0]) * r.cells[1], Z = r.cells[2];
  const std::int64_t slab = std::max<std::int64_t>(16, (Z + 15) / 16);
  tbb::enumerable_thread_specific<CellRangeScanners> perThread(
      [&] { return CellRangeScanners(spline, plane); });
  // The upper end's scanners (with an envelope): their highs replace the lower end's.
  tbb::enumerable_thread_specific<SpanRangeScanner> upperScanners(
      [&] { return SpanRangeScanner(upper ? *upper : spline); });
  const double bezierRounding = perThread.local().bezier.relativeRounding();
  std::atomic<std::int64_t> empties{0};
  tbb::parallel_for(std::int64_t(0), (Z + slab - 1) / slab, [&](std::int64_t task) {
    CellRangeScanners& t = perThread.local();
    SpanRangeScanner& scan = t.scan;
    BezierRangeScanner& bezier = t.bezier;
    std::vector<float>&lo = t.lo, &hi = t.hi, &bezierLo = t.bezierLo, &bezierHi = t.bezierHi;
    std::int64_t count = 0;
    for (std::int64_t z = task * slab; z < std::min(Z, (task + 1) * slab); ++z) {
      scan.plane(z, lo.data(), hi.data());
      if (upper) upperScanners.local().plane(z, bezierHi.data(), hi.data());  // its lows unused
      // By the control points' range first: empty, visible everywhere, or undecided (the
      // range touches a transparent table entry and a visible one). The Bezier range lies
      // within it, so only undecided cells can change: flagged 2 here, then computed.
      std::uint8_t* f = flags.data() + z * plane;
      bool undecided = false;
      for (std::int64_t q = 0; q < plane; ++q) {
        const float l = lo[static_cast<size_t>(q)], h = hi[static_cast<size_t>(q)];
        std::uint8_t state = 0;
        if (std::isfinite(l) && std::isfinite(h)) {  // else a control point is not finite
          const float pad = skippingMargin(r, l, h);
          using O = TransferFunctionTable::RangeOpacity;
          const O o = table.rangeOpacity(l - pad, h + pad);
          // Without Bezier ranges an undecided cell stays visible.
          state = o == O::Transparent ? 1 : o == O::Mixed && bezierRanges ? 2 : 0;
        }
        f[q] = state;
        undecided = undecided || state == 2;
      }
      if (undecided) {
        // A visible value at the cell's centre settles it (the centre is computed in float,
        // but only "not empty" is concluded from it, which is always safe).
        bezier.centres(z, bezierLo.data(), f);
        undecided = false;
        for (std::int64_t q = 0; q < plane; ++q)
          if (f[q] == 2) {
            if (table.classify(bezierLo[static_cast<size_t>(q)]).alpha > 0.0f)
              f[q] = 0;
            else
              undecided = true;
          }
      }
      if (undecided) bezier.plane(z, bezierLo.data(), bezierHi.data(), f);
      for (std::int64_t q = 0; q < plane; ++q) {
        if (f[q] == 2) {
          const size_t i = static_cast<size_t>(q);
          float l, h;
          const bool empty =
              skippingRange(r, bezierRounding, lo[i], hi[i], bezierLo[i], bezierHi[i], l, h) &&
              table.transparentOver(l, h);
          f[q] = empty ? 1 : 0;
        }
        count += f[q];
      }
    }
    empties += count;
  });
  out.emptyCells = empties;

  // The pyramid: a block is empty when all its cells are (the least of their 0/1 flags).
  CellPyramid pyramid = buildCellPyramid(r.cells, flags.data(), /*greatest=*/false);
  out.levels = pyramid.levels;
  for (int l = 0; l < out.levels; ++l) out.level[l] = pyramid.level[l];
  out.pyramid = std::move(pyramid.bytes);
  // Each empty cell keeps 1 + the level of the largest aligned all-empty block around it (1: the
  // cell alone), so that a ray's jump reads one byte instead of a flag per level. From the top
  // level down, a set block whose parent is not set fills its cells' rows; every cell of a set
  // block is written once.
  for (int l = out.levels - 1; l >= 0; --l) {
    const EmptyLevelView& L = out.level[l];
    const std::uint8_t* level = out.pyramid.data() + L.offset;
    const std::uint8_t* parent =
        l + 1 < out.levels ? out.pyramid.data() + out.level[l + 1].offset : nullptr;
    const int side = 2 << l;  // cells per axis of a block at this level
    const auto value = static_cast<std::uint8_t>(l + 2);
    tbb::parallel_for(0, L.count[2], [&](int k) {
      for (int j = 0; j < L.count[1]; ++j)
        for (int i = 0; i < L.count[0]; ++i) {
          if (!level[i + std::int64_t(L.count[0]) * (j + std::int64_t(L.count[1]) * k)]) continue;
          if (parent && parent[(i >> 1) +
                               out.level[l + 1].count[0] *
                                   ((j >> 1) + std::int64_t(out.level[l + 1].count[1]) * (k >> 1))])
            continue;
          const int x0 = i * side, x1 = std::min(x0 + side, r.cells[0]);
          for (int z = k * side; z < std::min((k + 1) * side, r.cells[2]); ++z)
            for (int y = j * side; y < std::min((j + 1) * side, r.cells[1]); ++y)
              std::fill_n(
                  flags.data() + x0 + std::int64_t(r.cells[0]) * (y + std::int64_t(r.cells[1]) * z),
                  x1 - x0, value);
        }
    });
  }
  return out;
}

std::shared_ptr<const EmptySpaceFlags> EmptySpaceCache::flags(const TensorBSpline& spline,
                                                              const TransferFunctionTable& table,
                                                              const ControlEnvelope* envelope) {
  const std::shared_ptr<const void> identity = spline.identity();
  const TransferFunctionView v = table.view();
  std::vector<std::uint64_t> key(static_cast<size_t>((v.count + 63) / 64) + 1, 0);
  for (int i = 0; i < v.count; ++i)
    if (v.entries[i].alpha == 0.0f) key[i / 64] |= std::uint64_t(1) << (i % 64);
  std::uint32_t lo, scale;
  std::memcpy(&lo, &v.lo, 4);
  std::memcpy(&scale, &v.scale, 4);
  key.back() = (std::uint64_t(lo) << 32) | scale;

  std::lock_guard lock(mutex_);
  const bool repeated = identity == lastSpline_;
  lastSpline_ = identity;
  const bool exactKept = flags_ && identity == spline_ && key == key_;
  // An instant of a time-varying model seen for the first time: the envelope's flags (built once
  // for every instant) rather than a build for this instant alone (nor its span ranges, which
  // cost as much as the frame); an instant rendered again (the camera moves, the time stays)
  // gets its own, tighter flags.
  if (envelope && !repeated && !exactKept) {
    const std::shared_ptr<const void> envelopeIdentity = envelope->lower.identity();
    if (!envelopeFlags_ || envelopeIdentity != envelopeSpline_ || key != envelopeKey_) {
      const SplineView upper = envelope->upper.view();
      envelopeFlags_ = std::make_shared<const EmptySpaceFlags>(buildEmptySpaceFlags(
          envelope->lower.view(), envelopeRanges(*envelope), table, false, &upper));
      envelopeSpline_ = envelopeIdentity;
      envelopeKey_ = key;
    }
    return current_ = envelopeFlags_;
  }
  if (!exactKept) {
    flags_ = std::make_shared<const EmptySpaceFlags>(
        buildEmptySpaceFlags(spline.view(), *spline.spanRanges(), table));
    spline_ = identity;
    key_ = std::move(key);
  }
  return current_ = flags_;
}

std::shared_ptr<const ExtremeBounds> EmptySpaceCache::extremeBounds(const TensorBSpline& spline) {
  const std::shared_ptr<const SpanRanges> ranges = spline.spanRanges();
  std::lock_guard lock(mutex_);
  if (!extremes_ || ranges != extremeRanges_) {
    extremes_ = std::make_shared<const ExtremeBounds>(buildExtremeBounds(spline.view(), *ranges));
    extremeRanges_ = ranges;
  }
  return extremes_;
}

}  // namespace mfadvr
