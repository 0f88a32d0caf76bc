// Ray packets (kernel/RayPacketIntegrator.h) change how rays share the processor, never what a
// ray computes: the renderer, which takes rows of eight pixels as one packet where it can, gives
// the image of integrateRay called pixel by pixel bit for bit, and the same counters, for every
// degree with a lane kernel, shaded and unshaded, perspective and parallel cameras, steps from
// the box or aligned to the camera, ray ends, image widths that leave pixels outside any packet,
// and transfer functions that make rays terminate early or never; with a domain mask or a mesh's
// exact boundary too, whose packets take only the samples inside.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/FrameAgreement.h"
#include "core/field/ModelField.h"
#include "core/mask/DomainBoundary.h"
#include "core/render/BoundaryRaster.h"
#include "core/render/ModelKernelSwitch.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "gpu/GpuTestScenes.h"

namespace mfadvr {
namespace {

using namespace test;

// The renderer's frame of `m` (packets where it takes them) against one ray at a time, one
// variation of the frame per render; returns the ray-by-ray counters. (Unused where the packet
// tests skip: builds without the lane kernel.)
[[maybe_unused]] RenderStats expectPacketFrame(const Model& m, const TransferFunction& tf,
                                               bool oddStep, bool shade, int render) {
  RenderSettings s = settingsFor(m.domain().min, m.domain().max, tf, shade);
  s.skipEmptySpace = false;  // else the renderer takes one ray at a time
  // Vary what a packet must get right, one variation per render (61: a width whose tiles' last
  // pixels go one at a time).
  varyFrame(s, render % 4, 61);
  if (oddStep) s.sampleDistance = 0.037;  // steps that do not divide the segments
  const ModelField field(m);
  const ModelRenderSetup setup(field, s);
  EXPECT_EQ(setup.view().empty, nullptr);
  return expectFrameOfRayByRay(s, setup, render);
}

TEST(RayPacket, PacketsRenderTheImageAndCountersOfOneRayAtATime) {
#if !defined(MFADVR_SPLINE_LANE_KERNEL)
  GTEST_SKIP() << "this build has no lane kernel (needs AVX2 and FMA): no ray packets";
#else
  static_assert(takesRayPackets<SplineRaySampler<1, false, false> >());
  static_assert(takesRayPackets<SplineRaySampler<2, false, true> >());
  static_assert(takesRayPackets<SplineRaySampler<3, false, true> >());
  // Skipping takes no packets (it marches rays in groups, InterleavedMarchTest).
  static_assert(!takesRayPackets<SplineRaySampler<2, true, false> >());
  int renders = 0;
  std::int64_t terminated = 0, samples = 0;
  const std::vector<TransferFunction> tfs = transferFunctions();
  for (int degree : {1, 2, 3})
    for (std::size_t f = 0; f < tfs.size(); ++f)
      for (bool shade : {false, true}) {
        const RenderStats rayStats =
            expectPacketFrame(mlModel(degree), tfs[f], f == 0, shade, renders++);
        terminated += rayStats.terminated;
        samples += rayStats.samples;
      }
  EXPECT_EQ(renders, 36);
  // The scenes exercise early termination (lanes ending before their packet).
  EXPECT_GT(terminated, 0);
  EXPECT_GT(samples, 0);
#endif
}

// A mesh's model: 4^3 unit cubes less a central cavity and a corner notch (rays of up to three
// stretches inside), degree 2.
[[maybe_unused]] const Model& holedCubeModel() {
  static const Model m = [] {
    const TetMesh mesh = cubeMesh(4, [](int i, int j, int k) {
      const bool cavity = i >= 1 && i <= 2 && j >= 1 && j <= 2 && k >= 1 && k <= 2;
      return !cavity && !(i == 3 && j == 3 && k == 3);
    });
    Model model(patternedSpline(10), DomainBox{Vec3d::Zero(), Vec3d::Constant(4)}, 0.0, 1.0);
    model.setBoundary(
        std::make_shared<const DomainBoundary>(boundaryOfTetrahedra(mesh.points, mesh.tets)));
    return model;
  }();
  return m;
}

// Masked renders (a domain mask alone, a mesh's exact boundary over a mask, a mesh with a cavity)
// take packets too, with the image and counters of one ray at a time querying alone.
TEST(RayPacket, MaskedPacketsRenderTheImageAndCountersOfOneRayAtATime) {
#if !defined(MFADVR_SPLINE_LANE_KERNEL)
  GTEST_SKIP() << "this build has no lane kernel (needs AVX2 and FMA): no ray packets";
#else
  int renders = 0;
  std::int64_t terminated = 0, samples = 0;
  const std::vector<TransferFunction> tfs = transferFunctions();
  for (const Model* m : {&maskedModel(), &boundedModel(), &holedCubeModel()}) {
    ASSERT_TRUE(m->mask().view().nodes || m->boundary());
    for (std::size_t f = 0; f < tfs.size(); f += 2)
      for (bool shade : {false, true}) {
        const RenderStats rayStats = expectPacketFrame(*m, tfs[f], f == 0, shade, renders++);
        terminated += rayStats.terminated;
        samples += rayStats.samples;
      }
  }
  EXPECT_EQ(renders, 18);
  EXPECT_GT(terminated, 0);
  EXPECT_GT(samples, 0);
#endif
}

// A packet of a mesh's model whose tile holds its rays' stretches is taken (integratePacket says
// so) and gives each lane integrateRay's pixel; without the tile the sampler refuses it.
TEST(RayPacket, AMeshPacketIsTakenWhereItsTileHoldsTheStretches) {
#if !defined(MFADVR_SPLINE_LANE_KERNEL)
  GTEST_SKIP() << "this build has no lane kernel (needs AVX2 and FMA): no ray packets";
#else
  const ModelField field(holedCubeModel());
  RenderSettings s = viewOf(32, 24, Vec3d(9, 7, 11), Vec3d(2, 2, 2), 30, 0.02);
  s.skipEmptySpace = false;
  s.transferFunction.color = {{0.0, Vec3f(0, 0, 1)}, {1.0, Vec3f(1, 0.5, 0)}};
  s.transferFunction.opacity = {{0.0, 0.1f}, {1.0, 0.6f}};
  const ModelRenderSetup setup(field, s);
  const ModelView& view = setup.view();
  const RayParams& rp = setup.params();
  const BoundaryRaster raster(view.boundary, rp.camera);
  BoundaryTileStretches tile;
  raster.gather(0, 0, 32, 24, tile);
  int taken = 0, refused = 0, inked = 0;
  for (int y = 0; y < 24; ++y)
    for (int x0 = 0; x0 < 32; x0 += kRayPacket) {
      SplineRaySampler<2, false, false> packet(view), alone(view);
      float rgba[kRayPacket][4];
      RayCounters counters;
      bool meets = false;  // a ray of the packet has steps to take
      for (int l = 0; l < kRayPacket; ++l) {
        RaySegment ray;
        meets |= raySegment(rp, x0 + l, y, ray) && ray.steps > 0;
      }
      refused += meets;
      EXPECT_EQ((integratePacket<true, false>(rp, packet, x0, y, rgba, counters)), !meets);
      counters = RayCounters{};
      packet.useBoundaryTile(tile.view);
      ASSERT_TRUE((integratePacket<true, false>(rp, packet, x0, y, rgba, counters)));
      ++taken;
      for (int l = 0; l < kRayPacket; ++l) {
        float one[4];
        integrateRay<true, false>(rp, alone, x0 + l, y, one, counters);
        for (int c = 0; c < 4; ++c) EXPECT_EQ(rgba[l][c], one[c]) << x0 + l << ", " << y;
        inked += one[3] > 0.05f;
      }
    }
  EXPECT_EQ(taken, 4 * 24);
  EXPECT_GT(refused, 4 * 24 / 2);
  EXPECT_GT(inked, 32 * 24 / 4);
#endif
}

// A lane's distance along its ray, where its stretches inside a mesh are looked up, is its ray's
// alone to the bit (any difference could put a sample at a stretch's end on the other side).
TEST(RayPacket, ALaneFindsItsDistanceAlongTheRayAsTheRayAloneDoes) {
#if !defined(MFADVR_SPLINE_LANE_KERNEL)
  GTEST_SKIP() << "this build has no lane kernel (needs AVX2 and FMA): no ray packets";
#else
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-40.0, 40.0), unit(-1.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    LaneDouble8 o[3], d[3], p[3], inverse;
    double one[8][3][3];  // lane: o, d, p
    for (int l = 0; l < 8; ++l) {
      for (int a = 0; a < 3; ++a) {
        o[a][l] = one[l][0][a] = coordinate(random);
        d[a][l] = one[l][1][a] = unit(random);
        p[a][l] = one[l][2][a] = one[l][0][a] + coordinate(random) * one[l][1][a];
      }
      inverse[l] = rayInverseLength2(one[l][1]);
    }
    const LaneDouble8 t = rayParameterOf<LaneDouble8>(o, d, inverse, p);
    for (int l = 0; l < 8; ++l)
      ASSERT_EQ(t[l], rayParameterOf<double>(one[l][0], one[l][1], inverse[l], one[l][2]))
          << "trial " << trial << ", lane " << l;
  }
#endif
}

}  // namespace
}  // namespace mfadvr
