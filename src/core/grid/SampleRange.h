#pragma once
// A box of sample indices of a grid, and the samples of such a box as a grid of their own: the
// unit in which partitioned and out-of-core encoding read their input.
#include <cstdint>

#include "core/grid/StructuredGrid.h"
#include "core/util/Vec.h"

namespace mfadvr {

// Inclusive sample index ranges per axis.
struct SampleRange {
  Index3 lo{0, 0, 0}, hi{0, 0, 0};
  Index3 dims() const { return {hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1}; }
  std::int64_t sampleCount() const {
    const Index3 d = dims();
    return d[0] * d[1] * d[2];
  }
};

// The whole grid of `dims` samples as a range.
SampleRange wholeRange(const Index3& dims);

// Throws mfadvr::Error unless `range` is non-empty and inside a grid of `dims` samples.
void requireRangeInside(const SampleRange& range, const Index3& dims);

// A grid with the layout of `grid` (spacing, names, sample type; inputBytes in proportion)
// covering `range`: origin at the range's first sample, values not filled in.
StructuredGrid subGridLayout(const StructuredGrid& grid, const SampleRange& range);

// The samples of `range` as a grid of their own (same spacing, origin at the range's first
// sample).
StructuredGrid subGrid(const StructuredGrid& grid, const SampleRange& range);

}  // namespace mfadvr
