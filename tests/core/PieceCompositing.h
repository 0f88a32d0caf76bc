#pragma once
// Test helper: compositing the images of the pieces of a partitioned volume.
#include <algorithm>
#include <utility>
#include <vector>

#include "core/image/Image.h"
#include "core/render/Camera.h"
#include "core/render/RenderSettings.h"
#include "core/render/kernel/CameraRays.h"

namespace mfadvr::test {

// What a compositor (IceT in ParaView) does with the pieces of a partitioned volume: per pixel,
// the premultiplied images of the pieces blended front to back in the order the ray meets them.
inline Image compositePieces(const RenderSettings& s, const std::vector<std::pair<Vec3d, Vec3d>>& boxes,
                      const std::vector<Image>& pieces) {
  Image out(s.width, s.height);
  const RayGenerator rays(s.camera, s.width, s.height);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      Vec3d o, d;
      rays.ray(x, y, o, d);
      std::vector<std::pair<double, size_t>> order;
      for (size_t i = 0; i < boxes.size(); ++i) {
        const double lo[3] = {boxes[i].first[0], boxes[i].first[1], boxes[i].first[2]};
        const double hi[3] = {boxes[i].second[0], boxes[i].second[1], boxes[i].second[2]};
        const double oo[3] = {o[0], o[1], o[2]}, dd[3] = {d[0], d[1], d[2]};
        double t0, t1;
        if (intersectBox(oo, dd, lo, hi, t0, t1)) order.push_back({t0, i});
      }
      std::sort(order.begin(), order.end());
      float* acc = out.pixel(x, y);
      for (const auto& [t, i] : order) {
        const float* p = pieces[i].pixel(x, y);
        const float behind = 1.0f - acc[3];
        for (int c = 0; c < 4; ++c) acc[c] += behind * p[c];
      }
    }
  return out;
}

}  // namespace mfadvr::test
