// Entry bounds (render/EntryBounds.h) let a ray begin its march past steps it would have
// skipped anyway. They must never pass over a step whose sample lies in a cell that is not
// empty (the image and the counters would change): checked step by step for every pixel, for
// cameras outside the model, close to it, inside it and parallel, axis-aligned views, steps
// aligned to the camera, and every level of blocks; and whole frames with the bounds against
// one ray at a time from its first step.
#include <gtest/gtest.h>

#include <cmath>

#include "core/FrameAgreement.h"
#include "core/field/ModelField.h"
#include "core/render/EntryBounds.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "gpu/GpuTestScenes.h"

namespace mfadvr {
namespace {

using namespace test;

// The cameras of the tests, by number.
constexpr int kCameras = 8;
void placeCamera(RenderSettings& s, int camera, const Vec3d& lo, const Vec3d& hi) {
  const Vec3d centre = 0.5 * (lo + hi);
  switch (camera) {
    case 0:  // settingsFor's: outside, at an angle
      break;
    case 1:  // close: the blocks' projections cover many tiles
      s.camera.zoom(4.0);
      break;
    case 2:  // inside the box, looking along a diagonal: blocks behind and beside the camera
      s.camera.position = centre + 0.1 * (hi - lo);
      s.camera.focalPoint = centre + Vec3d(1.0, 0.3, -0.2);
      s.camera.viewAngle = 70.0;
      s.camera.orthogonalizeViewUp();
      break;
    case 3:  // parallel projection
      s.camera.parallelProjection = true;
      s.camera.parallelScale = 0.6 * (hi - lo).norm();
      break;
    case 4:  // along an axis: directions with zero components
      s.camera.position = centre + Vec3d(0.0, 0.0, 3.0 * (hi - lo).norm());
      s.camera.focalPoint = centre;
      s.camera.viewUp = Vec3d(0.0, 1.0, 0.0);
      break;
    case 5:  // steps aligned to the camera
      s.alignSamplesToCamera = true;
      break;
    case 6:  // a host's skewed frustum (below)
      break;
    case 7:  // a host's skewed parallel rays (below): directions not unit
      s.camera.parallelProjection = true;
      s.camera.parallelScale = 0.6 * (hi - lo).norm();
      break;
  }
  s.camera.validate();
  if (camera >= 6) s.rays = skewedRays(s.primaryRays());  // not unit, not orthogonal
}

// A sparse scene: the built-in CT head phantom's bone and vessels (above 250 HU), air around
// the head and soft tissue inside it hidden.
const Model& ctHeadModel() {
  static const Model m = [] {
    StructuredFitOptions o;
    o.degree = {3, 3, 3};
    o.controlCounts = {36, 36, 36};
    return fitStructured(sampleBuiltin(*makeBuiltin("ct-head"), {40, 40, 40}), o);
  }();
  return m;
}

TransferFunction boneAndVessels() {
  return tfWith(TfSpace::Data, {{-1000.0, 0.0f}, {250.0, 0.0f}, {400.0, 0.8f}, {2000.0, 0.8f}});
}

TEST(EntryBounds, NoStepBeforeARaysEntryIsInACellThatIsNotEmpty) {
  std::int64_t checked = 0, rays = 0, raysStartingLater = 0;
  // The CT head (sparse), the Marschner-Lobb model's band and step (cells visible from near
  // the faces on); 4, 2 and 1 blocks per axis: coarse levels, the top.
  for (int scene : {0, 1, 2})
    for (int blocks : {kEntryBlocksPerAxis, 4, 2, 1})
      for (int camera = 0; camera < kCameras; ++camera) {
        const Model& m = scene == 0 ? ctHeadModel() : mlModel(3);
        const ModelField field(m);
        const TransferFunction tf =
            scene == 0 ? boneAndVessels() : transferFunctions()[scene == 1 ? 2 : 0];
        RenderSettings s = settingsFor(m.domain().min, m.domain().max, tf, false);
        s.width = 45;
        s.height = 38;
        placeCamera(s, camera, m.domain().min, m.domain().max);
        const ModelRenderSetup setup(field, s);
        ASSERT_NE(setup.view().empty, nullptr);
        const EntryBounds bounds(setup.params().camera, setup.view(), blocks);
        const EntryBoundsView entry = bounds.view();
        const RayParams& rp = setup.params();
        SplineRaySampler<3, true, false> sampler(setup.view());
        for (int y = 0; y < s.height; ++y)
          for (int x = 0; x < s.width; ++x) {
            RaySegment ray;
            if (!raySegment(rp, x, y, ray)) continue;
            const RayStart start = entryStart(entry, x, y, ray, rp.sampleDistance);
            ASSERT_GE(start.k, 0);
            ASSERT_LE(start.k, ray.steps);
            EXPECT_EQ(start.skipped, start.k);
            if (scene == 0 && blocks == kEntryBlocksPerAxis && start.k > 0) ++raysStartingLater;
            if (scene == 0 && blocks == kEntryBlocksPerAxis) ++rays;
            sampler.beginRay(ray.o, ray.d);
            for (std::int64_t k = 0; k < start.k; ++k, ++checked) {
              double p[3], length, tLeave;
              ASSERT_TRUE(stepSample(ray, k, rp.sampleDistance, p, length));
              ASSERT_TRUE(sampler.emptyAt(p, tLeave))
                  << "scene " << scene << ", blocks " << blocks << ", camera " << camera
                  << ", pixel " << x << ", " << y << ", step " << k << " of " << start.k;
            }
          }
      }
  // On the sparse scene at the default level the bounds do cut the way in: many rays begin
  // past their first step (not all: some cameras are inside the head or close to it).
  EXPECT_GT(raysStartingLater, rays / 4);
  EXPECT_GT(checked, 100000);
}

// The first steps the bounds pass over are those a march would have skipped, and the rays then
// go on as before: frames with the bounds (renderModelView) equal frames of one ray at a time
// from its first step, image and counters, for every camera and a few levels.
TEST(EntryBounds, FramesEqualThoseOfRaysFromTheirFirstStep) {
  int renders = 0;
  std::int64_t skipped = 0;
  const std::vector<TransferFunction> tfs = transferFunctions();
  // Models: mixed degrees, degree 2, degree 3, the CT head; transfer functions: the step, the
  // band and nothing visible (the CT head: its bone and vessels, and nothing visible).
  for (int model = 0; model < 4; ++model)
    for (int tf : {0, 2, 4})
      for (int camera = 0; camera < kCameras; ++camera) {
        if (model == 3 && tf == 2) continue;
        const Model& m = model == 0   ? mixedDegreeModel()
                         : model == 3 ? ctHeadModel()
                                      : mlModel(model);
        const TransferFunction f = model == 3 && tf == 0 ? boneAndVessels() : tfs[tf];
        RenderSettings s = settingsFor(m.domain().min, m.domain().max, f, camera % 2 == 0);
        s.width = 50;
        s.height = 41;
        placeCamera(s, camera, m.domain().min, m.domain().max);
        const ModelField field(m);
        const ModelRenderSetup setup(field, s);
        const RenderStats rayByRay = expectFrameOfRayByRay(s, setup, renders);
        skipped += rayByRay.skipped;
        ++renders;
      }
  EXPECT_EQ(renders, 88);
  EXPECT_GT(skipped, 0);
}

// A bound of +infinity (no occupied block covers the tile) passes over the whole ray; none at
// all (no bounds) starts at step 0; a bound before the ray's first step starts there too.
TEST(EntryBounds, StartIsClampedToTheRaysSteps) {
  RaySegment ray;
  ray.t0 = 1.0;
  ray.tEnter = 1.0;
  ray.tExit = 2.0;
  ray.steps = 10;
  const double dt = 0.1;
  double distance[4] = {INFINITY, 0.5, 1.55, NAN};
  const EntryBoundsView view{distance, 2, 2};
  EXPECT_EQ(entryStart(view, 0, 0, ray, dt).k, 10);       // tile 0
  EXPECT_EQ(entryStart(view, 3, 1, ray, dt).k, 0);        // tile 1: before the ray
  EXPECT_EQ(entryStart(view, 1, 2, ray, dt).k, 3);        // tile 2: 5 steps, less 2 of slack
  EXPECT_EQ(entryStart(view, 2, 3, ray, dt).skipped, 0);  // tile 3: no bound
  EXPECT_EQ(entryStart(EntryBoundsView{}, 0, 0, ray, dt).k, 0);
}

}  // namespace
}  // namespace mfadvr
