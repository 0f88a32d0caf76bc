// The blend modes other than composite, clipping planes, cropping and the depth image, against
// scenes whose pixels are known in closed form, and the MFA path against trilinear filtering
// where the two reconstructions coincide (a degree-1 interpolating model is trilinear).
#include <gtest/gtest.h>

#include <cmath>

#include "MarschnerLobbScene.h"
#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/image/ImageMetrics.h"
#include "core/render/PieceCompositor.h"
#include "core/render/RayCaster.h"
#include "core/render/ReconstructionMethod.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// A field of value a + b z on [-1, 1]^3 (zero gradient elsewhere is not needed: unshaded).
struct RampField {
  float a = 0.5f, b = 0.0f;
  Vec3d boxMin() const { return Vec3d(-1, -1, -1); }
  Vec3d boxMax() const { return Vec3d(1, 1, 1); }
  struct Sampler {
    const RampField* f;
    float value(const Vec3d& x) const { return f->a + f->b * static_cast<float>(x[2]); }
    ValueGradient valueGradient(const Vec3d& x) const {
      return {value(x), Vec3f(0.0f, 0.0f, f->b)};
    }
  };
  Sampler sampler() const { return {this}; }
};

// Straight down -z through the box with a parallel projection inside it: every ray crosses a
// thickness of 2; the image's x axis is world x.
RenderSettings downZ() {
  RenderSettings s;
  s.width = 16;
  s.height = 12;
  s.camera.position = Vec3d(0, 0, 5);
  s.camera.focalPoint = Vec3d(0, 0, 0);
  s.camera.parallelProjection = true;
  s.camera.parallelScale = 0.5;
  s.background = Vec3f(0.1f, 0.2f, 0.3f);
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{0.0, Vec3f(0, 0, 1)}, {1.0, Vec3f(1, 0, 0)}};
  s.transferFunction.opacity = {{0.0, 0.0f}, {1.0, 0.8f}};
  s.opacityUnitDistance = 1.0;
  s.sampleDistance = 0.05;
  return s;
}

TEST(BlendMode, NamesRoundTrip) {
  for (BlendMode m : {BlendMode::Composite, BlendMode::Maximum, BlendMode::Minimum,
                      BlendMode::Average, BlendMode::Additive})
    EXPECT_EQ(parseBlendMode(blendModeName(m)), m);
  EXPECT_EQ(parseBlendMode("mip"), BlendMode::Maximum);
  EXPECT_EQ(parseBlendMode("minip"), BlendMode::Minimum);
  EXPECT_FALSE(parseBlendMode("iso-surface"));
}

// Max and min classify the extreme value with its opacity uncorrected (VTK's MIP): value
// 0.5 + 0.4 z over z in [-1, 1] has max 0.9 and min 0.1 (at the samples nearest the faces).
TEST(BlendMode, MaxAndMinClassifyTheExtremeValue) {
  const RampField f{0.5f, 0.4f};
  for (BlendMode m : {BlendMode::Maximum, BlendMode::Minimum}) {
    RenderSettings s = downZ();
    s.blend = m;
    s.depth = true;
    const Image image = renderVolume(f, s);
    // The extreme sample is the first (max, z = 1 - dt/2) or the last (min).
    const double z = m == BlendMode::Maximum ? 1.0 - 0.025 : -1.0 + 0.025;
    const double v = 0.5 + 0.4 * z, a = 0.8 * v;
    const float* p = image.pixel(5, 7);
    EXPECT_NEAR(p[0], a * v + (1 - a) * 0.1, 1e-3) << blendModeName(m);
    EXPECT_NEAR(p[1], (1 - a) * 0.2, 1e-3);
    EXPECT_NEAR(p[2], a * (1 - v) + (1 - a) * 0.3, 1e-3);
    EXPECT_NEAR(p[3], a, 1e-3);
    // Depth: from the camera at z = 5 to the extreme sample.
    EXPECT_NEAR(image.depth[7 * s.width + 5], 5.0 - z, 1e-6);
  }
}

// Average: the step-weighted mean of a(v) v' over the samples; additive: their sum a v' L / u,
// both grey and opaque.
TEST(BlendMode, AverageAndAdditiveOfAConstantField) {
  const RampField f{0.25f, 0.0f};
  const double a = 0.8 * 0.25, level = a * 0.25;
  RenderSettings s = downZ();
  s.blend = BlendMode::Average;
  Image image = renderVolume(f, s);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.pixel(3, 3)[c], level, 1e-5);
  EXPECT_EQ(image.pixel(3, 3)[3], 1.0f);
  s.blend = BlendMode::Additive;
  for (double unit : {1.0, 0.5, 10.0}) {
    for (double dt : {0.05, 0.3}) {  // 0.3 does not divide the thickness: the sum does not care
      s.opacityUnitDistance = unit;
      s.sampleDistance = dt;
      image = renderVolume(f, s);
      const double sum = std::min(1.0, level * 2.0 / unit);
      EXPECT_NEAR(image.pixel(3, 3)[0], sum, 1e-5) << unit << " " << dt;
    }
  }
}

// The average range keeps only the values inside it; none inside: the background.
TEST(BlendMode, AverageRangeSelectsValues) {
  const RampField f{0.5f, 0.4f};  // 0.1 .. 0.9 along the ray
  RenderSettings s = downZ();
  s.blend = BlendMode::Average;
  s.averageRange = std::pair(0.7, 0.9);
  const Image image = renderVolume(f, s);
  // v in [0.7, 0.9]: z in [0.5, 1]; mean of 0.8 v^2 over it.
  double sum = 0, n = 0;
  for (double z = 0.5 + 0.025; z < 1.0; z += 0.05, n += 1) sum += 0.8 * std::pow(0.5 + 0.4 * z, 2);
  EXPECT_NEAR(image.pixel(4, 4)[0], sum / n, 2e-3);
  s.averageRange = std::pair(2.0, 3.0);
  const Image none = renderVolume(f, s);
  EXPECT_NEAR(none.pixel(4, 4)[2], 0.3f, 1e-6);
  EXPECT_EQ(none.pixel(4, 4)[3], 0.0f);
}

// A clipping plane through x = 0.1 with normal +x keeps the right part of the image; a plane
// parallel to the rays that faces away removes every ray; the kept part is unchanged.
TEST(BlendMode, ClippingPlanesCutRaysAnalytically) {
  const RampField f{0.5f, 0.4f};
  RenderSettings s = downZ();
  const Image whole = renderVolume(f, s);
  s.clipPlanes.push_back({Vec3d(0.1, 0, 0), Vec3d(2, 0, 0)});
  const Image clipped = renderVolume(f, s);
  const RayGenerator rays(s.camera, s.width, s.height);
  for (int x = 0; x < s.width; ++x) {
    double o[3], d[3];
    primaryRay(rays.rays(), x, 5, o, d);
    const float* p = clipped.pixel(x, 5);
    if (o[0] < 0.1) {
      EXPECT_EQ(p[3], 0.0f) << x;
      EXPECT_NEAR(p[0], 0.1f, 1e-6);
    } else {
      for (int c = 0; c < 4; ++c) EXPECT_EQ(p[c], whole.pixel(x, 5)[c]) << x;
    }
  }
  // A plane across the rays (normal -z through z = 0) keeps the far half: the composite is that
  // of the lower half alone.
  s.clipPlanes = {{Vec3d(0, 0, 0), Vec3d(0, 0, -1)}};
  const Image lower = renderVolume(f, s);
  RenderSettings cropped = downZ();
  cropped.crop = DomainBox{Vec3d(-1, -1, -1), Vec3d(1, 1, 0)};
  const Image lowerByCrop = renderVolume(f, cropped);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(lower.pixel(7, 7)[c], lowerByCrop.pixel(7, 7)[c], 1e-6);
  EXPECT_GT(std::abs(lower.pixel(7, 7)[3] - whole.pixel(7, 7)[3]), 0.05f);
}

// Cropping renders the sub-box only; a crop beside the box leaves the background.
TEST(BlendMode, CroppingKeepsTheSubBox) {
  const RampField f{0.5f, 0.0f};
  RenderSettings s = downZ();
  s.crop = DomainBox{Vec3d(-1, -1, -0.5), Vec3d(1, 1, 0.5)};  // thickness 1 instead of 2
  const Image image = renderVolume(f, s);
  const double a = 0.8 * 0.5, kept = 1 - std::pow(1 - a, 1.0);
  EXPECT_NEAR(image.pixel(8, 6)[3], kept, 1e-5);
  s.crop = DomainBox{Vec3d(2, 2, 2), Vec3d(3, 3, 3)};
  EXPECT_EQ(renderVolume(f, s).pixel(8, 6)[3], 0.0f);
}

// Composite depth: where 1 - (1 - a)^(s / u) first reaches 0.5, to within a step.
TEST(BlendMode, CompositeDepthIsWhereOpacityReachesHalf) {
  const RampField f{1.0f, 0.0f};  // opacity 0.8 per unit distance
  RenderSettings s = downZ();
  s.depth = true;
  s.opacityUnitDistance = 1.0;
  const Image image = renderVolume(f, s);
  const double into = std::log(0.5) / std::log(1.0 - 0.8);  // 0.43 units into the box
  EXPECT_NEAR(image.depth[3 * s.width + 3], 4.0 + into, s.sampleDistance);
  // A transparent field has no depth.
  RampField clear{0.0f, 0.0f};
  const Image none = renderVolume(clear, s);
  EXPECT_TRUE(std::isnan(none.depth[3 * s.width + 3]));
}

// A degree-1 interpolating MFA model is trilinear interpolation of its samples: every blend
// mode renders both alike (the model's path: its own sampler, no packets, no skipping), with
// clipping and cropping.
TEST(BlendMode, DegreeOneModelRendersLikeTrilinearInEveryMode) {
  const auto ml = makeBuiltin("marschner-lobb");
  const StructuredGrid grid = sampleBuiltin(*ml, {21, 21, 21});
  StructuredFitOptions fit;
  fit.degree = {1, 1, 1};
  const Model model = fitStructured(grid, fit);
  SceneData scene;
  scene.model = &model;
  scene.grid = &grid;
  scene.differenceStep = grid.spacing;
  RenderSettings s = mlSettings(48);
  s.shade = false;
  s.sampleDistance = 0.02;
  s.clipPlanes.push_back({Vec3d(0.1, 0, 0), Vec3d(1, 0.3, 0)});
  s.crop = DomainBox{Vec3d(-1, -1, -0.8), Vec3d(1, 0.9, 1)};
  for (BlendMode m : {BlendMode::Composite, BlendMode::Maximum, BlendMode::Minimum,
                      BlendMode::Average, BlendMode::Additive}) {
    s.blend = m;
    MethodSpec spec;
    spec.method = ReconstructionMethod::Mfa;
    const Image mfa = renderMethod(scene, spec, s);
    spec.method = ReconstructionMethod::Trilinear;
    const Image trilinear = renderMethod(scene, spec, s);
    const double psnr = compareImages(toImage8(mfa), toImage8(trilinear)).psnr;
    EXPECT_GT(psnr, 50.0) << blendModeName(m);
  }
}

// Non-composite blends of a multi-piece model are refused, not composited wrongly.
TEST(BlendMode, PiecesRefuseOtherBlends) {
  RenderSettings s = downZ();
  s.blend = BlendMode::Maximum;
  const std::vector<DomainBox> regions{DomainBox{Vec3d(-1, -1, -1), Vec3d(0, 1, 1)},
                                       DomainBox{Vec3d(0, -1, -1), Vec3d(1, 1, 1)}};
  EXPECT_THROW(renderPieces(s, regions,
                            [](size_t, const RenderSettings& p, RenderStats*) {
                              return Image(p.width, p.height);
                            }),
               Error);
}

TEST(BlendMode, RejectsBadClippingAndCropping) {
  RenderSettings s = downZ();
  s.clipPlanes.push_back({Vec3d(0, 0, 0), Vec3d(0, 0, 0)});
  EXPECT_THROW(s.validate(), Error);
  s.clipPlanes.assign(kMaxClipPlanes + 1, ClipPlane{});
  EXPECT_THROW(s.validate(), Error);
  s.clipPlanes.clear();
  s.crop = DomainBox{Vec3d(1, 0, 0), Vec3d(0, 1, 1)};
  EXPECT_THROW(s.validate(), Error);
  s.crop.reset();
  s.averageRange = std::pair(1.0, 0.0);
  EXPECT_THROW(s.validate(), Error);
}

}  // namespace
}  // namespace mfadvr
