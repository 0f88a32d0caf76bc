#include "core/image/FloatImageFile.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "core/util/AtomicFile.h"
#include "core/util/Error.h"

namespace mfadvr {

namespace {

// `values` after `header`, as little-endian float32.
std::string withFloats(std::string header, const std::vector<float>& values) {
  const size_t start = header.size();
  header.resize(start + values.size() * sizeof(float));
  char* out = header.data() + start;
  for (size_t i = 0; i < values.size(); ++i) {
    std::uint32_t bits = std::bit_cast<std::uint32_t>(values[i]);
    if constexpr (std::endian::native == std::endian::big)
      bits = (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
    std::memcpy(out + i * sizeof(float), &bits, sizeof bits);
  }
  return header;
}

}  // namespace

void writeDepthImage(const std::string& path, const Image& image, const std::string& rule) {
  const size_t count = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.width <= 0 || image.height <= 0 || image.depth.size() != count)
    throw Error("cannot write " + path + ": the render kept no depth for this image");
  const std::string header = "NRRD0004\n# mfadvr depth: " + rule +
                             "; NaN: none; x fastest, row 0 at the top\n"
                             "type: float\n"
                             "dimension: 2\n"
                             "sizes: " +
                             std::to_string(image.width) + " " + std::to_string(image.height) +
                             "\n"
                             "kinds: space space\n"
                             "encoding: raw\n"
                             "endian: little\n"
                             "\n";
  writeFileAtomically(path, withFloats(header, image.depth));
}

void writeFloatImage(const std::string& path, const Image& image) {
  const size_t count = 4 * static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.width <= 0 || image.height <= 0 || image.rgba.size() != count)
    throw Error("cannot write " + path + ": inconsistent image (" + std::to_string(image.width) +
                " x " + std::to_string(image.height) + ", " + std::to_string(image.rgba.size()) +
                " floats)");
  std::string bytes =
      "NRRD0004\n"
      "# mfadvr image: channels are linear RGBA (RGB composited over the background, A the "
      "accumulated opacity); x fastest, row 0 at the top\n"
      "type: float\n"
      "dimension: 3\n"
      "sizes: 4 " +
      std::to_string(image.width) + " " + std::to_string(image.height) +
      "\n"
      "kinds: RGBA-color space space\n"
      "encoding: raw\n"
      "endian: little\n"
      "\n";
  writeFileAtomically(path, withFloats(std::move(bytes), image.rgba));
}

}  // namespace mfadvr
