#include "core/render/EmptySpaceGrid.h"

#include "core/render/kernel/SplineRaySampler.h"  // kEmptyBlock

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace mfadvr {

EmptySpaceFlags buildEmptySpaceFlags(const SpanRanges& r, const TransferFunctionTable& table) {
  const std::int64_t n = std::int64_t(r.cells[0]) * r.cells[1] * r.cells[2];
  EmptySpaceFlags out;
  // A cell's widened range lies within the whole spline's, widened by at least as much, and
  // the entries a range touches grow with it: when the whole range touches no transparent
  // entry, no cell is empty, and the per-cell pass (a sizeable part of a frame) is not needed.
  const float wholePad = skippingMargin(r, r.lowest, r.highest);
  if (!table.mayBeTransparentOver(r.lowest - wholePad, r.highest + wholePad)) return out;
  std::vector<std::uint8_t>& flags = out.cells;
  flags.assign(static_cast<size_t>(n), 0);
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, n, 1 << 14), [&](const auto& range) {
    for (std::int64_t i = range.begin(); i < range.end(); ++i) {
      const float lo = r.min[i], hi = r.max[i];
      const float pad = skippingMargin(r, lo, hi);
      flags[i] = table.transparentOver(lo - pad, hi + pad) ? 1 : 0;
    }
  });
  for (int a = 0; a < 3; ++a) out.blockCounts[a] = (r.cells[a] + kEmptyBlock - 1) / kEmptyBlock;
  const int* b = out.blockCounts;
  out.blocks.assign(static_cast<size_t>(b[0]) * b[1] * b[2], 1);
  // One layer of blocks per task: the layers write disjoint blocks.
  std::vector<std::int64_t> emptyPerLayer(static_cast<size_t>(b[2]), 0);
  tbb::parallel_for(0, b[2], [&](int kb) {
    std::int64_t empties = 0;
    const int kEnd = std::min(r.cells[2], (kb + 1) * kEmptyBlock);
    for (int k = kb * kEmptyBlock; k < kEnd; ++k)
      for (int j = 0; j < r.cells[1]; ++j)
        for (int i = 0; i < r.cells[0]; ++i) {
          const bool empty =
              flags[i + std::int64_t(r.cells[0]) * (j + std::int64_t(r.cells[1]) * k)];
          empties += empty ? 1 : 0;
          if (!empty) out.blocks[i / kEmptyBlock + b[0] * (j / kEmptyBlock + b[1] * kb)] = 0;
        }
    emptyPerLayer[kb] = empties;
  });
  for (const std::int64_t e : emptyPerLayer) out.emptyCells += e;
  return out;
}

std::shared_ptr<const EmptySpaceFlags> EmptySpaceCache::flags(const TensorBSpline& spline,
                                                              const TransferFunctionTable& table) {
  const std::shared_ptr<const SpanRanges> ranges = spline.spanRanges();
  const TransferFunctionView v = table.view();
  std::vector<std::uint64_t> key(static_cast<size_t>((v.count + 63) / 64) + 1, 0);
  for (int i = 0; i < v.count; ++i)
    if (v.entries[i].alpha == 0.0f) key[i / 64] |= std::uint64_t(1) << (i % 64);
  std::uint32_t lo, scale;
  std::memcpy(&lo, &v.lo, 4);
  std::memcpy(&scale, &v.scale, 4);
  key.back() = (std::uint64_t(lo) << 32) | scale;

  std::lock_guard lock(mutex_);
  if (!flags_ || ranges != ranges_ || key != key_) {
    flags_ = std::make_shared<const EmptySpaceFlags>(buildEmptySpaceFlags(*ranges, table));
    ranges_ = ranges;
    key_ = std::move(key);
  }
  return flags_;
}

}  // namespace mfadvr
