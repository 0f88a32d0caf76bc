#pragma once
// The stretches inside a mesh's exact boundary of a frame's primary rays, gathered tile by tile
// by projecting the boundary's triangles into the image (the way a rasterizer finds the pixels a
// triangle covers) instead of one hierarchy traversal per ray.
//
// Once per frame every triangle is projected along the camera's rays into pixel coordinates
// and listed in the 16 x 16 pixel bins its bounding rectangle overlaps. For a tile, each listed
// triangle is tried only on the pixels of its rectangle that its projection, widened by
// kRasterMargin pixels, covers; each of those rays is tested against it with the same
// watertight test as the per-ray query (crossesTriangle), and the crossings are merged and
// turned into stretches the same way: the stretches are those of the per-ray query, to the bit
// (the projection only decides which triangles a ray is tested against, and leaves out none
// that the test could find: the widening is far beyond the rounding of either).
//
// The whole line of a ray counts (its part behind the camera too): a triangle behind a
// perspective camera projects through the camera's position like one in front. A triangle that
// reaches across the plane of the camera's position projects to no bounded region; those are
// kept apart and tried on every ray of a tile whose double cone of lines they meet.
// A pixel whose ray crosses more than kTileCrossings triangles is left to the per-ray query.
#include <cstdint>
#include <vector>

#include "core/mask/BoundaryView.h"
#include "core/render/kernel/BoundaryTileView.h"
#include "core/render/kernel/CameraRays.h"

namespace mfadvr {

// How far, in pixels, a triangle's projection is widened before pixels are tried against it.
inline constexpr double kRasterMargin = 0.05;
// Crossings gathered per pixel of a tile; a ray with more is queried alone.
inline constexpr int kTileCrossings = 32;

// One thread's buffers for the tiles it renders, reused from tile to tile.
struct BoundaryTileStretches {
  std::vector<int> count;
  std::vector<double> intervals;
  std::vector<BoundaryLine> lines;
  std::vector<BoundaryCrossing> crossings;
  // The view of the last tile gathered.
  BoundaryTileView view;
};

class BoundaryRaster {
 public:
  // Projects the triangles of `boundary` (which must outlive this) for `camera`'s rays.
  BoundaryRaster(const BoundaryView& boundary, const CameraRays& camera);

  // The stretches of the rays of pixels [x0, x1) x [y0, y1) into out (out.view).
  void gather(int x0, int y0, int x1, int y1, BoundaryTileStretches& out) const;

  // Counts for the documentation and tests: triangles listed in bins, and those across the
  // camera's plane.
  std::int64_t binnedTriangles() const { return static_cast<std::int64_t>(binTriangle_.size()); }
  std::int64_t straddlingTriangles() const { return static_cast<std::int64_t>(straddling_.size()); }

 private:
  // A projected triangle: its bounding pixel rectangle (inclusive) and, where its projection is
  // a proper triangle of moderate size, its three edges as a x + b y + c >= 0 inside, widened.
  struct Projected {
    int rect[4];  // x0, y0, x1, y1
    bool empty() const { return rect[0] > rect[2] || rect[1] > rect[3]; }
    bool hasEdges = false;
    double edge[3][3];
  };
  void tryTriangle(const Projected* projected, std::int32_t triangle, int x0, int y0, int x1,
                   int y1, int tileX, int tileY, int tileWidth, BoundaryTileStretches& out) const;

  BoundaryView boundary_;
  CameraRays camera_;
  // False where the camera's axes cannot be inverted or the bins would take too much memory:
  // every ray then queries the boundary alone.
  bool usable_ = true;
  int binsX_ = 0, binsY_ = 0;
  std::vector<Projected> projected_;       // per triangle
  std::vector<std::int32_t> binStart_;     // binsX * binsY + 1
  std::vector<std::int32_t> binTriangle_;  // triangle indices, bin by bin
  std::vector<std::int32_t> straddling_;   // triangles across the camera's plane
};

}  // namespace mfadvr
