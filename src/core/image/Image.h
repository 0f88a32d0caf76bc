#pragma once
// Images as the renderer produces them (linear float RGBA) and as they are stored and compared
// (8-bit RGB or RGBA). Both keep row 0 at the top, x fastest, like PNG.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace mfadvr {

// Larger images are refused rather than attempted: 2^28 pixels is already 4 GiB of float RGBA.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 28;

// A rendered image: linear RGBA floats, row 0 at the TOP, x fastest. RGB is already composited
// over the background; alpha is the accumulated opacity.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;  // 4 * width * height
  // width * height ray distances (RenderSettings::depth), NaN where none; empty when not asked.
  std::vector<float> depth;

  Image() = default;
  // Zero-filled; throws mfadvr::Error on w <= 0, h <= 0 or more than kMaxImagePixels pixels.
  Image(int w, int h);

  float* pixel(int x, int y) { return rgba.data() + 4 * (static_cast<size_t>(y) * width + x); }
  const float* pixel(int x, int y) const {
    return rgba.data() + 4 * (static_cast<size_t>(y) * width + x);
  }
};

// 8-bit image, channels 3 (RGB) or 4 (RGBA), row 0 at the top.
struct Image8 {
  int width = 0, height = 0, channels = 3;
  std::vector<std::uint8_t> data;  // channels * width * height
};

// Rounds clamp(v, 0, 1) * 255 to nearest (NaN becomes 0). RGB, or RGBA with `withAlpha`.
Image8 toImage8(const Image& image, bool withAlpha = false);

// Throws mfadvr::Error (naming `what`) unless the image is non-empty, within kMaxImagePixels,
// has 3 or 4 channels and exactly channels * width * height bytes of data.
void checkImage8(const Image8& image, std::string_view what);

}  // namespace mfadvr
