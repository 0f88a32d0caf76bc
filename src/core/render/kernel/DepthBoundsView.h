#pragma once
// Where a ray can first and last meet a cell that is not empty, bounded per tile of pixels
// (host).
//
// On a sparse scene most of a ray's jumps over empty blocks come before its first visible cell,
// and a ray that passes the visible cells goes on jumping to the box's far face
// (docs/benchmarks.md). DepthBounds (render/DepthBounds.h) projects the coarse blocks of the
// empty-space pyramid that are not all empty onto the image, once per frame, and keeps per tile
// of pixels the least and greatest distance from the camera to such a block covering the tile.
// A ray of the tile has no sample in a cell that is not empty outside that range, so its march
// may begin at the one and end at the other: every step passed over would have been skipped,
// and is counted as skipped.
#include <cmath>
#include <cstdint>

#include "core/render/kernel/RayIntegrator.h"

namespace mfadvr {

struct DepthBoundsView {
  // Per tile of `tile` x `tile` pixels, x fastest over tilesX: a ray distance below which no
  // sample of the tile's rays lies in a cell that is not empty (+infinity: none at all). Null:
  // no bounds, every ray walks all its steps.
  const double* nearest = nullptr;
  // Per tile: a ray distance beyond which no sample of the tile's rays lies in a cell that is not
  // empty (-infinity: none at all). Null: the rays go to their ends.
  const double* farthest = nullptr;
  int tile = 1;
  int tilesX = 0;
};

// Where the march of the ray through pixel (x, y) may begin (the returned start: every step
// before it lies in empty cells) and end (ray.steps is cut to the steps before the farthest
// bound; the start's `tail` counts those cut off that had a sample, all in empty cells). Two
// steps of slack on each side keep the rounding of a midpoint's distance on the safe side.
MFADVR_INLINE RayStart boundSteps(const DepthBoundsView& b, int x, int y, RaySegment& ray,
                                  double dt) {
  if (!b.nearest) return {};
  const std::int64_t tile = static_cast<std::int64_t>(y / b.tile) * b.tilesX + x / b.tile;
  const double steps = static_cast<double>(ray.steps);
  RayStart start;
  const double first = std::floor((b.nearest[tile] - ray.t0) / dt) - 2.0;
  if (first > 0.0) {
    start.k = first < steps ? static_cast<std::int64_t>(first) : ray.steps;
    start.skipped = start.k;
  }
  // Step j starts at t0 + j dt: from the first that starts beyond the bound, every sample does.
  if (!b.farthest) return start;
  const double last = std::ceil((b.farthest[tile] - ray.t0) / dt) + 2.0;
  if (!(last < steps)) return start;
  const std::int64_t end =
      last > static_cast<double>(start.k) ? static_cast<std::int64_t>(last) : start.k;
  // Steps from the first without length on have no sample (the integration stops there).
  std::int64_t sampled = ray.steps;
  double length;
  while (sampled > end &&
         (rayStep(static_cast<double>(sampled - 1), ray.t0, ray.tEnter, ray.tExit, dt, length),
          !(length > 0.0)))
    --sampled;
  start.tail = sampled - end;
  ray.steps = end;
  return start;
}

}  // namespace mfadvr
