#include "core/grid/GridSamples.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {

GridSamples::GridSamples(const StructuredGrid& grid)
    : GridSamples(of(grid.values.data(), grid.dims)) {
  if (static_cast<std::int64_t>(grid.values.size()) != grid.sampleCount())
    data_ = floats_ = nullptr;
}

const float* GridSamples::values(std::int64_t first, std::int64_t count,
                                 std::vector<float>& scratch) const {
  if (floats_) return floats_ + first;
  scratch.resize(static_cast<size_t>(count));
  convert_(data_, first, count, scratch.data());
  return scratch.data();
}

std::vector<float> GridSamples::toFloats() const {
  std::vector<float> out(static_cast<size_t>(empty() ? 0 : sampleCount()));
  if (empty()) return out;
  if (floats_)
    std::copy(floats_, floats_ + sampleCount(), out.begin());
  else
    convert_(data_, 0, sampleCount(), out.data());
  return out;
}

void GridSamples::validateFor(const StructuredGrid& layout) const {
  const std::string what = layout.source.empty() ? std::string("volume") : layout.source;
  if (empty() || dims_ != layout.dims) {
    std::ostringstream m;
    m << what << ": " << (empty() ? 0 : sampleCount()) << " values for a " << layout.dims[0] << "x"
      << layout.dims[1] << "x" << layout.dims[2] << " grid";
    throw Error(m.str());
  }
  if (integral_) return;
  std::vector<float> scratch;
  const std::int64_t planeSize = dims_[0] * dims_[1];
  for (std::int64_t k = 0; k < dims_[2]; ++k) {
    const float* v = plane(k, scratch);
    for (std::int64_t i = 0; i < planeSize; ++i)
      if (!std::isfinite(v[i]))
        throw Error(nonFiniteSampleMessage(layout, k * planeSize + i, v[i]));
  }
}

std::pair<float, float> GridSamples::range() const {
  if (empty() || sampleCount() == 0) return {0.0f, 0.0f};
  std::vector<float> scratch;
  const std::int64_t planeSize = dims_[0] * dims_[1];
  float lo = plane(0, scratch)[0], hi = lo;
  for (std::int64_t k = 0; k < dims_[2]; ++k) {
    const float* v = plane(k, scratch);
    const auto [a, b] = std::minmax_element(v, v + planeSize);
    lo = std::min(lo, *a);
    hi = std::max(hi, *b);
  }
  return {lo, hi};
}

}  // namespace mfadvr
