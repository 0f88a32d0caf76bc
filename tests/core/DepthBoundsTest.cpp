// Depth bounds (render/DepthBounds.h) let a ray begin its march past steps it would have
// skipped anyway, and end it before such steps. They must never pass over a step whose sample
// lies in a cell that is not empty (the image and the counters would change): checked step by
// step for every pixel, for cameras outside the model, close to it, inside it and parallel,
// axis-aligned views, steps aligned to the camera, and every level of blocks; and whole frames
// with the bounds against one ray at a time over all its steps.
#include <gtest/gtest.h>

#include <cmath>

#include "core/FrameAgreement.h"
#include "core/field/ModelField.h"
#include "core/render/DepthBounds.h"
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

// A cubic fit of n^3 control points to a built-in function sampled on (n + 4)^3 points.
Model cubicFit(const char* builtin, int n) {
  StructuredFitOptions o;
  o.degree = {3, 3, 3};
  o.controlCounts = {n, n, n};
  return fitStructured(sampleBuiltin(*makeBuiltin(builtin), {n + 4, n + 4, n + 4}), o);
}

// A sparse scene: the built-in CT head phantom's bone and vessels (above 250 HU), air around
// the head and soft tissue inside it hidden.
const Model& ctHeadModel() {
  static const Model m = cubicFit("ct-head", 36);
  return m;
}

TransferFunction boneAndVessels() {
  return tfWith(TfSpace::Data, {{-1000.0, 0.0f}, {250.0, 0.0f}, {400.0, 0.8f}, {2000.0, 0.8f}});
}

// A ball in the middle of the box, with empty space before and behind it: the Gaussian beam's
// values above 200 (of 255 at the centre).
const Model& ballModel() {
  static const Model m = cubicFit("gaussian-beam", 20);
  return m;
}

TransferFunction ballCore() {
  return tfWith(TfSpace::Data, {{0.0, 0.0f}, {200.0, 0.0f}, {230.0, 0.8f}, {255.0, 0.8f}});
}

TEST(DepthBounds, NoStepOutsideARaysBoundsIsInACellThatIsNotEmpty) {
  std::int64_t checked = 0, rays = 0, raysStartingLater = 0, ballRays = 0, raysEndingEarlier = 0;
  // The CT head (sparse), the Marschner-Lobb model's band and step (cells visible from near
  // the faces on), a ball in the middle; 4, 2 and 1 blocks per axis: coarse levels, the top.
  for (int scene : {0, 1, 2, 3})
    for (int blocks : {kDepthBlocksPerAxis, 4, 2, 1})
      for (int camera = 0; camera < kCameras; ++camera) {
        const Model& m = scene == 0 ? ctHeadModel() : scene == 3 ? ballModel() : mlModel(3);
        const ModelField field(m);
        const TransferFunction tf = scene == 0   ? boneAndVessels()
                                    : scene == 3 ? ballCore()
                                                 : transferFunctions()[scene == 1 ? 2 : 0];
        RenderSettings s = settingsFor(m.domain().min, m.domain().max, tf, false);
        s.width = 45;
        s.height = 38;
        placeCamera(s, camera, m.domain().min, m.domain().max);
        const ModelRenderSetup setup(field, s);
        ASSERT_NE(setup.view().empty, nullptr);
        const DepthBounds bounds(setup.params().camera, setup.view(), blocks);
        const DepthBoundsView depth = bounds.view();
        const RayParams& rp = setup.params();
        SplineRaySampler<3, true, false> sampler(setup.view());
        for (int y = 0; y < s.height; ++y)
          for (int x = 0; x < s.width; ++x) {
            RaySegment whole;
            if (!raySegment(rp, x, y, whole)) continue;
            RaySegment ray = whole;
            const RayStart start = boundSteps(depth, x, y, ray, rp.sampleDistance);
            ASSERT_GE(start.k, 0);
            ASSERT_LE(start.k, ray.steps);
            ASSERT_LE(ray.steps, whole.steps);
            EXPECT_EQ(start.skipped, start.k);
            if (scene == 0 && blocks == kDepthBlocksPerAxis) {
              ++rays;
              if (start.k > 0) ++raysStartingLater;
            }
            if (scene == 3 && blocks == kDepthBlocksPerAxis) {
              ++ballRays;
              if (ray.steps < whole.steps && ray.steps > start.k) ++raysEndingEarlier;
            }
            sampler.beginRay(ray);
            std::int64_t sampledAfter = 0;  // steps cut off that have a sample
            for (std::int64_t k = 0; k < whole.steps; ++k) {
              if (k == start.k) k = ray.steps;  // the steps between the bounds
              double p[3], length, tLeave;
              if (!stepSample(whole, k, rp.sampleDistance, p, length)) continue;
              ++checked;
              if (k >= ray.steps) ++sampledAfter;
              ASSERT_TRUE(sampler.emptyAt(p, tLeave))
                  << "scene " << scene << ", blocks " << blocks << ", camera " << camera
                  << ", pixel " << x << ", " << y << ", step " << k << " outside [" << start.k
                  << ", " << ray.steps << ") of " << whole.steps;
            }
            EXPECT_EQ(start.tail, sampledAfter);
          }
      }
  // At the default level the bounds do cut the way in on the sparse scene (not for every ray:
  // some cameras are inside the head or close to it), and the way out behind the ball (the
  // head's bone reaches the box's faces).
  EXPECT_GT(raysStartingLater, rays / 4);
  EXPECT_GT(raysEndingEarlier, ballRays / 3);
  EXPECT_GT(checked, 100000);
}

// The steps the bounds pass over, first and last, are those a march would have skipped, and the
// rays go on as before between them: frames with the bounds (renderModelView) equal frames of
// one ray at a time over all its steps, image and counters, for every camera.
TEST(DepthBounds, FramesEqualThoseOfRaysOverAllTheirSteps) {
  int renders = 0;
  std::int64_t skipped = 0;
  const std::vector<TransferFunction> tfs = transferFunctions();
  // Models: mixed degrees, degree 2, degree 3, the CT head, the ball; transfer functions: the
  // step, the band and nothing visible (the CT head: its bone and vessels, and nothing
  // visible; the ball: its core, and nothing visible).
  for (int model = 0; model < 5; ++model)
    for (int tf : {0, 2, 4})
      for (int camera = 0; camera < kCameras; ++camera) {
        if (model >= 3 && tf == 2) continue;
        const Model& m = model == 0   ? mixedDegreeModel()
                         : model == 3 ? ctHeadModel()
                         : model == 4 ? ballModel()
                                      : mlModel(model);
        const TransferFunction f = model == 3 && tf == 0   ? boneAndVessels()
                                   : model == 4 && tf == 0 ? ballCore()
                                                           : tfs[tf];
        RenderSettings s = settingsFor(m.domain().min, m.domain().max, f, camera % 2 == 0);
        s.width = 50;
        s.height = 41;
        placeCamera(s, camera, m.domain().min, m.domain().max);
        const ModelField field(m);
        const ModelRenderSetup setup(field, s);
        // One float step of slack: the runtime-degree model (model 0) has shown a one-step
        // difference in one channel of one pixel between the two paths, which are compiled in
        // different translation units (the library's frame, this file's rays); the samples and
        // counters are the same.
        const RenderStats rayByRay = expectFrameOfRayByRay(s, setup, renders, 2);
        skipped += rayByRay.skipped;
        ++renders;
      }
  EXPECT_EQ(renders, 104);
  EXPECT_GT(skipped, 0);
}

// A bound of +infinity (no occupied block covers the tile) passes over the whole ray; none at
// all (no bounds) starts at step 0; a bound before the ray's first step starts there too. The
// far bound cuts the steps after it (with two of slack), never before the start.
TEST(DepthBounds, StartAndEndAreClampedToTheRaysSteps) {
  RaySegment whole;
  whole.t0 = 1.0;
  whole.tEnter = 1.0;
  whole.tExit = 2.0;
  whole.steps = 10;
  const double dt = 0.1;
  double nearest[6] = {INFINITY, 0.5, 1.55, NAN, 1.25, 1.15};
  double farthest[6] = {-INFINITY, 1.62, 3.0, NAN, 0.5, 1.45};
  const DepthBoundsView view{nearest, farthest, 2, 2};
  struct Case {
    int x, y;
    std::int64_t k, steps, tail;
  };
  const Case cases[] = {
      {0, 0, 10, 10, 0},  // tile 0: nothing occupied
      {3, 1, 0, 9, 1},    // tile 1: before the ray; ends at ceil(6.2) + 2
      {1, 2, 3, 10, 0},   // tile 2: 5 steps, less 2 of slack; the end after the ray's
      {2, 3, 0, 10, 0},   // tile 3: no bounds
      {0, 4, 0, 0, 10},   // tile 4: ends before it starts: no step left (k = 0 by the slack)
      {2, 4, 0, 7, 3},    // tile 5: ceil(4.5) + 2
  };
  for (const Case& c : cases) {
    RaySegment ray = whole;
    const RayStart start = boundSteps(view, c.x, c.y, ray, dt);
    EXPECT_EQ(start.k, c.k) << c.x << ", " << c.y;
    EXPECT_EQ(start.skipped, c.k) << c.x << ", " << c.y;
    EXPECT_EQ(ray.steps, c.steps) << c.x << ", " << c.y;
    EXPECT_EQ(start.tail, c.tail) << c.x << ", " << c.y;
  }
  RaySegment ray = whole;
  EXPECT_EQ(boundSteps(DepthBoundsView{}, 0, 0, ray, dt).k, 0);
  EXPECT_EQ(ray.steps, 10);
  // A step without length (it starts at the ray's exit) has no sample: not in the tail.
  ray = whole;
  ray.steps = 11;
  const RayStart start = boundSteps(view, 3, 1, ray, dt);
  EXPECT_EQ(ray.steps, 9);
  EXPECT_EQ(start.tail, 1);
}

}  // namespace
}  // namespace mfadvr
