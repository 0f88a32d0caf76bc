#include "core/FrameAgreement.h"

#include "core/render/ModelKernelSwitch.h"

namespace mfadvr::test {

Image renderRayByRay(const RenderSettings& s, const ModelRenderSetup& setup, RenderStats& stats) {
  Image image(s.width, s.height);
  RayCounters counters;
  const ModelView& view = setup.view();
  modelKernelSwitch(view, s.needsGradients(), [&]<int P, bool Masked, bool Shade, bool Skip>() {
    SplineRaySampler<P, Skip, Shade> sampler(view);
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x)
        integrateRay<Masked, Shade>(setup.params(), sampler, x, y, image.pixel(x, y), counters);
  });
  stats.samples = counters.samples;
  stats.skipped = counters.skipped;
  stats.terminated = counters.terminated;
  stats.raysHit = counters.hits;
  return image;
}

}  // namespace mfadvr::test
