#include "core/decode/GridDecoder.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/encode/StructuredEncoder.h"
#include "core/util/Error.h"

namespace mfadvr {

DecodeGrid decodeGridWithSamples(const Model& model, const Index3& dims) {
  DecodeGrid g;
  g.dims = dims;
  g.origin = model.domain().min;
  const Vec3d extent = model.domain().extent();
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 2 || dims[a] > (1 << 20))
      throw Error("a decoded grid needs 2 to 1048576 samples per axis, got " +
                  std::to_string(dims[a]) + " along " + "xyz"[a]);
    g.spacing[a] = extent[a] / static_cast<double>(dims[a] - 1);
  }
  return g;
}

DecodeGrid defaultDecodeGrid(const Model& model) {
  const Index3 recorded = model.provenance().sampleDims;
  if (recorded[0] >= 2 && recorded[1] >= 2 && recorded[2] >= 2)
    return decodeGridWithSamples(model, recorded);
  const Vec3d extent = model.domain().extent();
  const Vec3d spacing = model.dataSpacing();
  Index3 dims{};
  for (int a = 0; a < 3; ++a)
    dims[a] = std::max<std::int64_t>(2, std::llround(extent[a] / spacing[a]) + 1);
  return decodeGridWithSamples(model, dims);
}

void decodeBySlabs(const Model& model, const DecodeGrid& grid, std::int64_t slabSamples,
                   const std::function<void(std::int64_t, std::int64_t,
                                            std::span<const double>)>& sink) {
  const Index3& d = grid.dims;
  const std::int64_t plane = d[0] * d[1];
  const std::int64_t planesPerSlab = std::clamp<std::int64_t>(slabSamples / plane, 1, d[2]);
  const bool masked = !model.mask().empty();
  for (std::int64_t z0 = 0; z0 < d[2]; z0 += planesPerSlab) {
    const std::int64_t z1 = std::min(d[2], z0 + planesPerSlab);
    std::vector<double> values = splineOnGrid(model.spline(), d, z0, z1);
    if (masked) {
      tbb::parallel_for(z0, z1, [&](std::int64_t z) {
        for (std::int64_t y = 0; y < d[1]; ++y)
          for (std::int64_t x = 0; x < d[0]; ++x) {
            const Vec3d p = grid.origin + Vec3d(static_cast<double>(x), static_cast<double>(y),
                                                static_cast<double>(z))
                                              .cwiseProduct(grid.spacing);
            if (!model.inside(p))
              values[static_cast<size_t>((z - z0) * plane + y * d[0] + x)] =
                  std::numeric_limits<double>::quiet_NaN();
          }
      });
    }
    sink(z0, z1, values);
  }
}

}  // namespace mfadvr
