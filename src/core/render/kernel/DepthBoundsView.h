#pragma once
// Where a ray can first and last meet a cell that is not empty, bounded per tile of pixels
// (host).
//
// On a sparse scene most of a ray's jumps over empty blocks come before its first visible cell,
// and a ray that passes the visible cells goes on jumping to the box's far face
// (docs/benchmarks.md). DepthBounds (render/DepthBounds.h) projects the coarse blocks of the
// empty-space pyramid that are not all empty onto the image, once per frame, and keeps per tile
// of pixels the greatest distance from the camera to such a block covering the tile, the boxes
// of the kDepthBoxes such blocks nearest the camera, and the least distance to the others. A ray
// of the tile has no sample in a cell that is not empty before both its entry into the kept boxes
// it crosses and that least distance, nor after the greatest distance: its march may begin at
// the first and end at the last, every step passed over would have been skipped, and is counted
// as skipped. Each ray takes its own start from the boxes (a box test each), rather than the
// tile's least distance to any block: a ray at a leaf's edge that misses the leaf no longer
// marches from the leaf's depth.
#include <cmath>
#include <cstdint>

#include "core/render/kernel/CameraRays.h"
#include "core/render/kernel/RayIntegrator.h"

namespace mfadvr {

// Boxes kept per tile: the blocks nearest the camera. More boxes start more rays nearer their
// first visible cell (4 instead of 1: a fifth fewer walk steps on the way in on a 256^3 bonsai),
// but their lists cost more to build per frame than the walks they save, and the box tests slow
// dense scenes (docs/benchmarks.md, "Each ray's own start").
inline constexpr int kDepthBoxes = 1;

struct DepthBoundsView {
  // Per tile of `tile` x `tile` pixels, x fastest over tilesX: a ray distance below which no
  // sample of the tile's rays lies in a cell that is not empty, unless it lies in one of the
  // tile's boxes (+infinity: none at all). Null: no bounds, every ray walks all its steps.
  const double* nearest = nullptr;
  // Per tile: a ray distance beyond which no sample of the tile's rays lies in a cell that is not
  // empty (-infinity: none at all). Null: the rays go to their ends.
  const double* farthest = nullptr;
  int tile = 1;
  int tilesX = 0;
  // Per tile, kDepthBoxes indices into `boxes` (-1 after the last): boxes holding every cell that
  // is not empty of the blocks nearest the camera among those covering the tile. Null: none.
  const std::int32_t* tileBoxes = nullptr;
  // Per tile, kDepthBoxes least distances from the camera (along the rays) to a point of each
  // kept box, in ascending order; no ray enters a box before its distance.
  const double* tileKeys = nullptr;
  // Per box: its least corner, then its greatest (6 doubles), in world coordinates, grown by a
  // margin beyond any rounding of a sample's location.
  const double* boxes = nullptr;
};

// The least ray distance at which the ray (o, d) of tile `tile` may meet a cell that is not
// empty: the least of its entries into the tile's boxes it crosses and the tile's nearest bound
// for its other blocks.
MFADVR_INLINE double nearestOnRay(const DepthBoundsView& b, std::int64_t tile, const double o[3],
                                  const double d[3]) {
  double nearest = b.nearest[tile];
  if (!b.tileBoxes) return nearest;
  const std::int32_t* kept = b.tileBoxes + tile * kDepthBoxes;
  if (kept[0] < 0) return nearest;
  double inv[3];
  inverseDirection(d, inv);
  const double* key = b.tileKeys + tile * kDepthBoxes;
  // The boxes come nearest first; none from one whose least distance is past the nearest found
  // on could lower it.
  for (int i = 0; i < kDepthBoxes && kept[i] >= 0 && key[i] < nearest; ++i) {
    const double* box = b.boxes + 6 * std::int64_t(kept[i]);
    double enter, leave;
    // (A box the ray leaves behind its origin holds none of its samples.)
    if (intersectBoxInverse(o, d, inv, box, box + 3, enter, leave) && leave >= 0.0 &&
        enter < nearest)
      nearest = enter;
  }
  return nearest;
}

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
  const double first = std::floor((nearestOnRay(b, tile, ray.o, ray.d) - ray.t0) / dt) - 2.0;
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
