// libFuzzer target: the .mfa loaders (one model, multi-block, time-varying; copying or using
// the bytes in place; the header summary) must turn any byte string into models or an Error. The
// files' checksums keep mutations away from the coded control points, so the input is also read as
// a coded section of its own: a selector byte (bit 7: zfp, else lossless; bits 0-6: the control
// grid 5 x 4 x (1 + bits % 8)) and the payload.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/model/BlockModelFile.h"
#include "core/model/ControlCoding.h"
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
    // In place: the model holds the only owner of its bytes when it is queried.
    auto owned = std::make_shared<std::vector<std::uint8_t>>(data, data + size);
    const std::span<const std::uint8_t> view(*owned);
    const mfadvr::Model m = mfadvr::parseModel(view, "fuzz", nullptr, std::move(owned));
    (void)m.valueGradient(mfadvr::Vec3d::Ones());
  } catch (const mfadvr::Error&) {
  }
  try {
    // Time-varying files (format version 4): every instant, and the 4-D spline directly.
    const mfadvr::TimeVaryingModel m =
        mfadvr::parseTimeVaryingModel(std::span<const std::uint8_t>(data, size));
    (void)m.at(0.5).value(mfadvr::Vec3d::Zero());
    const mfadvr::Vec3d p = mfadvr::Vec3d::Zero();
    const double t = 0.25;
    float v = 0.0f, rate = 0.0f;
    mfadvr::Vec3f g;
    m.evaluate({&p, 1}, {&t, 1}, {&v, 1}, {&g, 1}, {&rate, 1});
  } catch (const mfadvr::Error&) {
  }
  try {
    (void)mfadvr::summarizeModelHead(std::span<const std::uint8_t>(data, size), size, "fuzz");
  } catch (const mfadvr::Error&) {
  }
  if (size >= 1) {
    const bool zfp = (data[0] & 0x80) != 0;
    const mfadvr::Index3 dims{5, 4, 1 + (data[0] & 0x7f) % 8};
    const mfadvr::ControlCoding coding{
        zfp ? mfadvr::ControlCoder::kZfp : mfadvr::ControlCoder::kLossless, 1e-3};
    try {
      const auto ctrl = mfadvr::decodeControlPoints(
          std::span<const std::uint8_t>(data + 1, size - 1), dims, coding);
      if (ctrl.size() != static_cast<size_t>(dims[0] * dims[1] * dims[2])) __builtin_trap();
    } catch (const mfadvr::Error&) {
    }
  }
  try {
    for (const auto& b : mfadvr::parseBlockModels(std::span<const std::uint8_t>(data, size)))
      (void)b.model.value(b.region.min);
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
