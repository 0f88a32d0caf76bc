#include "core/image/Image.h"

#include <cmath>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

bool validSize(std::int64_t w, std::int64_t h) {
  return w > 0 && h > 0 && w <= kMaxImagePixels / h;
}

std::string sizeText(std::int64_t w, std::int64_t h) {
  return std::to_string(w) + " x " + std::to_string(h);
}

std::uint8_t toByte(float v) {
  // Written so that NaN fails both tests and lands on 0.
  if (!(v > 0.0f)) return 0;
  if (!(v < 1.0f)) return 255;
  return static_cast<std::uint8_t>(std::lround(static_cast<double>(v) * 255.0));
}

}  // namespace

Image::Image(int w, int h) {
  if (!validSize(w, h))
    throw Error("invalid image size " + sizeText(w, h) + " (each side must be positive, at most " +
                std::to_string(kMaxImagePixels) + " pixels in all)");
  width = w;
  height = h;
  rgba.assign(4 * static_cast<size_t>(w) * static_cast<size_t>(h), 0.0f);
}

Image8 toImage8(const Image& image, bool withAlpha) {
  if (!validSize(image.width, image.height) ||
      image.rgba.size() != 4 * static_cast<size_t>(image.width) * image.height)
    throw Error("toImage8: inconsistent image (" + sizeText(image.width, image.height) + ", " +
                std::to_string(image.rgba.size()) + " floats)");
  Image8 out;
  out.width = image.width;
  out.height = image.height;
  out.channels = withAlpha ? 4 : 3;
  const size_t n = static_cast<size_t>(image.width) * image.height;
  out.data.resize(n * out.channels);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < out.channels; ++c)
      out.data[i * out.channels + c] = toByte(image.rgba[4 * i + c]);
  return out;
}

void checkImage8(const Image8& image, std::string_view what) {
  const std::string name(what);
  if (!validSize(image.width, image.height))
    throw Error(name + ": invalid image size " + sizeText(image.width, image.height));
  if (image.channels != 3 && image.channels != 4)
    throw Error(name + ": " + std::to_string(image.channels) + " channels (expected 3 or 4)");
  const size_t expected =
      static_cast<size_t>(image.channels) * static_cast<size_t>(image.width) * image.height;
  if (image.data.size() != expected)
    throw Error(name + ": " + std::to_string(image.data.size()) + " bytes of pixel data for a " +
                sizeText(image.width, image.height) + " image with " +
                std::to_string(image.channels) + " channels (expected " + std::to_string(expected) +
                ")");
}

}  // namespace mfadvr
