#pragma once
// The stretches inside a mesh's exact boundary of the primary rays of one tile of pixels,
// gathered for the whole tile at once (BoundaryRaster.h) and read by the ray sampler in place of
// its own per-ray query of the boundary (BoundaryView.h), whose result they equal.
#include <cstdint>

#include "core/mask/BoundaryView.h"
#include "core/util/HostDevice.h"

namespace mfadvr {

// A pixel's count when its stretches were not gathered (the sampler then queries the boundary).
inline constexpr int kStretchesNotGathered = -2;

struct BoundaryTileView {
  // Per pixel of the tile, row by row: the count of stretches, -1 when the ray has more
  // crossings or stretches than the renderer follows (the voxel mask decides), or
  // kStretchesNotGathered; and 2 * kMaxBoundaryIntervals distances per pixel. Null: no tile.
  const int* count = nullptr;
  const double* intervals = nullptr;
  int x0 = 0, y0 = 0, width = 0, height = 0;
  int imageWidth = 1;  // pixel index = y * imageWidth + x (RaySegment::pixel)

  // The stretches of the ray of `pixel` (their count, or -1, with `intervals` pointed at them),
  // or kStretchesNotGathered for a pixel outside the tile or one not gathered.
  MFADVR_HD MFADVR_INLINE int find(std::int64_t pixel, const double*& stretches) const {
    if (!count || pixel < 0) return kStretchesNotGathered;
    const int x = static_cast<int>(pixel % imageWidth) - x0;
    const int y = static_cast<int>(pixel / imageWidth) - y0;
    if (x < 0 || y < 0 || x >= width || y >= height) return kStretchesNotGathered;
    const std::int64_t i = static_cast<std::int64_t>(y) * width + x;
    stretches = intervals + 2 * kMaxBoundaryIntervals * i;
    return count[i];
  }
};

}  // namespace mfadvr
