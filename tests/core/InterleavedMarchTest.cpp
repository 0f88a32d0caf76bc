// The interleaved march in (kernel/InterleavedMarch.h) changes how rays share the processor,
// never what a ray computes: with empty-space skipping the renderer marches each group of
// kMarchGroup pixels of a row in together, and must give the image of integrateRay called pixel
// by pixel bit for bit, with the same counters (samples, skipped samples, terminated rays, rays
// that hit), for every degree (and mixed degrees), with and without a domain mask, shaded and
// unshaded, perspective and parallel cameras, steps from the box or aligned to the camera, ray
// ends, widths that leave pixels outside any group, and transfer functions that hide most of
// the volume, some of it, or all.
#include <gtest/gtest.h>

#include <cmath>

#include "core/FrameAgreement.h"
#include "core/field/ModelField.h"
#include "core/render/ModelKernelSwitch.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "gpu/GpuTestScenes.h"

namespace mfadvr {
namespace {

using namespace test;

TEST(InterleavedMarch, GroupsRenderTheImageAndCountersOfOneRayAtATime) {
  static_assert(marchesRaysApart<SplineRaySampler<3, true, true> >());
  static_assert(marchesRaysApart<SplineRaySampler<0, true, false> >());
  static_assert(!marchesRaysApart<SplineRaySampler<3, false, true> >());  // nothing to skip
  int renders = 0;
  std::int64_t skipped = 0, terminated = 0, samples = 0;
  const std::vector<TransferFunction> tfs = transferFunctions();
  // 0: the mixed-degree model; 4: a degree-3 model with a domain mask (samples outside it are
  // passed over uncounted, during the march too).
  for (int degree : {0, 1, 2, 3, 4})
    for (std::size_t f = 0; f < tfs.size(); ++f)
      for (bool shade : {false, true}) {
        const Model& m = degree == 0   ? mixedDegreeModel()
                         : degree == 4 ? maskedModel()
                                       : mlModel(degree);
        RenderSettings s = settingsFor(m.domain().min, m.domain().max, tfs[f], shade);
        ASSERT_TRUE(s.skipEmptySpace);
        // Vary what a group must get right, one variation per render (63: a width whose tiles'
        // last pixels go one at a time).
        varyFrame(s, renders % 4, 63);
        if (f == 0) s.sampleDistance = 0.037;  // steps that do not divide the segments
        const ModelField field(m);
        const ModelRenderSetup setup(field, s);
        const RenderStats rayStats = expectFrameOfRayByRay(s, setup, renders);
        skipped += rayStats.skipped;
        terminated += rayStats.terminated;
        samples += rayStats.samples;
        ++renders;
      }
  EXPECT_EQ(renders, 60);
  // The scenes exercise the march (skipped samples), rays that end on a visible sample and rays
  // that reach their end (the all-transparent transfer function).
  EXPECT_GT(skipped, 0);
  EXPECT_GT(terminated, 0);
  EXPECT_GT(samples, 0);
}

// marchIn itself: each ray of a group stops at its first sample outside empty cells (which
// integrateRay then evaluates first), having skipped exactly the samples before it; a ray that
// misses the box, or has only empty cells, is left as integrateRay would find it.
TEST(InterleavedMarch, EachRayStopsAtItsFirstSampleOutsideEmptyCells) {
  const Model& m = mlModel(3);
  // Visible only in a band of values: most cells empty, some rays through no visible cell.
  RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[2], false);
  s.width = 40;
  s.height = 30;
  const ModelField field(m);
  const ModelRenderSetup setup(field, s);
  ASSERT_NE(setup.view().empty, nullptr);
  const RayParams& rp = setup.params();
  SplineRaySampler<3, true, false> sampler(setup.view());
  constexpr int G = kMarchGroup;
  RayCounters counters;
  int stoppedInside = 0, ranOut = 0, missed = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x + G <= s.width; x += G) {
      RaySegment segment[G];
      const RaySegment* rays[G];
      for (int g = 0; g < G; ++g)
        rays[g] = raySegment(rp, x + g, y, segment[g]) ? &segment[g] : nullptr;
      RayStart start[G];
      marchIn<G, false>(rp, sampler, rays, start, counters);
      for (int g = 0; g < G; ++g) {
        if (!rays[g]) {
          EXPECT_EQ(start[g].k, 0);
          EXPECT_EQ(start[g].skipped, 0);
          ++missed;
          continue;
        }
        const RaySegment& ray = *rays[g];
        sampler.beginRay(ray);
        // Every step before start.k was skipped, and its sample lies in an empty cell.
        EXPECT_EQ(start[g].skipped, start[g].k);
        for (std::int64_t k = 0; k < start[g].k; ++k) {
          double p[3], length, tLeave;
          ASSERT_TRUE(stepSample(ray, k, rp.sampleDistance, p, length));
          EXPECT_TRUE(sampler.emptyAt(p, tLeave))
              << "pixel " << x + g << ", " << y << " step " << k;
        }
        if (start[g].k < ray.steps) {
          double p[3], length, tLeave;
          ASSERT_TRUE(stepSample(ray, start[g].k, rp.sampleDistance, p, length));
          EXPECT_FALSE(sampler.emptyAt(p, tLeave));
          ++stoppedInside;
        } else {
          EXPECT_EQ(start[g].k, ray.steps);
          ++ranOut;
        }
      }
    }
  EXPECT_GT(stoppedInside, 0);
  EXPECT_GT(ranOut, 0);
  EXPECT_GT(missed, 0);
}

}  // namespace
}  // namespace mfadvr
