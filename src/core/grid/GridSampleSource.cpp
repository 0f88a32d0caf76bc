#include "core/grid/GridSampleSource.h"

#include <algorithm>

#include "core/util/Error.h"

namespace mfadvr {

InMemoryGridSource::InMemoryGridSource(const StructuredGrid& grid) : grid_(grid) {
  grid_.validate();
  layout_ = subGridLayout(grid_, wholeRange(grid_.dims));
  layout_.notes = grid_.notes;
}

StructuredGrid InMemoryGridSource::read(const SampleRange& range) {
  return subGrid(grid_, range);
}

std::pair<double, double> InMemoryGridSource::valueRange() {
  const auto [lo, hi] = std::minmax_element(grid_.values.begin(), grid_.values.end());
  return {*lo, *hi};
}

}  // namespace mfadvr
