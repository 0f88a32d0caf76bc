// libFuzzer target: the .mfa loaders (one model, multi-block) must turn any byte string into
// models or an Error.
#include <cstdint>
#include <span>

#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  try {
    const mfadvr::Model m = mfadvr::parseModel(std::span<const std::uint8_t>(data, size));
    (void)m.valueGradient(mfadvr::Vec3d::Zero());
    (void)m.inside(mfadvr::Vec3d::Zero());
  } catch (const mfadvr::Error&) {
  }
  try {
    for (const auto& b : mfadvr::parseBlockModels(std::span<const std::uint8_t>(data, size)))
      (void)b.model.value(b.region.min);
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
