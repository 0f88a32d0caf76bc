#include "core/analytic/BuiltinGridSource.h"

#include <algorithm>

namespace mfadvr {

BuiltinGridSource::BuiltinGridSource(const std::string& spec) {
  const BuiltinSpec s = parseBuiltinSpec(spec);
  function_ = makeBuiltin(s.name);
  layout_ = builtinGridLayout(*function_, s.dims);
}

StructuredGrid BuiltinGridSource::read(const SampleRange& range) {
  StructuredGrid g = subGridLayout(layout_, range);
  fillBuiltinSamples(*function_, g);
  g.validate();
  return g;
}

std::pair<double, double> BuiltinGridSource::valueRange() {
  if (haveRange_) return range_;
  // Slabs of about 2^22 samples: enough planes to share among threads, little memory.
  const std::int64_t plane = layout_.dims[0] * layout_.dims[1];
  const std::int64_t planes = std::max<std::int64_t>(1, (std::int64_t{1} << 22) / plane);
  double lo = 0.0, hi = 0.0;
  for (std::int64_t k = 0; k < layout_.dims[2]; k += planes) {
    const std::int64_t last = std::min(layout_.dims[2], k + planes) - 1;
    const StructuredGrid slab = read({{0, 0, k}, {layout_.dims[0] - 1, layout_.dims[1] - 1, last}});
    const auto [a, b] = std::minmax_element(slab.values.begin(), slab.values.end());
    lo = k == 0 ? *a : std::min<double>(lo, *a);
    hi = k == 0 ? *b : std::max<double>(hi, *b);
  }
  range_ = {lo, hi};
  haveRange_ = true;
  return range_;
}

}  // namespace mfadvr
