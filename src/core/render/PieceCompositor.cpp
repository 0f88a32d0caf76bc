#include "core/render/PieceCompositor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include <Eigen/LU>

#include "core/render/Camera.h"
#include "core/render/kernel/CameraRays.h"
#include "core/util/Error.h"

namespace mfadvr {

Image compositeInVisibilityOrder(const RenderSettings& s, const std::vector<DomainBox>& regions,
                                 const std::vector<Image>& images) {
  if (regions.size() != images.size())
    throw Error("internal: one image per region is needed to composite pieces");
  for (const Image& im : images)
    if (im.width != s.width || im.height != s.height)
      throw Error("internal: piece images must have the render's size");
  Image out(s.width, s.height);
  const CameraRays rays = s.primaryRays();
  std::vector<std::pair<double, size_t>> order;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      double oo[3], dd[3];
      primaryRay(rays, x, y, oo, dd);
      order.clear();
      for (size_t i = 0; i < regions.size(); ++i) {
        const double lo[3] = {regions[i].min[0], regions[i].min[1], regions[i].min[2]};
        const double hi[3] = {regions[i].max[0], regions[i].max[1], regions[i].max[2]};
        double t0, t1;
        if (intersectBox(oo, dd, lo, hi, t0, t1)) order.push_back({t0, i});
      }
      std::sort(order.begin(), order.end());
      float* acc = out.pixel(x, y);
      for (const auto& [t, i] : order) {
        const float* p = images[i].pixel(x, y);
        const float behind = 1.0f - acc[3];
        for (int c = 0; c < 4; ++c) acc[c] += behind * p[c];
      }
    }
  return out;
}

std::vector<size_t> gridVisibilityOrder(const RenderSettings& settings,
                                        const std::vector<DomainBox>& regions) {
  // Each axis's faces, and each region's cell on it.
  std::vector<double> faces[3];
  for (int a = 0; a < 3; ++a) {
    for (const DomainBox& r : regions) {
      faces[a].push_back(r.min[a]);
      faces[a].push_back(r.max[a]);
    }
    std::sort(faces[a].begin(), faces[a].end());
    faces[a].erase(std::unique(faces[a].begin(), faces[a].end()), faces[a].end());
  }
  std::vector<std::array<std::int64_t, 3>> cells(regions.size());
  for (size_t i = 0; i < regions.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      const auto lo = std::lower_bound(faces[a].begin(), faces[a].end(), regions[i].min[a]);
      const auto hi = std::lower_bound(faces[a].begin(), faces[a].end(), regions[i].max[a]);
      if (hi - lo != 1) return {};  // spans a face of another region: not a grid's cell
      cells[i][a] = lo - faces[a].begin();
    }
  {
    std::vector<std::array<std::int64_t, 3>> sorted = cells;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return {};
  }
  // Per axis, the camera's cell (-1 before the first face, the cell count after the last);
  // parallel rays all go one way: the cells are counted from the side they come from.
  const CameraRays rays = settings.primaryRays();
  std::vector<std::pair<std::int64_t, size_t>> keyed(regions.size());
  for (size_t i = 0; i < regions.size(); ++i) {
    std::int64_t key = 0;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t n = std::int64_t(faces[a].size()) - 1, c = cells[i][a];
      if (rays.parallel) {
        key += rays.forward[a] > 0.0 ? c : rays.forward[a] < 0.0 ? n - 1 - c : 0;
      } else {
        const std::int64_t camera =
            std::upper_bound(faces[a].begin(), faces[a].end(), rays.position[a]) -
            faces[a].begin() - 1;
        key += c > camera ? c - camera : camera - c;
      }
    }
    keyed[i] = {key, i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<size_t> order;
  for (const auto& [key, i] : keyed) order.push_back(i);
  return order;
}

PixelRect projectedPixels(const CameraRays& rays, const DomainBox& region) {
  PixelRect r{0, rays.width - 1, 0, rays.height - 1};
  // A point p is position + a forward + b right + c up (the rays' vectors need not be
  // orthogonal or unit: a host's frustum may be skewed). Perspective: p is on the ray of image
  // coordinates (b / a, c / a), in front when a > 0; parallel: (b, c).
  Eigen::Matrix3d basis;
  basis << rays.forward[0], rays.right[0], rays.up[0], rays.forward[1], rays.right[1], rays.up[1],
      rays.forward[2], rays.right[2], rays.up[2];
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(basis);
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  bool projected = lu.isInvertible();
  for (int corner = 0; corner < 8 && projected; ++corner) {
    Vec3d v;
    for (int k = 0; k < 3; ++k)
      v[k] = ((corner >> k) & 1 ? region.max[k] : region.min[k]) - rays.position[k];
    const Vec3d abc = lu.solve(v);
    const double a = abc[0], b = abc[1], c = abc[2];
    if (!rays.parallel && !(a > 0.0)) projected = false;
    const double scale = rays.parallel ? 1.0 : 1.0 / a;
    const double p[2] = {b * scale, c * scale};
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  if (projected && std::isfinite(lo[0] + lo[1] + hi[0] + hi[1])) {
    // primaryRay's pixel centres: sx = (2 (x + 1/2) / width - 1) halfWidth, sy likewise with y
    // downwards; two pixels of margin for rounding.
    auto column = [&](double sx) { return (sx / rays.halfWidth + 1.0) * 0.5 * rays.width - 0.5; };
    auto row = [&](double sy) { return (1.0 - sy / rays.halfHeight) * 0.5 * rays.height - 0.5; };
    r.x0 = static_cast<int>(std::clamp(std::floor(column(lo[0])) - 2.0, 0.0, double(rays.width)));
    r.x1 = static_cast<int>(std::clamp(std::ceil(column(hi[0])) + 2.0, -1.0, rays.width - 1.0));
    r.y0 = static_cast<int>(std::clamp(std::floor(row(hi[1])) - 2.0, 0.0, double(rays.height)));
    r.y1 = static_cast<int>(std::clamp(std::ceil(row(lo[1])) + 2.0, -1.0, rays.height - 1.0));
  }
  return r;
}

std::int64_t raysStillGoing(const CameraRays& rays, const std::vector<float>& ends,
                            const DomainBox& region) {
  const PixelRect r = projectedPixels(rays, region);
  if (ends.empty()) return r.count();
  std::int64_t n = 0;
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) n += ends[static_cast<size_t>(y) * rays.width + x] > 0.0f;
  return n;
}

namespace {

// Whether a ray of `rays` that does not end at once (ends: none, or > 0) crosses `region` before
// its end. Only the pixels onto which the region's corners project are tested.
bool anyRayCrosses(const CameraRays& rays, const std::vector<float>& ends,
                   const DomainBox& region) {
  const PixelRect r = projectedPixels(rays, region);
  const double boxLo[3] = {region.min[0], region.min[1], region.min[2]};
  const double boxHi[3] = {region.max[0], region.max[1], region.max[2]};
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) {
      const double end = ends.empty() ? INFINITY : ends[static_cast<size_t>(y) * rays.width + x];
      if (!(end > 0.0)) continue;
      double o[3], d[3], tEnter, tExit;
      primaryRay(rays, x, y, o, d);
      if (intersectBox(o, d, boxLo, boxHi, tEnter, tExit) && tExit > std::max(tEnter, 0.0) &&
          tEnter < end)
        return true;
    }
  return false;
}

}  // namespace

Image renderPieces(const RenderSettings& settings, const std::vector<DomainBox>& regions,
                   const PieceRenderer& renderPiece, RenderStats* stats) {
  // The pieces' images are composited front to back: only composite renders combine so, and
  // a depth would need the pieces' opacities in order.
  if (regions.size() > 1 && settings.blend != BlendMode::Composite)
    throw Error(std::string("the ") + blendModeName(settings.blend) +
                " blend renders one-piece models only (this one has " +
                std::to_string(regions.size()) + " pieces); use the composite blend");
  if (regions.size() > 1 && settings.depth)
    throw Error("a depth image is made for one-piece models only (this one has " +
                std::to_string(regions.size()) + " pieces)");
  RenderSettings piece = settings;
  piece.alignSamplesToCamera = true;
  piece.background = Vec3f::Zero();
  piece.progress = nullptr;
  std::vector<size_t> order =
      regions.size() > 1 ? gridVisibilityOrder(settings, regions) : std::vector<size_t>{};
  const bool inOrder = !order.empty();
  if (!inOrder)
    for (size_t i = 0; i < regions.size(); ++i) order.push_back(i);
  std::vector<Image> images;
  RenderStats total;
  // In order, a pixel whose composite has reached the early-termination opacity ends its ray
  // before the pieces behind (piece.rayEnd 0 there), as a ray through the whole volume would
  // stop; a piece that no ray still going crosses is not rendered at all (nor, by a caller that
  // reads pieces as they are rendered, read).
  const CameraRays rays = settings.primaryRays();
  const float stop = static_cast<float>(settings.earlyTerminationOpacity);
  bool anyStopped = false;
  for (size_t k = 0; k < order.size(); ++k) {
    const size_t i = order[k];
    if (anyStopped && !anyRayCrosses(rays, piece.rayEnd, regions[i])) {
      if (settings.progress) settings.progress(double(k + 1) / double(regions.size()));
      continue;
    }
    piece.clipBox = regions[i];
    RenderStats pieceStats;
    Image image = renderPiece(i, piece, &pieceStats);
    if (!inOrder || k == 0) {
      images.push_back(std::move(image));
    } else {
      // Front to back, as compositeInVisibilityOrder does for the pieces a ray meets; a piece
      // the ray misses is 0 there and leaves the pixel as it is.
      if (image.width != settings.width || image.height != settings.height)
        throw Error("internal: piece images must have the render's size");
      float* acc = images.front().rgba.data();
      const float* p = image.rgba.data();
      for (size_t q = 0; q < image.rgba.size(); q += 4) {
        const float behind = 1.0f - acc[q + 3];
        for (int c = 0; c < 4; ++c) acc[q + c] += behind * p[q + c];
      }
    }
    if (inOrder) {
      const std::vector<float>& acc = images.front().rgba;
      for (size_t q = 0; q < acc.size() / 4; ++q)
        if (acc[4 * q + 3] >= stop && (piece.rayEnd.empty() || piece.rayEnd[q] > 0.0f)) {
          if (piece.rayEnd.empty()) piece.rayEnd.assign(acc.size() / 4, INFINITY);
          piece.rayEnd[q] = 0.0f;
          anyStopped = true;
        }
    }
    total.seconds += pieceStats.seconds;
    total.rays = pieceStats.rays;
    total.raysHit += pieceStats.raysHit;
    total.samples += pieceStats.samples;
    total.terminated += pieceStats.terminated;
    total.skipped += pieceStats.skipped;
    if (settings.progress) settings.progress(double(k + 1) / double(regions.size()));
  }
  if (stats) *stats = total;
  // A single piece, or the pieces composited in order, are already the composite.
  return images.size() == 1 ? std::move(images.front())
                            : compositeInVisibilityOrder(settings, regions, images);
}

void compositeOverBackground(Image& image, const Vec3f& background) {
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      float* p = image.pixel(x, y);
      const float behind = 1.0f - p[3];
      for (int c = 0; c < 3; ++c) p[c] += behind * background[c];
    }
}

}  // namespace mfadvr
