// The MFA model's render path: the shared per-ray integration over SplineRaySampler, with the
// spline's degree, the domain mask, shading and empty-space skipping chosen once per render.
#include <chrono>

#include "core/render/EmptySpaceGrid.h"
#include "core/render/RayCaster.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {

Image renderModel(const ModelField& field, const RenderSettings& settings, RenderStats* stats) {
  settings.validate();
  const Model& model = field.model();
  const TransferFunctionTable table(
      settings.transferFunction,
      OpacityCorrection(settings.sampleDistance / settings.opacityUnitDistance));
  const RayParams params =
      compileRayParams(settings, table, model.domain().min, model.domain().max);

  ModelView view;
  view.spline = model.spline().view();
  const Vec3d extent = model.domain().extent();
  for (int a = 0; a < 3; ++a) {
    view.boxMin[a] = model.domain().min[a];
    view.inverseExtent[a] = 1.0 / extent[a];
  }
  view.mask = model.mask().view();
  std::shared_ptr<const EmptySpaceFlags> flags;
  // The flags' (re)build is part of the frame: its time is added to the ray casting's.
  const auto setupStart = std::chrono::steady_clock::now();
  if (settings.skipEmptySpace) {
    EmptySpaceCache local;
    EmptySpaceCache& cache = field.emptySpaceCache() ? *field.emptySpaceCache() : local;
    flags = cache.flags(model.spline(), table);
    // Nothing to skip: the loop without the per-sample test.
    if (flags->emptyCells > 0) {
      view.empty = flags->cells.data();
      view.emptyBlocks = flags->blocks.data();
      for (int a = 0; a < 3; ++a) view.blocks[a] = flags->blockCounts[a];
    }
  }
  const double setupSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - setupStart).count();

  Image image(settings.width, settings.height);
  const bool masked = !model.mask().empty();
  const bool skip = view.empty != nullptr;
  splineDegreeSwitch(view.spline, [&]<int P>() {
    auto cast = [&]<bool Masked, bool Shade, bool Skip>() {
      castRays<Masked, Shade>(
          settings, params, [&] { return SplineRaySampler<P, Skip, Shade>(view); }, image, stats);
    };
    // Eight loops per degree: with and without the mask test, shading and skipping.
    auto withSkip = [&]<bool Masked, bool Shade>() {
      if (skip)
        cast.template operator()<Masked, Shade, true>();
      else
        cast.template operator()<Masked, Shade, false>();
    };
    auto withShade = [&]<bool Masked>() {
      if (settings.shade)
        withSkip.template operator()<Masked, true>();
      else
        withSkip.template operator()<Masked, false>();
    };
    if (masked)
      withShade.template operator()<true>();
    else
      withShade.template operator()<false>();
  });
  if (stats) stats->seconds += setupSeconds;
  return image;
}

}  // namespace mfadvr
