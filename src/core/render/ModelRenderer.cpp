// The MFA model's render path: the shared per-ray integration over SplineRaySampler, with the
// spline's degree, the domain mask, shading and empty-space skipping chosen once per render
// (ModelKernelSwitch.h).
#include "core/render/ModelKernelSwitch.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {

Image renderModelView(const RenderSettings& settings, const RayParams& params,
                      const ModelView& view, RenderStats* stats) {
  Image image(settings.width, settings.height);
  modelKernelSwitch(view, settings.shade, [&]<int P, bool Masked, bool Shade, bool Skip>() {
    castRays<Masked, Shade>(
        settings, params, [&] { return SplineRaySampler<P, Skip, Shade>(view); }, image, stats);
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
