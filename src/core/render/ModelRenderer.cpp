// The MFA model's render path: the shared per-ray integration over SplineRaySampler, with the
// spline's degree, the domain mask, shading and empty-space skipping chosen once per render.
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {

Image renderModelView(const RenderSettings& settings, const RayParams& params,
                      const ModelView& view, RenderStats* stats) {
  Image image(settings.width, settings.height);
  const bool masked = view.mask.nodes != nullptr;
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
  return image;
}

Image renderModel(const ModelField& field, const RenderSettings& settings, RenderStats* stats) {
  const ModelRenderSetup setup(field, settings);
  Image image = renderModelView(settings, setup.params(), setup.view(), stats);
  if (stats) stats->seconds += setup.setupSeconds();
  return image;
}

}  // namespace mfadvr
