#include "core/render/DepthBounds.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

namespace mfadvr {

namespace {

// An occupied block's projection: the tiles it may cover and its distances.
struct BlockFootprint {
  int tx0, ty0, tx1, ty1;  // tiles [tx0, tx1] x [ty0, ty1]
  double nearest;          // the least distance of a point of the block from the camera
  double farthest;         // the greatest
  double box[6];           // the box, least corner then greatest, grown (DepthBoundsView)
};

struct LevelBlocks {
  const std::uint8_t* flags;
  int count[3];
};

LevelBlocks levelBlocks(const ModelView& v, const int cells[3], int level) {
  if (level == 0) return {v.empty, {cells[0], cells[1], cells[2]}};
  const EmptyLevelView& L = v.emptyLevel[level - 1];
  return {v.emptyPyramid + L.offset, {L.count[0], L.count[1], L.count[2]}};
}

// Image-plane coordinates of a point: q - position written as w0 forward + w1 right + w2 up
// (the camera's vectors need be neither unit nor orthogonal: a host's frustum) is w = inverse
// (q - position), the inverse of the matrix [forward right up]; not valid when the vectors are
// degenerate.
struct ImagePlane {
  double inverse[3][3];  // rows
  bool valid = false;

  explicit ImagePlane(const CameraRays& c) {
    const double* f = c.forward;
    const double* r = c.right;
    const double* u = c.up;
    const double rows[3][3] = {
        // cross products over the determinant
        {r[1] * u[2] - r[2] * u[1], r[2] * u[0] - r[0] * u[2], r[0] * u[1] - r[1] * u[0]},
        {u[1] * f[2] - u[2] * f[1], u[2] * f[0] - u[0] * f[2], u[0] * f[1] - u[1] * f[0]},
        {f[1] * r[2] - f[2] * r[1], f[2] * r[0] - f[0] * r[2], f[0] * r[1] - f[1] * r[0]}};
    const double det = f[0] * rows[0][0] + f[1] * rows[0][1] + f[2] * rows[0][2];
    valid = std::isfinite(det) && std::abs(det) > 1e-300;
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 3; ++a) inverse[i][a] = valid ? rows[i][a] / det : 0.0;
  }
};

// The footprints of level `level`'s occupied blocks, one list per plane of blocks (z); returns
// the tiles they cover in all.
std::int64_t footprints(const CameraRays& cam, const ImagePlane& plane, const ModelView& v,
                        const int cells[3], int level, int tilesX, int tilesY,
                        std::vector<std::vector<BlockFootprint>>& planes) {
  const LevelBlocks blocks = levelBlocks(v, cells, level);
  // An occupied block is projected as the box of its occupied sub-blocks one level finer (a
  // cell's box at level 0): bounds of the finer level's precision for 8 flag reads per block.
  const int fine = level > 0 ? level - 1 : 0, ratio = level > 0 ? 2 : 1;
  const LevelBlocks subs = levelBlocks(v, cells, fine);
  // Per axis a and sub-block boundary b: the boundary's world coordinate, and `grow`: how far
  // the boxes are grown on axis a, far beyond the rounding of a sample's location (its
  // parameter's, and its world coordinate's at the camera's distance), so that a sample located
  // in a box's cell is in the grown box. Per side s (0: the boundary as a box's least face, moved
  // down by grow; 1: as its greatest, moved up) the face's coordinate less the camera's, and that
  // offset's part of each image-plane coordinate (a corner's w is the sum of its three faces'
  // parts): every distance and projection is the grown box's, so that a ray's entry into a box
  // is never less than the box's least distance (DepthBoundsView's early end relies on it).
  std::vector<double> face[2][3], part[2][3], world[3];
  double grow[3];
  for (int a = 0; a < 3; ++a) {
    const KnotAxisView& axis = v.spline.axis[a];
    const int p = axis.degree, n = subs.count[a];
    grow[a] =
        1e-7 / v.inverseExtent[a] +
        1e-12 * (std::abs(v.boxMin[a]) + 1.0 / v.inverseExtent[a] + std::abs(cam.position[a]));
    world[a].resize(std::size_t(n) + 1);
    for (int s = 0; s < 2; ++s) {
      face[s][a].resize(std::size_t(n) + 1);
      part[s][a].resize(3 * (std::size_t(n) + 1));
    }
    for (int b = 0; b <= n; ++b) {
      const int c = std::min(b << fine, cells[a]);
      world[a][b] = v.boxMin[a] + axis.knots[p + c] / v.inverseExtent[a];
      for (int s = 0; s < 2; ++s) {
        const double q = world[a][b] + (s ? grow[a] : -grow[a]) - cam.position[a];
        face[s][a][b] = q;
        for (int i = 0; i < 3; ++i) part[s][a][3 * b + i] = plane.inverse[i][a] * q;
      }
    }
  }
  // Pixel coordinates whose centres have image-plane coordinates (sx, sy).
  const double W = cam.width, H = cam.height;
  const double xScale = 0.5 * W / cam.halfWidth, yScale = -0.5 * H / cam.halfHeight;
  const double xOffset = 0.5 * W - 0.5, yOffset = 0.5 * H - 0.5;
  planes.assign(static_cast<std::size_t>(blocks.count[2]), {});
  std::vector<std::int64_t> planeCover(planes.size(), 0);
  tbb::parallel_for(0, blocks.count[2], [&](int bz) {
    std::vector<BlockFootprint>& list = planes[static_cast<std::size_t>(bz)];
    std::int64_t& cover = planeCover[static_cast<std::size_t>(bz)];
    std::int64_t index = std::int64_t(bz) * blocks.count[1] * blocks.count[0];
    for (int by = 0; by < blocks.count[1]; ++by)
      for (int bx = 0; bx < blocks.count[0]; ++bx, ++index) {
        if (blocks.flags[index]) continue;  // all empty
        // The sub-block range [lo, hi] per axis of the occupied sub-blocks.
        int lo[3] = {INT_MAX, INT_MAX, INT_MAX}, hi[3] = {-1, -1, -1};
        const int at[3] = {bx, by, bz};
        for (int k = bz * ratio; k < std::min(bz * ratio + ratio, subs.count[2]); ++k)
          for (int j = by * ratio; j < std::min(by * ratio + ratio, subs.count[1]); ++j)
            for (int i = bx * ratio; i < std::min(bx * ratio + ratio, subs.count[0]); ++i) {
              if (subs.flags[i +
                             std::int64_t(subs.count[0]) * (j + std::int64_t(subs.count[1]) * k)])
                continue;
              const int s[3] = {i, j, k};
              for (int a = 0; a < 3; ++a)
                lo[a] = std::min(lo[a], s[a]), hi[a] = std::max(hi[a], s[a]);
            }
        // (An occupied block has an occupied sub-block; the box of the block itself otherwise.)
        for (int a = 0; a < 3; ++a)
          if (hi[a] < lo[a]) {
            lo[a] = at[a] * ratio;
            hi[a] = std::min(at[a] * ratio + ratio, subs.count[a]) - 1;
          }
        const int bound[3][2] = {{lo[0], hi[0] + 1}, {lo[1], hi[1] + 1}, {lo[2], hi[2] + 1}};
        BlockFootprint f{0, 0, tilesX - 1, tilesY - 1, 0.0, 0.0, {}};
        for (int a = 0; a < 3; ++a) {
          f.box[a] = world[a][bound[a][0]] - grow[a];
          f.box[3 + a] = world[a][bound[a][1]] + grow[a];
        }
        double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
        bool behind = false;  // a corner not in front of a perspective camera
        double nearest = INFINITY, farthest = -INFINITY;
        for (int c = 0; c < 8; ++c) {
          double w[3] = {0.0, 0.0, 0.0};
          for (int a = 0; a < 3; ++a) {
            const int side = (c >> a) & 1;
            const double* t = &part[side][a][3 * bound[a][side]];
            for (int i = 0; i < 3; ++i) w[i] += t[i];
          }
          double sx = w[1], sy = w[2];
          if (cam.parallel) {
            nearest = std::min(nearest, w[0]);  // the ray distance along the (unnormalized) d
            farthest = std::max(farthest, w[0]);
          } else {
            if (!(w[0] > 1e-9 * (std::abs(w[1]) + std::abs(w[2])))) {
              behind = true;
              break;
            }
            sx /= w[0];
            sy /= w[0];
          }
          const double px = sx * xScale + xOffset, py = sy * yScale + yOffset;
          xMin = std::min(xMin, px), xMax = std::max(xMax, px);
          yMin = std::min(yMin, py), yMax = std::max(yMax, py);
        }
        if (!cam.parallel) {
          // The distances from the camera to the box's nearest and farthest points (a
          // perspective ray's direction is unit).
          double sum = 0.0, farSum = 0.0;
          for (int a = 0; a < 3; ++a) {
            const double l = face[0][a][bound[a][0]], h = face[1][a][bound[a][1]];
            const double e = l > 0.0 ? l : (h < 0.0 ? -h : 0.0);
            const double m = std::max(std::abs(l), std::abs(h));
            sum += e * e;
            farSum += m * m;
          }
          nearest = std::sqrt(sum);
          farthest = std::sqrt(farSum);
        }
        f.nearest = nearest;
        f.farthest = farthest;
        if (!behind) {
          // Pixels whose centres lie within the projection, one more on each side for the
          // rounding of the projection.
          const double x0 = std::ceil(xMin) - 1.0, x1 = std::floor(xMax) + 1.0;
          const double y0 = std::ceil(yMin) - 1.0, y1 = std::floor(yMax) + 1.0;
          if (!(x1 >= 0.0 && y1 >= 0.0 && x0 < W && y0 < H)) continue;  // off the image
          f.tx0 = static_cast<int>(std::max(x0, 0.0)) / kDepthTile;
          f.ty0 = static_cast<int>(std::max(y0, 0.0)) / kDepthTile;
          f.tx1 = static_cast<int>(std::min(x1, W - 1.0)) / kDepthTile;
          f.ty1 = static_cast<int>(std::min(y1, H - 1.0)) / kDepthTile;
        }
        cover += std::int64_t(f.tx1 - f.tx0 + 1) * (f.ty1 - f.ty0 + 1);
        list.push_back(f);
      }
  });
  std::int64_t covered = 0;
  for (std::int64_t c : planeCover) covered += c;
  return covered;
}

}  // namespace

DepthBounds::DepthBounds(const CameraRays& camera, const ModelView& view, int blocksPerAxis) {
  tilesX_ = (camera.width + kDepthTile - 1) / kDepthTile;
  const int tilesY = (camera.height + kDepthTile - 1) / kDepthTile;
  const std::int64_t tiles = std::int64_t(tilesX_) * tilesY;
  const ImagePlane plane(camera);
  if (!plane.valid) {  // no image plane to project onto: rays walk all their steps
    nearest_.assign(static_cast<std::size_t>(tiles), 0.0);
    farthest_.assign(static_cast<std::size_t>(tiles), std::numeric_limits<double>::infinity());
    return;
  }
  nearest_.assign(static_cast<std::size_t>(tiles), std::numeric_limits<double>::infinity());
  farthest_.assign(static_cast<std::size_t>(tiles), -std::numeric_limits<double>::infinity());
  int cells[3];
  int most = 0;
  for (int a = 0; a < 3; ++a) {
    cells[a] = view.spline.axis[a].count - view.spline.axis[a].degree;
    most = std::max(most, cells[a]);
  }
  level_ = 0;
  while (level_ < view.emptyLevels && (most + (1 << level_) - 1) >> level_ > blocksPerAxis)
    ++level_;
  // Tile updates per pixel of the image (and at least) before a coarser level is taken.
  constexpr std::int64_t kCoverPerPixel = 16, kCoverAtLeast = 1 << 16;
  const std::int64_t budget =
      std::max(kCoverPerPixel * camera.width * camera.height, kCoverAtLeast);
  std::vector<std::vector<BlockFootprint>> planes;
  std::int64_t covered = footprints(camera, plane, view, cells, level_, tilesX_, tilesY, planes);
  while (covered > budget && level_ < view.emptyLevels)
    covered = footprints(camera, plane, view, cells, ++level_, tilesX_, tilesY, planes);
  // The footprints in one list, in the planes' order; per row of tiles, those that cover it.
  std::vector<BlockFootprint> blocks;
  for (const auto& list : planes) blocks.insert(blocks.end(), list.begin(), list.end());
  occupied_ = static_cast<std::int64_t>(blocks.size());
  std::vector<std::int64_t> rowStart(static_cast<std::size_t>(tilesY) + 1, 0);
  for (const BlockFootprint& f : blocks)
    for (int ty = f.ty0; ty <= f.ty1; ++ty) ++rowStart[static_cast<std::size_t>(ty) + 1];
  for (int ty = 0; ty < tilesY; ++ty) rowStart[ty + 1] += rowStart[ty];
  std::vector<std::int32_t> rowBlocks(static_cast<std::size_t>(rowStart[tilesY]));
  {
    std::vector<std::int64_t> fill(rowStart.begin(), rowStart.end() - 1);
    for (std::size_t i = 0; i < blocks.size(); ++i)
      for (int ty = blocks[i].ty0; ty <= blocks[i].ty1; ++ty)
        rowBlocks[static_cast<std::size_t>(fill[ty]++)] = static_cast<std::int32_t>(i);
  }
  boxes_.resize(6 * blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i)
    std::copy(blocks[i].box, blocks[i].box + 6, boxes_.begin() + 6 * std::ptrdiff_t(i));
  // Per tile, the kDepthBoxes blocks of least nearest distance (the first taken on a tie) are
  // kept with their boxes; the nearest bound is the least of the others'. Rows of tiles are
  // independent, so the result does not depend on the threads.
  tileBoxes_.assign(static_cast<std::size_t>(tiles) * kDepthBoxes, -1);
  tileKeys_.resize(tileBoxes_.size());
  tbb::parallel_for(0, tilesY, [&](int ty) {
    std::int32_t* kept = tileBoxes_.data() + std::int64_t(ty) * tilesX_ * kDepthBoxes;
    double* rest = nearest_.data() + std::int64_t(ty) * tilesX_;
    double* greatest = farthest_.data() + std::int64_t(ty) * tilesX_;
    for (std::int64_t r = rowStart[ty]; r < rowStart[ty + 1]; ++r) {
      const std::int32_t index = rowBlocks[static_cast<std::size_t>(r)];
      const BlockFootprint& f = blocks[static_cast<std::size_t>(index)];
      for (int tx = f.tx0; tx <= f.tx1; ++tx) {
        greatest[tx] = std::max(greatest[tx], f.farthest);
        std::int32_t* k = kept + std::int64_t(tx) * kDepthBoxes;
        double* key = tileKeys_.data() + (std::int64_t(ty) * tilesX_ + tx) * kDepthBoxes;
        int n = 0;
        while (n < kDepthBoxes && k[n] >= 0) ++n;
        if (n == kDepthBoxes) {
          if (!(f.nearest < key[n - 1])) {
            rest[tx] = std::min(rest[tx], f.nearest);
            continue;
          }
          rest[tx] = std::min(rest[tx], key[n - 1]);  // the farthest kept block gives way
          --n;
        }
        int at = n;
        for (; at > 0 && f.nearest < key[at - 1]; --at) {
          key[at] = key[at - 1];
          k[at] = k[at - 1];
        }
        key[at] = f.nearest;
        k[at] = index;
      }
    }
  });
}

}  // namespace mfadvr
