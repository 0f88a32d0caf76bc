#include "core/image/ImageResize.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

// For each output coordinate: the two source indices and the weight of the second.
struct Tap {
  int i0, i1;
  float w;
};

std::vector<Tap> taps(int from, int to) {
  std::vector<Tap> t(static_cast<size_t>(to));
  const double scale = static_cast<double>(from) / to;
  for (int x = 0; x < to; ++x) {
    const double s = std::clamp((x + 0.5) * scale - 0.5, 0.0, static_cast<double>(from - 1));
    const int i0 = std::min(static_cast<int>(s), from - 1);
    t[x] = {i0, std::min(i0 + 1, from - 1), static_cast<float>(s - i0)};
  }
  return t;
}

}  // namespace

Image resizeBilinear(const Image& source, int width, int height) {
  if (source.width <= 0 || source.height <= 0 ||
      source.rgba.size() != 4 * static_cast<size_t>(source.width) * source.height)
    throw Error("cannot resize an empty image");
  Image out(width, height);
  if (width == source.width && height == source.height) {
    out.rgba = source.rgba;
    return out;
  }
  const std::vector<Tap> tx = taps(source.width, width), ty = taps(source.height, height);
  for (int y = 0; y < height; ++y) {
    const Tap& v = ty[y];
    for (int x = 0; x < width; ++x) {
      const Tap& h = tx[x];
      const float* a = source.pixel(h.i0, v.i0);
      const float* b = source.pixel(h.i1, v.i0);
      const float* c = source.pixel(h.i0, v.i1);
      const float* d = source.pixel(h.i1, v.i1);
      float* o = out.pixel(x, y);
      for (int ch = 0; ch < 4; ++ch) {
        const float top = a[ch] + h.w * (b[ch] - a[ch]);
        const float bottom = c[ch] + h.w * (d[ch] - c[ch]);
        o[ch] = top + v.w * (bottom - top);
      }
    }
  }
  return out;
}

}  // namespace mfadvr
