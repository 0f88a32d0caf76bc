// libFuzzer target: the point-list parser of `mfadvr query --points`.
#include <cstdint>
#include <string_view>

#include "core/util/Error.h"
#include "core/util/PointList.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  try {
    (void)mfadvr::parsePointList(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
