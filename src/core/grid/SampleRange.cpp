#include "core/grid/SampleRange.h"

#include <cmath>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {

SampleRange wholeRange(const Index3& dims) {
  return {{0, 0, 0}, {dims[0] - 1, dims[1] - 1, dims[2] - 1}};
}

void requireRangeInside(const SampleRange& range, const Index3& dims) {
  for (int a = 0; a < 3; ++a)
    if (range.lo[a] < 0 || range.hi[a] < range.lo[a] || range.hi[a] >= dims[a])
      throw Error(std::string("internal: sample range outside the grid along ") + "xyz"[a]);
}

StructuredGrid subGridLayout(const StructuredGrid& grid, const SampleRange& range) {
  requireRangeInside(range, grid.dims);
  StructuredGrid g;
  g.dims = range.dims();
  g.origin = grid.position(range.lo[0], range.lo[1], range.lo[2]);
  g.spacing = grid.spacing;
  g.source = grid.source;
  g.fieldName = grid.fieldName;
  g.fieldAssociation = grid.fieldAssociation;
  g.sampleType = grid.sampleType;
  const double bytesPerSample =
      grid.sampleCount() > 0 ? double(grid.inputBytes) / double(grid.sampleCount()) : 0.0;
  g.inputBytes = static_cast<std::int64_t>(std::llround(bytesPerSample * double(g.sampleCount())));
  return g;
}

StructuredGrid subGrid(const StructuredGrid& grid, const SampleRange& range) {
  StructuredGrid g = subGridLayout(grid, range);
  g.values.resize(static_cast<size_t>(g.sampleCount()));
  size_t out = 0;
  for (std::int64_t k = range.lo[2]; k <= range.hi[2]; ++k)
    for (std::int64_t j = range.lo[1]; j <= range.hi[1]; ++j) {
      const float* row =
          &grid.values[static_cast<size_t>(range.lo[0] + grid.dims[0] * (j + grid.dims[1] * k))];
      for (std::int64_t i = 0; i < g.dims[0]; ++i) g.values[out++] = row[i];
    }
  return g;
}

}  // namespace mfadvr
