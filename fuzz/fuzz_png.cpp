// libFuzzer target: the PNG reader must turn any byte string into an image or an Error.
#include <cstdint>
#include <span>

#include "core/image/PngFile.h"
#include "core/util/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  try {
    const mfadvr::Image8 im = mfadvr::decodePng(std::span<const std::uint8_t>(data, size));
    mfadvr::checkImage8(im, "decoded");
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
