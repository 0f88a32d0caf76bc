// libFuzzer target: the JSON box forms of 2-D transfer functions (`render --tf2d FILE.json`)
// and of curvature transfer functions (`render --curvature-tf FILE.json`), each input read as
// both, then the tables a render builds from what they accept (the 1-D envelope, the 2-D
// entries, the curvature entries).
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
  try {
    mfadvr::RenderSettings s;
    s.curvatureTransferFunction = mfadvr::parseCurvatureTransferFunctionJson(text, "fuzz");
    s.validate();
    const mfadvr::ClassificationTables tables(s);
    const mfadvr::CurvatureTransferView v = tables.curvatureView(s.primaryRays());
    if (!v.table || v.width != s.curvatureTransferFunction->width) __builtin_trap();
    const float g[3] = {0.0f, 0.0f, -1.0f}, h[6] = {-1.0f, 0.0f, 0.0f, -2.0f, 0.0f, 0.0f};
    const double d[3] = {0.0, 0.0, -1.0};
    float c[3] = {1.0f, 1.0f, 1.0f}, factor = 1.0f, contour;
    v.apply(g, h, d, 1.0, c, factor, contour);
    if (!(factor >= 0.0f && factor <= 1.0f && c[0] >= 0.0f && c[0] <= 1.0f)) __builtin_trap();
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
