#include "core/FrameAgreement.h"

#include <stdexcept>
#include <string>

#include "core/render/ModelKernelSwitch.h"

namespace mfadvr::test {

void requireReferenceDegree(const ModelView& view) {
  const int p = view.spline.axis[0].degree;
  if (p > kReferenceMaxDegree && p == view.spline.axis[1].degree &&
      p == view.spline.axis[2].degree && p <= kMaxUnrolledDegree)
    throw std::invalid_argument("the reference loops are compiled for degrees up to " +
                                std::to_string(kReferenceMaxDegree) + ", not " +
                                std::to_string(p));
}

Image renderRayByRay(const RenderSettings& s, const ModelRenderSetup& setup, RenderStats& stats) {
  Image image(s.width, s.height);
  RayCounters counters;
  const ModelView& view = setup.view();
  requireReferenceDegree(view);
  modelKernelSwitch<kReferenceMaxDegree>(view, s.needsGradients(), [&]<int P, bool Masked, bool Shade, bool Skip>() {
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
