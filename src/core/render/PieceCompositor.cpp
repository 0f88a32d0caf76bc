#include "core/render/PieceCompositor.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

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

Image renderPieces(const RenderSettings& settings, const std::vector<DomainBox>& regions,
                   const PieceRenderer& renderPiece, RenderStats* stats) {
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
  for (size_t k = 0; k < order.size(); ++k) {
    const size_t i = order[k];
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
