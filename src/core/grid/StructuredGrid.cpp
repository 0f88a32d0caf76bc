#include "core/grid/StructuredGrid.h"

#include <cmath>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {

void StructuredGrid::validate() const {
  const std::string what = source.empty() ? std::string("volume") : source;
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 1) throw Error(what + ": grid dimensions must be at least 1 on every axis");
    if (!(spacing[a] > 0.0) || !std::isfinite(spacing[a]))
      throw Error(what + ": grid spacing must be positive and finite");
    if (!std::isfinite(origin[a])) throw Error(what + ": grid origin must be finite");
  }
  if (static_cast<std::int64_t>(values.size()) != sampleCount()) {
    std::ostringstream m;
    m << what << ": " << values.size() << " values for a " << dims[0] << "x" << dims[1] << "x"
      << dims[2] << " grid";
    throw Error(m.str());
  }
  for (std::int64_t n = 0; n < sampleCount(); ++n) {
    if (!std::isfinite(values[static_cast<size_t>(n)])) {
      const std::int64_t i = n % dims[0], j = (n / dims[0]) % dims[1], k = n / (dims[0] * dims[1]);
      std::ostringstream m;
      m << what << ": sample (" << i << ", " << j << ", " << k << ") is "
        << values[static_cast<size_t>(n)]
        << "; NaN and Inf values (and values beyond the float32 range, about 3.4e38, which the "
           "samples are held in) cannot be encoded";
      throw Error(m.str());
    }
  }
}

}  // namespace mfadvr
