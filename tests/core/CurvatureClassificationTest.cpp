// Classification by curvature: curvature transfer functions and thickness-controlled contours.
// The level sets of f = -(x^2 + y^2 + z^2) are spheres around its maximum, k1 = k2 = 1 / r
// (field/Curvature.h's sign: they bend around higher values); an interpolating cubic model
// reproduces f, so which colour a curvature table gives each shell, and where a sphere's
// silhouette lies in the image, are known.
#include <gtest/gtest.h>

#include <cmath>

#include "core/encode/StructuredEncoder.h"
#include "core/field/ModelField.h"
#include "core/grid/StructuredGrid.h"
#include "core/render/ClassificationTables.h"
#include "core/render/RayCaster.h"
#include "core/render/ReconstructionMethod.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// f = -(x^2 + y^2 + z^2) on [-1, 1]^3.
StructuredGrid bowl() {
  StructuredGrid g;
  g.dims = {17, 17, 17};
  g.origin = Vec3d(-1.0, -1.0, -1.0);
  g.spacing = Vec3d(0.125, 0.125, 0.125);
  g.values.resize(size_t(g.sampleCount()));
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
        g.at(i, j, k) = -g.position(i, j, k).squaredNorm();
  return g;
}

// Looking down -z, parallel, the box's [-1, 1]^2 filling the image: pixel (c, r) sees
// x = -1 + 2 (c + 0.5) / size.
RenderSettings topView(int size) {
  RenderSettings s;
  s.width = s.height = size;
  s.camera.resetToBounds(Vec3d(-1, -1, -1), Vec3d(1, 1, 1));
  s.camera.parallelProjection = true;
  s.camera.parallelScale = 1.0;
  s.camera.validate();
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{-3.0, Vec3f(1.0f, 0.0f, 0.0f)}};
  s.transferFunction.opacity = {{-3.0, 1.0f}};
  s.opacityUnitDistance = 0.05;
  s.sampleDistance = 0.01;
  return s;
}

// A JSON table: green where k1 and k2 both lie in [lo, hi], the opacity factor `opacity` there.
CurvatureTransferFunction boxOf(double lo, double hi, double opacity = 1.0) {
  const std::string text =
      "{\"boxes\": [{\"k1\": [" + std::to_string(lo) + ", " + std::to_string(hi) + "], \"k2\": [" +
      std::to_string(lo) + ", " + std::to_string(hi) +
      "], \"color\": [0, 1, 0], \"opacity\": " + std::to_string(opacity) + "}]}";
  return parseCurvatureTransferFunctionJson(text, "test table");
}

TEST(CurvatureTransferView, SphereTakesTheEntryOfItsCurvature) {
  RenderSettings s = topView(8);
  s.curvatureTransferFunction = boxOf(1.5, 2.5);
  const ClassificationTables tables(s);
  const CurvatureTransferView v = tables.curvatureView(s.primaryRays());
  ASSERT_TRUE(v.active());
  const double d[3] = {0.0, 0.0, -1.0};
  const float h[6] = {-2.0f, 0.0f, 0.0f, -2.0f, 0.0f, -2.0f};
  for (double r : {0.3, 0.5, 0.8}) {
    const float g[3] = {0.0f, 0.0f, static_cast<float>(-2.0 * r)};  // at (0, 0, r)
    float c[3] = {1.0f, 0.0f, 0.0f}, factor = 1.0f, contour = 1.0f;
    v.apply(g, h, d, 1.0, c, factor, contour);
    const bool inBox = 1.0 / r >= 1.5 && 1.0 / r <= 2.5;
    EXPECT_NEAR(c[1], inBox ? 1.0f : 0.0f, 1e-5f) << "r " << r;
    EXPECT_NEAR(c[0], inBox ? 0.0f : 1.0f, 1e-5f) << "r " << r;
    EXPECT_EQ(factor, 1.0f);
    EXPECT_EQ(contour, 0.0f);  // no contours asked for
  }
  // No gradient, no curvature: the sample stays as it is.
  const float zero[3] = {0.0f, 0.0f, 0.0f};
  float c[3] = {0.2f, 0.3f, 0.4f}, factor = 1.0f, contour = 0.0f;
  v.apply(zero, h, d, 1.0, c, factor, contour);
  EXPECT_EQ(c[0], 0.2f);
  EXPECT_EQ(c[2], 0.4f);
}

TEST(CurvatureTransferView, ContoursAreTheBandWithinTheirWidthOfTheSilhouette) {
  // A sphere of radius r seen along -z; a pixel of 0.01 world units (parallel); contours of 3
  // pixels: the points within T = 0.03 of the silhouette in the image, |n . v| <=
  // sqrt(T/r (2 - T/r)).
  RenderSettings s = topView(200);
  s.contourPixels = 3.0;
  const ClassificationTables tables(s);
  const CurvatureTransferView v = tables.curvatureView(s.primaryRays());
  ASSERT_NEAR(v.pixelBase, 0.01, 1e-12);
  const double r = 0.5, T = 0.03;
  const double d[3] = {0.0, 0.0, -1.0};
  const float h[6] = {-2.0f, 0.0f, 0.0f, -2.0f, 0.0f, -2.0f};
  for (double rho : {0.0, 0.3, 0.45, 0.462, 0.475, 0.49, 0.499}) {
    const double z = std::sqrt(r * r - rho * rho);
    const float g[3] = {static_cast<float>(-2.0 * rho), 0.0f, static_cast<float>(-2.0 * z)};
    float c[3] = {1.0f, 1.0f, 1.0f}, factor = 1.0f, contour = 0.0f;
    v.apply(g, h, d, 1.0, c, factor, contour);
    const bool band = rho >= r - T;
    if (std::abs(rho - (r - T)) > 1e-3) {
      EXPECT_EQ(contour, band ? 1.0f : 0.0f) << "rho " << rho;
    }
    EXPECT_EQ(c[0], 1.0f);  // contours change the colour after shading, not here
  }
}

TEST(CurvatureClassification, ShellsTakeTheColourOfTheirCurvature) {
  const StructuredGrid g = bowl();
  const Model model = fitStructured(g, StructuredFitOptions{});
  SceneData scene;
  scene.model = &model;
  scene.grid = &g;
  scene.differenceStep = g.spacing;
  RenderSettings s = topView(32);
  // A shell around r = 0.5 (k = 2): visible for values -0.3025 .. -0.2025 (r 0.45 .. 0.55).
  s.transferFunction.opacity = {{-0.31, 0.0f}, {-0.30, 1.0f}, {-0.205, 1.0f}, {-0.20, 0.0f}};
  s.curvatureTransferFunction = boxOf(1.5, 2.5);
  const int centre = s.width / 2;
  for (ReconstructionMethod method :
       {ReconstructionMethod::Mfa, ReconstructionMethod::BSpline, ReconstructionMethod::Tricubic,
        ReconstructionMethod::Trilinear}) {
    MethodSpec spec;
    spec.method = method;
    const Image image = renderMethod(scene, spec, s);
    const float* p = image.pixel(centre, centre);
    ASSERT_GT(p[3], 0.5f) << methodName(method);
    if (method == ReconstructionMethod::Trilinear) {
      // The trilinear filter has no second derivatives along the axes: its shells are flat
      // (k = 0) and keep the value transfer function's red.
      EXPECT_GT(p[0], 4.0f * p[1]) << methodName(method);
    } else {
      EXPECT_GT(p[1], 10.0f * p[0]) << methodName(method);
    }
  }
  // The table's opacity factor: 0 hides the shell.
  s.curvatureTransferFunction = boxOf(1.5, 2.5, 0.0);
  const Image hidden = renderVolume(ModelField(model), s);
  EXPECT_LT(hidden.pixel(centre, centre)[3], 0.05f);
}

TEST(CurvatureClassification, ContoursDrawTheSilhouetteOfABall) {
  const StructuredGrid g = bowl();
  const Model model = fitStructured(g, StructuredFitOptions{});
  const ModelField field(model);
  const int size = 100;  // a pixel of 0.02 world units
  RenderSettings s = topView(size);
  s.transferFunction.color = {{-3.0, Vec3f(1.0f, 1.0f, 1.0f)}};
  s.transferFunction.opacity = {{-0.26, 0.0f}, {-0.25, 1.0f}};  // the ball r <= 0.5
  s.opacityUnitDistance = 0.001;
  s.sampleDistance = 0.002;
  s.contourPixels = 3.0;  // 0.06 world units: a rim from r 0.44 to 0.5
  s.contourColor = Vec3f(0.0f, 0.0f, 0.0f);
  // The ball's surface as the composite blend meets it, and as the exact isosurface.
  for (BlendMode blend : {BlendMode::Composite, BlendMode::Iso}) {
    s.blend = blend;
    s.isoSurfaces = {IsoSurface{-0.25, Vec3f(1.0f, 1.0f, 1.0f), 1.0f}};
    s.contourPixels = 3.0;
    const Image image = renderVolume(field, s);
    int rim = 0, inside = 0;
    for (int c = size / 2; c < size; ++c) {
      const double rho = -1.0 + 2.0 * (c + 0.5) / size;  // along the middle row
      const float* p = image.pixel(c, size / 2);
      if (rho < 0.42) {
        EXPECT_GT(p[0], 0.9f) << blendModeName(blend) << " rho " << rho;
        ++inside;
      } else if (rho > 0.455 && rho < 0.495) {
        EXPECT_LT(p[0], 0.1f) << blendModeName(blend) << " rho " << rho;
        ++rim;
      }
    }
    EXPECT_GE(rim, 2) << blendModeName(blend);
    EXPECT_GE(inside, 10) << blendModeName(blend);
    // Without contours the rim is white.
    s.contourPixels = 0.0;
    const Image plain = renderVolume(field, s);
    EXPECT_GT(plain.pixel(size / 2 + 23, size / 2)[0], 0.9f) << blendModeName(blend);
  }
}

TEST(CurvatureClassification, PresetsAndTablesAreCheckedForCompositeAndIsoOnly) {
  EXPECT_THROW(readCurvatureTransferFunction("ridges", 1.0), Error);
  EXPECT_THROW(readCurvatureTransferFunction("mean:-1", 1.0), Error);
  EXPECT_THROW(readCurvatureTransferFunction("mean:x", 1.0), Error);
  EXPECT_THROW(readCurvatureTransferFunction("missing.json", 1.0), Error);
  EXPECT_THROW(parseCurvatureTransferFunctionJson("{\"boxes\": []}", "t"), Error);
  EXPECT_THROW(parseCurvatureTransferFunctionJson("{\"boxes\": [{\"k1\": [0, 1]}]}", "t"), Error);
  EXPECT_THROW(parseCurvatureTransferFunctionJson(
                   "{\"boxes\": [{\"k1\": [0, 1], \"k2\": [0, 1], \"weight\": 2}]}", "t"),
               Error);
  for (const char* name : {"ridges-valleys", "mean", "gaussian"}) {
    const CurvatureTransferFunction tf = readCurvatureTransferFunction(name, 2.0);
    EXPECT_NO_THROW(tf.validate());
    EXPECT_DOUBLE_EQ(tf.k1Hi, 4.0);
  }
  // mean: white at zero mean curvature, the warm end at k1 = k2 = K.
  const CurvatureTransferFunction mean = curvaturePreset("mean", 1.0);
  const float* flat = mean.entry(mean.width / 2, mean.height / 2);
  EXPECT_NEAR(flat[0], flat[2], 0.05f);
  const int atK = (mean.width - 1) * 3 / 4;  // k1 = k2 = K
  const float* convex = mean.entry(atK, atK);
  EXPECT_GT(convex[0], 3.0f * convex[2]);

  RenderSettings s = topView(8);
  s.contourPixels = 2.0;
  s.blend = BlendMode::Maximum;
  EXPECT_THROW(s.validate(), Error);
  s.blend = BlendMode::Iso;
  s.isoSurfaces = {IsoSurface{-0.25, {}, {}}};
  EXPECT_NO_THROW(s.validate());
  s.blend = BlendMode::Composite;
  s.contourColor = Vec3f(2.0f, 0.0f, 0.0f);
  EXPECT_THROW(s.validate(), Error);
}

}  // namespace
}  // namespace mfadvr
