// Ray packets (kernel/RayPacketIntegrator.h) change how rays share the processor, never what a
// ray computes: the renderer, which takes rows of eight pixels as one packet where it can, gives
// the image of integrateRay called pixel by pixel bit for bit, and the same counters, for every
// degree with a lane kernel, shaded and unshaded, perspective and parallel cameras, steps from
// the box or aligned to the camera, ray ends, image widths that leave pixels outside any packet,
// and transfer functions that make rays terminate early or never.
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

TEST(RayPacket, PacketsRenderTheImageAndCountersOfOneRayAtATime) {
#if !defined(MFADVR_SPLINE_LANE_KERNEL)
  GTEST_SKIP() << "this build has no lane kernel (needs AVX2 and FMA): no ray packets";
#else
  static_assert(takesRayPackets<SplineRaySampler<1, false, false> >());
  static_assert(takesRayPackets<SplineRaySampler<2, false, true> >());
  static_assert(takesRayPackets<SplineRaySampler<3, false, true> >());
  // Skipping and masks take no packets (skipping marches rays in groups, InterleavedMarchTest).
  static_assert(!takesRayPackets<SplineRaySampler<2, true, false> >());
  int renders = 0;
  std::int64_t terminated = 0, samples = 0;
  const std::vector<TransferFunction> tfs = transferFunctions();
  for (int degree : {1, 2, 3})
    for (std::size_t f = 0; f < tfs.size(); ++f)
      for (bool shade : {false, true}) {
        const Model& m = mlModel(degree);
        RenderSettings s = settingsFor(m.domain().min, m.domain().max, tfs[f], shade);
        s.skipEmptySpace = false;  // else the renderer takes one ray at a time
        // Vary what a packet must get right, one variation per render (61: a width whose tiles'
        // last pixels go one at a time).
        varyFrame(s, renders % 4, 61);
        if (f == 0) s.sampleDistance = 0.037;  // steps that do not divide the segments
        const ModelField field(m);
        const ModelRenderSetup setup(field, s);
        ASSERT_EQ(setup.view().empty, nullptr);
        const RenderStats rayStats = expectFrameOfRayByRay(s, setup, renders);
        terminated += rayStats.terminated;
        samples += rayStats.samples;
        ++renders;
      }
  EXPECT_EQ(renders, 36);
  // The scenes exercise early termination (lanes ending before their packet).
  EXPECT_GT(terminated, 0);
  EXPECT_GT(samples, 0);
#endif
}

}  // namespace
}  // namespace mfadvr
