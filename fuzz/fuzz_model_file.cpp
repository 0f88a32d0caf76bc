// libFuzzer target: the .mfa loader must turn any byte string into a model or an Error.
#include <cstdint>
#include <span>

#include "core/model/ModelFile.h"
#include "core/util/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  try {
    const mfadvr::Model m = mfadvr::parseModel(std::span<const std::uint8_t>(data, size));
    (void)m.valueGradient(mfadvr::Vec3d::Zero());
    (void)m.inside(mfadvr::Vec3d::Zero());
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
