#pragma once
// Where a ray can first meet a cell that is not empty, bounded per tile of pixels (host).
//
// On a sparse scene most of a ray's jumps over empty blocks come before its first visible cell
// (docs/benchmarks.md). EntryBounds (render/EntryBounds.h) projects the coarse blocks of the
// empty-space pyramid that are not all empty onto the image, once per frame, and keeps per tile
// of pixels the least distance from the camera to such a block covering the tile. A ray of the
// tile has no sample in a cell that is not empty before that distance, so its march may begin
// there: every step before it would have been skipped, and is counted as skipped.
#include <cmath>
#include <cstdint>

#include "core/render/kernel/RayIntegrator.h"

namespace mfadvr {

struct EntryBoundsView {
  // Per tile of `tile` x `tile` pixels, x fastest over tilesX: a ray distance below which no
  // sample of the tile's rays lies in a cell that is not empty (+infinity: none at all). Null:
  // no bounds, every ray starts at its first step.
  const double* distance = nullptr;
  int tile = 1;
  int tilesX = 0;
};

// Where the march of the ray through pixel (x, y) may begin: every step before it lies in empty
// cells. Two steps of slack keep the rounding of a midpoint's distance on the safe side.
MFADVR_INLINE RayStart entryStart(const EntryBoundsView& b, int x, int y, const RaySegment& ray,
                                  double dt) {
  if (!b.distance) return {};
  const double bound = b.distance[static_cast<std::int64_t>(y / b.tile) * b.tilesX + x / b.tile];
  const double first = std::floor((bound - ray.t0) / dt) - 2.0;
  if (!(first > 0.0)) return {};
  const std::int64_t k =
      first < static_cast<double>(ray.steps) ? static_cast<std::int64_t>(first) : ray.steps;
  return {k, k};
}

}  // namespace mfadvr
