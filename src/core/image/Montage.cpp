#include "core/image/Montage.h"

#include <algorithm>

#include "core/util/Error.h"

namespace mfadvr {

Image8 montageHorizontal(const std::vector<Image8>& images, int gap, std::uint8_t background) {
  if (images.empty()) throw Error("a montage needs at least one image");
  if (gap < 0) throw Error("montage gap must be >= 0");
  Image8 out;
  out.channels = 3;
  for (const auto& im : images) {
    out.width += im.width;
    out.height = std::max(out.height, im.height);
  }
  out.width += gap * static_cast<int>(images.size() - 1);
  out.data.assign(static_cast<size_t>(out.width) * out.height * 3, background);
  int x0 = 0;
  for (const auto& im : images) {
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        for (int c = 0; c < 3; ++c)
          out.data[(static_cast<size_t>(y) * out.width + x0 + x) * 3 + c] =
              im.data[(static_cast<size_t>(y) * im.width + x) * im.channels + c];
    x0 += im.width + gap;
  }
  return out;
}

}  // namespace mfadvr
