#include "core/render/PieceCompositor.h"

#include <algorithm>
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

Image renderPieces(const RenderSettings& settings, const std::vector<DomainBox>& regions,
                   const PieceRenderer& renderPiece, RenderStats* stats) {
  RenderSettings piece = settings;
  piece.alignSamplesToCamera = true;
  piece.background = Vec3f::Zero();
  piece.progress = nullptr;
  std::vector<Image> images;
  RenderStats total;
  for (size_t i = 0; i < regions.size(); ++i) {
    piece.clipBox = regions[i];
    RenderStats pieceStats;
    images.push_back(renderPiece(i, piece, &pieceStats));
    total.seconds += pieceStats.seconds;
    total.rays = pieceStats.rays;
    total.raysHit += pieceStats.raysHit;
    total.samples += pieceStats.samples;
    total.terminated += pieceStats.terminated;
    total.skipped += pieceStats.skipped;
    if (settings.progress) settings.progress(double(i + 1) / double(regions.size()));
  }
  if (stats) *stats = total;
  // A single piece is already its own composite.
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
