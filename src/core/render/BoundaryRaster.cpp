#include "core/render/BoundaryRaster.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace mfadvr {
namespace {

// Bins of 16 x 16 pixels: the tiles of the ray caster's driver (forEachTile).
constexpr int kBin = 16;
// A vertex nearer the plane of a perspective camera's position than this fraction of its
// distance from it makes its triangle one that reaches across that plane.
constexpr double kPlaneFraction = 1e-6;
// Projected coordinates beyond this many pixels are not used for a triangle's edges (their
// rounding would approach the margin); its rectangle alone then selects the pixels.
constexpr double kMaxEdgeCoordinate = 1e6;
// At most this many bin entries; a frame that would need more leaves every ray to its own
// query (2^24 entries: 64 MiB).
constexpr std::int64_t kMaxBinEntries = std::int64_t(1) << 24;

static_assert(kTileCrossings <= kMaxBoundaryCrossings,
              "a pixel's gathered crossings must be fewer than the per-ray query's limit");

}  // namespace

BoundaryRaster::BoundaryRaster(const BoundaryView& boundary, const CameraRays& camera)
    : boundary_(boundary), camera_(camera) {
  binsX_ = (camera.width + kBin - 1) / kBin;
  binsY_ = (camera.height + kBin - 1) / kBin;
  binStart_.assign(static_cast<size_t>(binsX_) * binsY_ + 1, 0);
  if (!boundary.nodes || boundary.triangleCount <= 0) return;

  // (distance along forward, right, up) of a point relative to the camera's position: the
  // inverse of the matrix whose columns are the camera's axes (orthonormal from RayGenerator,
  // but any basis projects correctly this way).
  Eigen::Matrix3d axes;
  for (int a = 0; a < 3; ++a) {
    axes(a, 0) = camera.forward[a];
    axes(a, 1) = camera.right[a];
    axes(a, 2) = camera.up[a];
  }
  Eigen::Matrix3d toCamera;
  bool invertible = false;
  axes.computeInverseWithCheck(toCamera, invertible);
  if (!invertible || !(camera.halfWidth > 0.0) || !(camera.halfHeight > 0.0)) {
    usable_ = false;
    return;
  }
  const Eigen::Vector3d position(camera.position[0], camera.position[1], camera.position[2]);
  const double w = camera.width, h = camera.height;

  const auto count = static_cast<size_t>(boundary.triangleCount);
  projected_.resize(count);
  // Per triangle: 0 outside the image, 1 binned, 2 across the camera's plane.
  std::vector<std::uint8_t> kind(count, 0);
  auto project = [&](size_t i) {
    Projected& pr = projected_[i];
    pr.rect[0] = pr.rect[1] = 0;
    pr.rect[2] = pr.rect[3] = -1;  // empty
    const double* tri = boundary.triangles + 9 * i;
    double px[3][2];
    int side = 0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d q =
          Eigen::Vector3d(tri[3 * k], tri[3 * k + 1], tri[3 * k + 2]) - position;
      const Eigen::Vector3d s = toCamera * q;
      double sx = s[1], sy = s[2];
      if (!camera.parallel) {
        const double z = s[0];
        const int zSide = z > 0.0 ? 1 : -1;
        if (!(std::abs(z) > kPlaneFraction * q.norm()) || (side != 0 && zSide != side)) {
          kind[i] = 2;
          return;
        }
        side = zSide;
        sx /= z;
        sy /= z;
      }
      // The inverse of primaryRay's pixel centres: pixel x's ray has sx = (2 (x + 0.5) / width
      // - 1) halfWidth.
      px[k][0] = (sx / camera.halfWidth + 1.0) * 0.5 * w - 0.5;
      px[k][1] = (1.0 - sy / camera.halfHeight) * 0.5 * h - 0.5;
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 2; ++a) {
        lo[a] = std::min(lo[a], px[k][a]);
        hi[a] = std::max(hi[a], px[k][a]);
      }
    // Clamped in floating point first, so that far projections cannot overflow an int.
    pr.rect[0] = static_cast<int>(std::clamp(std::ceil(lo[0] - kRasterMargin), 0.0, w));
    pr.rect[1] = static_cast<int>(std::clamp(std::ceil(lo[1] - kRasterMargin), 0.0, h));
    pr.rect[2] = static_cast<int>(std::clamp(std::floor(hi[0] + kRasterMargin), -1.0, w - 1.0));
    pr.rect[3] = static_cast<int>(std::clamp(std::floor(hi[1] + kRasterMargin), -1.0, h - 1.0));
    if (pr.empty()) return;  // outside the image
    kind[i] = 1;
    const double area = (px[1][0] - px[0][0]) * (px[2][1] - px[0][1]) -
                        (px[1][1] - px[0][1]) * (px[2][0] - px[0][0]);
    bool moderate = true;
    for (int k = 0; k < 3; ++k)
      moderate = moderate && std::abs(px[k][0]) <= kMaxEdgeCoordinate &&
                 std::abs(px[k][1]) <= kMaxEdgeCoordinate;
    if (area != 0.0 && moderate) {
      // Inside is to the left of each edge p -> q of a counter-clockwise triangle; widened by
      // the margin along the edge's normal (|a| + |b| >= the normal's length).
      const double orientation = area > 0.0 ? 1.0 : -1.0;
      for (int e = 0; e < 3; ++e) {
        const double* p = px[e];
        const double* q = px[(e + 1) % 3];
        const double a = orientation * (p[1] - q[1]), b = orientation * (q[0] - p[0]);
        pr.edge[e][0] = a;
        pr.edge[e][1] = b;
        pr.edge[e][2] = -(a * p[0] + b * p[1]) + kRasterMargin * (std::abs(a) + std::abs(b));
      }
      pr.hasEdges = true;
    }
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 1024), [&](const auto& r) {
    for (size_t i = r.begin(); i < r.end(); ++i) project(i);
  });
  std::int64_t entries = 0;
  for (size_t i = 0; i < count; ++i) {
    if (kind[i] == 2) straddling_.push_back(static_cast<std::int32_t>(i));
    if (kind[i] != 1) continue;
    const Projected& pr = projected_[i];
    entries += static_cast<std::int64_t>(pr.rect[2] / kBin - pr.rect[0] / kBin + 1) *
               (pr.rect[3] / kBin - pr.rect[1] / kBin + 1);
  }
  if (entries > kMaxBinEntries) {
    usable_ = false;
    return;
  }
  for (size_t i = 0; i < count; ++i) {
    const Projected& pr = projected_[i];
    if (pr.empty()) continue;
    for (int by = pr.rect[1] / kBin; by <= pr.rect[3] / kBin; ++by)
      for (int bx = pr.rect[0] / kBin; bx <= pr.rect[2] / kBin; ++bx)
        ++binStart_[static_cast<size_t>(by) * binsX_ + bx + 1];
  }
  for (size_t b = 1; b < binStart_.size(); ++b) binStart_[b] += binStart_[b - 1];
  binTriangle_.resize(static_cast<size_t>(entries));
  std::vector<std::int32_t> next(binStart_.begin(), binStart_.end() - 1);
  for (size_t i = 0; i < count; ++i) {
    const Projected& pr = projected_[i];
    if (pr.empty()) continue;
    for (int by = pr.rect[1] / kBin; by <= pr.rect[3] / kBin; ++by)
      for (int bx = pr.rect[0] / kBin; bx <= pr.rect[2] / kBin; ++bx)
        binTriangle_[static_cast<size_t>(next[static_cast<size_t>(by) * binsX_ + bx]++)] =
            static_cast<std::int32_t>(i);
  }
}

void BoundaryRaster::tryTriangle(const Projected* pr, std::int32_t triangle, int x0, int y0, int x1,
                                 int y1, int tileX, int tileY, int tileWidth,
                                 BoundaryTileStretches& out) const {
  if (pr) {
    x0 = std::max(x0, pr->rect[0]);
    y0 = std::max(y0, pr->rect[1]);
    x1 = std::min(x1, pr->rect[2] + 1);
    y1 = std::min(y1, pr->rect[3] + 1);
  }
  const double* tri = boundary_.triangles + 9 * static_cast<std::int64_t>(triangle);
  const bool edges = pr && pr->hasEdges;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      if (edges) {
        const auto& e = pr->edge;
        if (e[0][0] * x + e[0][1] * y + e[0][2] < 0.0 ||
            e[1][0] * x + e[1][1] * y + e[1][2] < 0.0 || e[2][0] * x + e[2][1] * y + e[2][2] < 0.0)
          continue;
      }
      const size_t p = static_cast<size_t>(y - tileY) * tileWidth + (x - tileX);
      int& n = out.count[p];
      if (n > kTileCrossings) continue;  // overflowed: left to the per-ray query
      // A line without direction crosses nothing (as in forEachCrossing).
      if (!out.lines[p].valid) continue;
      double t = 0.0;
      int step = 0;
      if (!crossesTriangle(out.lines[p], tri, t, step)) continue;
      if (n == kTileCrossings) {
        n = kTileCrossings + 1;
        continue;
      }
      out.crossings[p * kTileCrossings + static_cast<size_t>(n++)] = {t, step};
    }
}

void BoundaryRaster::gather(int x0, int y0, int x1, int y1, BoundaryTileStretches& out) const {
  const int width = std::max(x1 - x0, 0), height = std::max(y1 - y0, 0);
  const size_t pixels = static_cast<size_t>(width) * height;
  out.count.assign(pixels, 0);
  out.intervals.resize(pixels * 2 * kMaxBoundaryIntervals);
  out.view = BoundaryTileView{out.count.data(), out.intervals.data(), x0, y0, width,
                              height,           camera_.width};
  if (!usable_ || !boundary_.nodes) {
    std::fill(out.count.begin(), out.count.end(), kStretchesNotGathered);
    return;
  }
  out.lines.resize(pixels);
  out.crossings.resize(pixels * kTileCrossings);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      double o[3], d[3];
      primaryRay(camera_, x, y, o, d);
      out.lines[static_cast<size_t>(y - y0) * width + (x - x0)] = boundaryLine(o, d);
    }

  // Each pixel lies in one bin, so that no triangle is tried twice on a pixel.
  for (int by = y0 / kBin; by <= (y1 - 1) / kBin && by < binsY_; ++by)
    for (int bx = x0 / kBin; bx <= (x1 - 1) / kBin && bx < binsX_; ++bx) {
      const int cx0 = std::max(x0, bx * kBin), cy0 = std::max(y0, by * kBin);
      const int cx1 = std::min(x1, (bx + 1) * kBin), cy1 = std::min(y1, (by + 1) * kBin);
      const size_t b = static_cast<size_t>(by) * binsX_ + bx;
      for (std::int32_t k = binStart_[b]; k < binStart_[b + 1]; ++k) {
        const std::int32_t i = binTriangle_[static_cast<size_t>(k)];
        tryTriangle(&projected_[static_cast<size_t>(i)], i, cx0, cy0, cx1, cy1, x0, y0, width, out);
      }
    }

  if (!straddling_.empty() && pixels > 0) {
    // The tile's lines all pass through the camera's position c with directions in the cone of
    // its corner rays: the forward cone is where every n_i . (x - c) >= 0 for the planes through
    // c and neighbouring corners, the backward cone where every one is <= 0. A triangle all on
    // the outer side of one plane misses the forward cone, all on the inner side of one misses
    // the backward cone; missing both, it meets none of the lines.
    const int cx[4] = {x0, x1 - 1, x1 - 1, x0}, cy[4] = {y0, y0, y1 - 1, y1 - 1};
    double corner[4][3], o[3], centre[3];
    for (int i = 0; i < 4; ++i) primaryRay(camera_, cx[i], cy[i], o, corner[i]);
    primaryRay(camera_, (x0 + x1 - 1) / 2, (y0 + y1 - 1) / 2, o, centre);
    double normal[4][3], normalLength[4];
    for (int i = 0; i < 4; ++i) {
      const double* a = corner[i];
      const double* b = corner[(i + 1) % 4];
      double* n = normal[i];
      n[0] = a[1] * b[2] - a[2] * b[1];
      n[1] = a[2] * b[0] - a[0] * b[2];
      n[2] = a[0] * b[1] - a[1] * b[0];
      if (n[0] * centre[0] + n[1] * centre[1] + n[2] * centre[2] < 0.0)
        for (int a2 = 0; a2 < 3; ++a2) n[a2] = -n[a2];
      normalLength[i] = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    for (const std::int32_t i : straddling_) {
      const double* tri = boundary_.triangles + 9 * static_cast<std::int64_t>(i);
      bool missesForward = false, missesBackward = false;
      for (int k = 0; k < 4; ++k) {
        bool allOutside = true, allInside = true;
        for (int v = 0; v < 3; ++v) {
          double q[3], qq = 0.0, s = 0.0;
          for (int a = 0; a < 3; ++a) {
            q[a] = tri[3 * v + a] - camera_.position[a];
            qq += q[a] * q[a];
            s += normal[k][a] * q[a];
          }
          const double margin = 1e-9 * normalLength[k] * std::sqrt(qq);
          allOutside = allOutside && s < -margin;
          allInside = allInside && s > margin;
        }
        missesForward = missesForward || allOutside;
        missesBackward = missesBackward || allInside;
      }
      if (!(missesForward && missesBackward))
        tryTriangle(nullptr, i, x0, y0, x1, y1, x0, y0, width, out);
    }
  }

  for (size_t p = 0; p < pixels; ++p) {
    int& n = out.count[p];
    if (n > kTileCrossings) {
      n = kStretchesNotGathered;
      continue;
    }
    BoundaryCrossing* c = &out.crossings[p * kTileCrossings];
    const int merged = mergeCrossings(c, n, boundary_.scale);
    n = intervalsOfCrossings(c, merged, &out.intervals[p * 2 * kMaxBoundaryIntervals],
                             kMaxBoundaryIntervals);
  }
}

}  // namespace mfadvr
