// libFuzzer target: the point-list parsers of `mfadvr query --points` ("x y z") and of
// scattered text inputs ("x y z v").
#include <cstdint>
#include <string_view>

#include "core/util/Error.h"
#include "core/util/PointList.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)mfadvr::parsePointList(text);
  } catch (const mfadvr::Error&) {
  }
  try {
    const mfadvr::ScatteredData d = mfadvr::parsePointValueList(text);
    if (d.points.size() != d.values.size() || d.points.empty()) __builtin_trap();
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
