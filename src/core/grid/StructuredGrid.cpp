#include "core/grid/StructuredGrid.h"

#include <cmath>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {

std::string nonFiniteSampleMessage(const StructuredGrid& grid, std::int64_t n, float value) {
  const Index3& d = grid.dims;
  std::ostringstream m;
  m << (grid.source.empty() ? std::string("volume") : grid.source) << ": sample (" << n % d[0]
    << ", " << (n / d[0]) % d[1] << ", " << n / (d[0] * d[1]) << ") is " << value
    << "; NaN and Inf values (and values beyond the float32 range, about 3.4e38, which the "
       "samples are held in) cannot be encoded";
  return m.str();
}

void StructuredGrid::validateLayout() const {
  const std::string what = source.empty() ? std::string("volume") : source;
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 1) throw Error(what + ": grid dimensions must be at least 1 on every axis");
    if (!(spacing[a] > 0.0) || !std::isfinite(spacing[a]))
      throw Error(what + ": grid spacing must be positive and finite");
    if (!std::isfinite(origin[a])) throw Error(what + ": grid origin must be finite");
  }
}

void StructuredGrid::validate() const {
  validateLayout();
  const std::string what = source.empty() ? std::string("volume") : source;
  if (static_cast<std::int64_t>(values.size()) != sampleCount()) {
    std::ostringstream m;
    m << what << ": " << values.size() << " values for a " << dims[0] << "x" << dims[1] << "x"
      << dims[2] << " grid";
    throw Error(m.str());
  }
  for (std::int64_t n = 0; n < sampleCount(); ++n)
    if (!std::isfinite(values[static_cast<size_t>(n)]))
      throw Error(nonFiniteSampleMessage(*this, n, values[static_cast<size_t>(n)]));
}

}  // namespace mfadvr
