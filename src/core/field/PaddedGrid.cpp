#include "core/field/PaddedGrid.h"

#include <tbb/parallel_for.h>

#include "core/util/Error.h"

namespace mfadvr {

PaddedGrid::PaddedGrid(const StructuredGrid& grid, const std::vector<double>* values)
    : dims_(grid.dims),
      origin_(grid.origin),
      boxMax_(grid.boxMax()),
      spacing_(grid.spacing),
      invSpacing_(grid.spacing.cwiseInverse()) {
  for (int a = 0; a < 3; ++a)
    if (dims_[a] < 2)
      throw Error("grid filters need at least 2 samples per axis; axis " + std::to_string(a) +
                  " has " + std::to_string(dims_[a]));
  const std::int64_t nx = dims_[0], ny = dims_[1], nz = dims_[2];
  sy_ = nx + 2;
  sz_ = sy_ * (ny + 2);
  data_.assign(static_cast<size_t>(sz_ * (nz + 2)), 0.0f);
  auto ref = [&](std::int64_t i, std::int64_t j, std::int64_t k) -> float& {
    return data_[static_cast<size_t>((i + 1) + sy_ * (j + 1) + sz_ * (k + 1))];
  };
  auto copyFrom = [&](const auto& v) {
    if (static_cast<std::int64_t>(v.size()) != grid.sampleCount())
      throw Error("grid sample count does not match its dimensions");
    tbb::parallel_for(std::int64_t(0), nz, [&](std::int64_t k) {
      for (std::int64_t j = 0; j < ny; ++j)
        for (std::int64_t i = 0; i < nx; ++i)
          ref(i, j, k) = static_cast<float>(v[static_cast<size_t>(i + nx * (j + ny * k))]);
    });
  };
  if (values)
    copyFrom(*values);
  else
    copyFrom(grid.values);
  // Ghosts axis by axis; later axes extrapolate the earlier ghosts too, which fills edges and
  // corners with the multilinear extrapolation.
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j) {
      ref(-1, j, k) = 2.0f * ref(0, j, k) - ref(1, j, k);
      ref(nx, j, k) = 2.0f * ref(nx - 1, j, k) - ref(nx - 2, j, k);
    }
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t i = -1; i <= nx; ++i) {
      ref(i, -1, k) = 2.0f * ref(i, 0, k) - ref(i, 1, k);
      ref(i, ny, k) = 2.0f * ref(i, ny - 1, k) - ref(i, ny - 2, k);
    }
  for (std::int64_t j = -1; j <= ny; ++j)
    for (std::int64_t i = -1; i <= nx; ++i) {
      ref(i, j, -1) = 2.0f * ref(i, j, 0) - ref(i, j, 1);
      ref(i, j, nz) = 2.0f * ref(i, j, nz - 1) - ref(i, j, nz - 2);
    }
}

}  // namespace mfadvr
