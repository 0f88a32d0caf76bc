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

Image8 montageGrid(const std::vector<std::vector<Image8>>& rows, int gap, std::uint8_t background) {
  if (rows.empty()) throw Error("a montage needs at least one row");
  std::vector<Image8> lines;
  for (const auto& row : rows) lines.push_back(montageHorizontal(row, gap, background));
  int width = 0, height = gap * static_cast<int>(lines.size() - 1);
  for (const auto& l : lines) {
    width = std::max(width, l.width);
    height += l.height;
  }
  Image8 out;
  out.width = width;
  out.height = height;
  out.channels = 3;
  out.data.assign(std::size_t(width) * height * 3, background);
  int y0 = 0;
  for (const auto& l : lines) {
    for (int y = 0; y < l.height; ++y)
      std::copy_n(&l.data[std::size_t(y) * l.width * 3], std::size_t(l.width) * 3,
                  &out.data[(std::size_t(y0 + y) * width) * 3]);
    y0 += l.height + gap;
  }
  return out;
}

}  // namespace mfadvr
