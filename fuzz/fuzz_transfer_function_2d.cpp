// libFuzzer target: the JSON box form of 2-D transfer functions (`render --tf2d FILE.json`),
// then the tables a render builds from what it accepts (the 1-D envelope, the 2-D entries).
#include <cstdint>
#include <string>

#include "core/render/ClassificationTables.h"
#include "core/util/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    mfadvr::RenderSettings s;
    s.transferFunction.space = mfadvr::TfSpace::Data;
    s.transferFunction.color = {{0.0, mfadvr::Vec3f::Ones()}};
    s.transferFunction.opacity = {{0.0, 1.0f}};
    s.transferFunction2D = mfadvr::parseTransferFunction2DJson(text, "fuzz");
    s.validate();
    const mfadvr::ClassificationTables tables(s);
    const mfadvr::GradientTransferView v = tables.gradientView();
    if (!v.table || v.width != s.transferFunction2D->width) __builtin_trap();
    const float g[3] = {1.0f, 0.0f, 0.0f};
    mfadvr::TfEntry e{};
    float factor;
    v.apply(0.5f, g, e, factor);
    if (!(e.alpha >= 0.0f && e.alpha <= 1.0f)) __builtin_trap();
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
