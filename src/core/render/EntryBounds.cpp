#include "core/render/EntryBounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mfadvr {

namespace {

// An occupied block's projection: the tiles it may cover and its least distance.
struct BlockFootprint {
  int tx0, ty0, tx1, ty1;  // tiles [tx0, tx1] x [ty0, ty1]
  double distance;
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

// Image-plane coordinates of a point: rel = q - position written as w0 forward + w1 right + w2
// up (the camera's vectors need be neither unit nor orthogonal: a host's frustum), through the
// inverse of the matrix [forward right up]. False when the vectors are degenerate.
struct ImagePlane {
  double inverse[3][3];  // rows
  bool valid = false;

  explicit ImagePlane(const CameraRays& c) {
    const double* f = c.forward;
    const double* r = c.right;
    const double* u = c.up;
    const double cols[3][3] = {
        {r[1] * u[2] - r[2] * u[1], r[2] * u[0] - r[0] * u[2], r[0] * u[1] - r[1] * u[0]},
        {u[1] * f[2] - u[2] * f[1], u[2] * f[0] - u[0] * f[2], u[0] * f[1] - u[1] * f[0]},
        {f[1] * r[2] - f[2] * r[1], f[2] * r[0] - f[0] * r[2], f[0] * r[1] - f[1] * r[0]}};
    const double det = f[0] * cols[0][0] + f[1] * cols[0][1] + f[2] * cols[0][2];
    valid = std::isfinite(det) && std::abs(det) > 1e-300;
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 3; ++a) inverse[i][a] = valid ? cols[i][a] / det : 0.0;
  }
  void apply(const double q[3], double w[3]) const {
    for (int i = 0; i < 3; ++i)
      w[i] = inverse[i][0] * q[0] + inverse[i][1] * q[1] + inverse[i][2] * q[2];
  }
};

// The footprints of level `level`'s occupied blocks; returns the tiles they cover in all.
std::int64_t footprints(const CameraRays& cam, const ModelView& v, const int cells[3], int level,
                        int tilesX, int tilesY, std::vector<BlockFootprint>& out) {
  out.clear();
  const LevelBlocks blocks = levelBlocks(v, cells, level);
  // Each block's physical extent per axis.
  std::vector<double> lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const KnotAxisView& axis = v.spline.axis[a];
    const int p = axis.degree, n = blocks.count[a];
    lo[a].resize(n);
    hi[a].resize(n);
    for (int b = 0; b < n; ++b) {
      const int c0 = b << level;
      const int c1 = std::min((b + 1) << level, cells[a]);
      lo[a][b] = v.boxMin[a] + axis.knots[p + c0] / v.inverseExtent[a];
      hi[a][b] = v.boxMin[a] + axis.knots[p + c1] / v.inverseExtent[a];
    }
  }
  const double W = cam.width, H = cam.height;
  const ImagePlane plane(cam);
  std::int64_t covered = 0;
  std::int64_t index = 0;
  for (int bz = 0; bz < blocks.count[2]; ++bz)
    for (int by = 0; by < blocks.count[1]; ++by)
      for (int bx = 0; bx < blocks.count[0]; ++bx, ++index) {
        if (blocks.flags[index]) continue;  // all empty
        const double boxLo[3] = {lo[0][bx], lo[1][by], lo[2][bz]};
        const double boxHi[3] = {hi[0][bx], hi[1][by], hi[2][bz]};
        BlockFootprint f{0, 0, tilesX - 1, tilesY - 1, 0.0};
        double xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
        bool behind = false;  // a corner not in front of a perspective camera
        double nearest = INFINITY;
        for (int c = 0; c < 8; ++c) {
          const double q[3] = {(c & 1 ? boxHi : boxLo)[0] - cam.position[0],
                               (c & 2 ? boxHi : boxLo)[1] - cam.position[1],
                               (c & 4 ? boxHi : boxLo)[2] - cam.position[2]};
          double w[3];
          plane.apply(q, w);
          double sx = w[1], sy = w[2];
          if (cam.parallel) {
            nearest = std::min(nearest, w[0]);  // the ray distance along the (unnormalized) d
          } else {
            if (!(w[0] > 1e-9 * (std::abs(w[1]) + std::abs(w[2])))) {
              behind = true;
              break;
            }
            sx /= w[0];
            sy /= w[0];
          }
          // Pixel coordinates whose centres have these image-plane coordinates.
          const double px = (sx / cam.halfWidth + 1.0) * 0.5 * W - 0.5;
          const double py = (1.0 - sy / cam.halfHeight) * 0.5 * H - 0.5;
          xMin = std::min(xMin, px), xMax = std::max(xMax, px);
          yMin = std::min(yMin, py), yMax = std::max(yMax, py);
        }
        if (!cam.parallel) {
          // The distance from the camera to the box (a perspective ray's direction is unit).
          double s = 0.0;
          for (int a = 0; a < 3; ++a) {
            const double e =
                std::max({boxLo[a] - cam.position[a], 0.0, cam.position[a] - boxHi[a]});
            s += e * e;
          }
          nearest = std::sqrt(s);
        }
        f.distance = nearest;
        if (!behind) {
          // Pixels whose centres lie within the projection, one more on each side for the
          // rounding of the projection.
          const double x0 = std::ceil(xMin) - 1.0, x1 = std::floor(xMax) + 1.0;
          const double y0 = std::ceil(yMin) - 1.0, y1 = std::floor(yMax) + 1.0;
          if (!(x1 >= 0.0 && y1 >= 0.0 && x0 < W && y0 < H)) continue;  // off the image
          f.tx0 = static_cast<int>(std::max(x0, 0.0)) / kEntryTile;
          f.ty0 = static_cast<int>(std::max(y0, 0.0)) / kEntryTile;
          f.tx1 = static_cast<int>(std::min(x1, W - 1.0)) / kEntryTile;
          f.ty1 = static_cast<int>(std::min(y1, H - 1.0)) / kEntryTile;
        }
        covered += std::int64_t(f.tx1 - f.tx0 + 1) * (f.ty1 - f.ty0 + 1);
        out.push_back(f);
      }
  return covered;
}

}  // namespace

EntryBounds::EntryBounds(const CameraRays& camera, const ModelView& view, int blocksPerAxis) {
  tilesX_ = (camera.width + kEntryTile - 1) / kEntryTile;
  const int tilesY = (camera.height + kEntryTile - 1) / kEntryTile;
  const std::int64_t tiles = std::int64_t(tilesX_) * tilesY;
  if (!ImagePlane(camera).valid) {  // no image plane to project onto: rays start at step 0
    distance_.assign(static_cast<std::size_t>(tiles), 0.0);
    return;
  }
  distance_.assign(static_cast<std::size_t>(tiles), std::numeric_limits<double>::infinity());
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
  std::vector<BlockFootprint> blocks;
  std::int64_t covered = footprints(camera, view, cells, level_, tilesX_, tilesY, blocks);
  while (covered > budget && level_ < view.emptyLevels)
    covered = footprints(camera, view, cells, ++level_, tilesX_, tilesY, blocks);
  occupied_ = static_cast<std::int64_t>(blocks.size());
  for (const BlockFootprint& f : blocks)
    for (int ty = f.ty0; ty <= f.ty1; ++ty) {
      double* row = distance_.data() + std::int64_t(ty) * tilesX_;
      for (int tx = f.tx0; tx <= f.tx1; ++tx) row[tx] = std::min(row[tx], f.distance);
    }
}

}  // namespace mfadvr
