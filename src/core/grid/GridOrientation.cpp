#include "core/grid/GridOrientation.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mfadvr {

OrientationResult orientToWorld(StructuredGrid& grid, const GridToWorld& toWorld,
                                double tolerance) {
  OrientationResult result;
  // The world position of sample 0: the matrix applies to the index frame's coordinates.
  Vec3d first = toWorld.offset;
  for (int w = 0; w < 3; ++w)
    for (int a = 0; a < 3; ++a) first[w] += toWorld.linear[w][a] * grid.origin[a];
  // For each index axis a: the world axis it runs along, its sign and its length.
  std::array<int, 3> worldAxisOf{-1, -1, -1};
  std::array<double, 3> signedScale{0, 0, 0};
  std::array<bool, 3> taken{false, false, false};
  bool axisAligned = true;
  for (int a = 0; a < 3; ++a) {
    double norm2 = 0.0;
    int best = 0;
    for (int w = 0; w < 3; ++w) {
      norm2 += toWorld.linear[w][a] * toWorld.linear[w][a];
      if (std::abs(toWorld.linear[w][a]) > std::abs(toWorld.linear[best][a])) best = w;
    }
    const double norm = std::sqrt(norm2);
    const double off =
        std::sqrt(std::max(0.0, norm2 - toWorld.linear[best][a] * toWorld.linear[best][a]));
    if (!(norm > 0.0) || off > tolerance * norm || taken[best]) {
      axisAligned = false;
      break;
    }
    taken[best] = true;
    worldAxisOf[a] = best;
    signedScale[a] = toWorld.linear[best][a];
  }

  if (!axisAligned) {
    grid.origin = first;
    result.axes = "oblique";
    result.note =
        "the file's orientation matrix is oblique (its voxel axes are not parallel to the "
        "world axes); the volume is kept in its voxel axes, with the file's spacing and its "
        "first voxel at the world position of the file's first voxel, so positions away from "
        "that voxel are not world (scanner) positions";
    return result;
  }

  static const char* kNames = "xyz";
  for (int a = 0; a < 3; ++a) {
    if (a) result.axes += ",";
    result.axes += signedScale[a] < 0 ? "-" : "+";
    result.axes += kNames[worldAxisOf[a]];
  }

  // Sample (i0, i1, i2) of the file lands at world index w[worldAxisOf[a]] = i_a, or
  // n_a - 1 - i_a where the axis runs backwards.
  StructuredGrid out = grid;
  Index3 outDims{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    const int w = worldAxisOf[a];
    outDims[w] = grid.dims[a];
    out.spacing[w] = std::abs(signedScale[a]) * grid.spacing[a];
    const double lastOffset = signedScale[a] * grid.spacing[a] * double(grid.dims[a] - 1);
    out.origin[w] = first[w] + std::min(0.0, lastOffset);
  }
  out.dims = outDims;
  for (std::int64_t k = 0; k < grid.dims[2]; ++k)
    for (std::int64_t j = 0; j < grid.dims[1]; ++j)
      for (std::int64_t i = 0; i < grid.dims[0]; ++i) {
        const std::array<std::int64_t, 3> in{i, j, k};
        std::array<std::int64_t, 3> at{0, 0, 0};
        for (int a = 0; a < 3; ++a)
          at[worldAxisOf[a]] = signedScale[a] < 0 ? grid.dims[a] - 1 - in[a] : in[a];
        out.at(at[0], at[1], at[2]) = grid.at(i, j, k);
      }
  grid = std::move(out);
  result.applied = true;
  return result;
}

}  // namespace mfadvr
