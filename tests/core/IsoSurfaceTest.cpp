// The iso blend: exact crossings of an MFA model (and of the grid filters) along each ray. An interpolating cubic model
// of a quadratic field reproduces it, so its level sets are exact spheres and cylinders whose
// ray distances are known in closed form; the walk goes cell by cell, so the hits do not depend
// on the step, and a surface thinner than the step is found.
#include <gtest/gtest.h>

#include <cmath>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/field/ModelField.h"
#include "core/grid/StructuredGrid.h"
#include "core/render/Camera.h"
#include "core/render/RayCaster.h"
#include "core/render/ReconstructionMethod.h"

namespace mfadvr {
namespace {

const Vec3d kCentre(0.1, -0.05, 0.08);

// (x - c)^2 + (y - c)^2 (+ (z - c)^2 unless a cylinder along z) on a box that is not a cube.
StructuredGrid quadratic(bool cylinder) {
  StructuredGrid g;
  g.dims = {15, 13, 11};
  g.origin = Vec3d(-1.0, -0.9, -0.8);
  g.spacing = Vec3d(2.0 / 14, 1.8 / 12, 1.6 / 10);
  g.values.resize(size_t(g.sampleCount()));
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i) {
        Vec3d x = g.position(i, j, k) - kCentre;
        if (cylinder) x[2] = 0.0;
        g.at(i, j, k) = x.squaredNorm();
      }
  return g;
}

RenderSettings isoSettings(const StructuredGrid& g, std::vector<IsoSurface> surfaces) {
  RenderSettings s;
  s.width = 48;
  s.height = 40;
  s.camera.resetToBounds(g.boxMin(), g.boxMax());
  s.camera.azimuth(25);
  s.camera.elevation(15);
  s.camera.validate();
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{0.0, Vec3f(1, 1, 1)}, {3.0, Vec3f(1, 1, 1)}};
  s.transferFunction.opacity = {{0.0, 1.0f}, {3.0, 1.0f}};
  s.blend = BlendMode::Iso;
  s.isoSurfaces = std::move(surfaces);
  s.depth = true;
  s.sampleDistance = 0.5 * g.spacing.minCoeff();
  return s;
}

// The first distance t > 0 where the ray o + t d meets the sphere (or cylinder about z) of
// radius r around kCentre inside the box; NaN if none (or too close to a tangent to judge).
double analyticHit(const StructuredGrid& g, const Vec3d& o, const Vec3d& d, double r,
                   bool cylinder) {
  Vec3d oc = o - kCentre, dd = d;
  if (cylinder) oc[2] = dd[2] = 0.0;
  const double a = dd.squaredNorm(), b = 2.0 * oc.dot(dd), c = oc.squaredNorm() - r * r;
  const double disc = b * b - 4 * a * c;
  // A miss, or a ray passing within 1 % of r^2 of a tangent (too steep a graze to judge).
  if (!(disc > 4.0 * a * 0.01 * r * r)) return NAN;
  for (double t : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)}) {
    const Vec3d p = o + t * d;
    if (t > 0 && (p.array() >= g.boxMin().array()).all() && (p.array() <= g.boxMax().array()).all())
      return t;
  }
  return NAN;
}

Image renderIso(const Model& model, const RenderSettings& s) {
  const ModelField field(model);
  return renderVolume(field, s);
}

// Each ray whose analytic hit distance t = analytic(o, d) is a number must have hit (a missed
// one counts as an infinite error); returns how many such rays and the worst |hit - t| as a
// fraction of the box diagonal.
struct HitErrors {
  int rays = 0;
  double worst = 0.0;
};
template <class Analytic>
HitErrors hitErrors(const Image& image, const RenderSettings& s, double diagonal,
                    Analytic&& analytic) {
  const RayGenerator rays(s.camera, s.width, s.height);
  HitErrors e;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      Vec3d o, d;
      rays.ray(x, y, o, d);
      const double t = analytic(o, d);
      if (std::isnan(t)) continue;
      const float hit = image.depth[size_t(y) * s.width + x];
      e.worst = std::isnan(hit) ? INFINITY : std::max(e.worst, std::abs(hit - t) / diagonal);
      ++e.rays;
    }
  return e;
}

TEST(IsoSurface, HitsSpheresAndCylindersAtTheirAnalyticDistance) {
  for (bool cylinder : {false, true}) {
    const StructuredGrid g = quadratic(cylinder);
    const Model model = fitStructured(g, StructuredFitOptions{});
    const double r = 0.6;
    const RenderSettings s = isoSettings(g, {{r * r, {}, {}}});
    const Image image = renderIso(model, s);
    const HitErrors e =
        hitErrors(image, s, (g.boxMax() - g.boxMin()).norm(), [&](const Vec3d& o, const Vec3d& d) {
          return analyticHit(g, o, d, r, cylinder);
        });
    EXPECT_GT(e.rays, 100);
    EXPECT_LT(e.worst, 1e-5) << (cylinder ? "cylinder" : "sphere");  // a miss is infinite
    std::printf("%s: %d rays, worst hit error %.2e of the diagonal\n",
                cylinder ? "cylinder" : "sphere", e.rays, e.worst);
  }
}

// The same hits at a step of a tenth of the spacing and at eight spacings: cells are walked,
// not samples; and a sphere of diameter far below the step is still hit.
TEST(IsoSurface, HitsDoNotDependOnTheStepAndThinShellsAreFound) {
  const StructuredGrid g = quadratic(false);
  const Model model = fitStructured(g, StructuredFitOptions{});
  RenderSettings fine = isoSettings(g, {{0.36, {}, {}}});
  fine.sampleDistance = 0.1 * g.spacing.minCoeff();
  RenderSettings coarse = fine;
  coarse.sampleDistance = 8.0 * g.spacing.minCoeff();
  const Image a = renderIso(model, fine), b = renderIso(model, coarse);
  for (size_t i = 0; i < a.depth.size(); ++i) {
    ASSERT_EQ(std::isnan(a.depth[i]), std::isnan(b.depth[i])) << i;
    if (!std::isnan(a.depth[i])) {
      ASSERT_EQ(a.depth[i], b.depth[i]) << i;
    }
  }
  // A sphere of radius 0.04 (diameter 0.08) at a step of 8 spacings (about 1.2).
  RenderSettings tiny = isoSettings(g, {{0.04 * 0.04, {}, {}}});
  tiny.sampleDistance = 8.0 * g.spacing.minCoeff();
  tiny.camera.focalPoint = kCentre;
  tiny.camera.zoom(8.0);
  const Image small = renderIso(model, tiny);
  int hits = 0;
  for (float t : small.depth) hits += !std::isnan(t);
  EXPECT_GT(hits, 20);
  // The analytic truth is sampled (it has no pieces): at that step it misses the sphere, as
  // VTK's isosurface blend, which looks for crossings between samples, would.
  struct Quadratic : BuiltinFunction {
    std::string name() const override { return "sphere"; }
    double value(const Vec3d& x) const override { return (x - kCentre).squaredNorm(); }
    double valueGradient(const Vec3d& x, Vec3d& gradient) const override {
      gradient = 2.0 * (x - kCentre);
      return value(x);
    }
    Index3 defaultDims() const override { return {15, 13, 11}; }
  } truth;
  SceneData scene;
  scene.grid = &g;
  scene.truth = &truth;
  scene.differenceStep = g.spacing;
  MethodSpec spec;
  spec.method = ReconstructionMethod::Truth;
  int sampledHits = 0;
  for (float t : renderMethod(scene, spec, tiny).depth) sampledHits += !std::isnan(t);
  EXPECT_LT(sampledHits, hits / 4);
}

Image renderGridIso(const StructuredGrid& g, ReconstructionMethod method, const RenderSettings& s) {
  SceneData scene;
  scene.grid = &g;
  scene.differenceStep = g.spacing;
  MethodSpec spec;
  spec.method = method;
  return renderMethod(scene, spec, s);
}

const ReconstructionMethod kPiecewisePolynomialFilters[] = {
    ReconstructionMethod::Trilinear, ReconstructionMethod::Tricubic,
    ReconstructionMethod::CatmullRom, ReconstructionMethod::BSpline};

// The grid filters are polynomials in each cell between samples (degree 3 along a ray for
// trilinear, 9 for the tricubic ones), so they are walked cell by cell as the model is: the
// same hits at a tenth of a spacing and at eight; and on a linear field, which each of them
// reproduces (the prefiltered B-spline too, away from its natural ends), the hits are the
// analytic plane's.
TEST(IsoSurface, GridFiltersAreWalkedCellByCellToo) {
  const StructuredGrid g = quadratic(false);
  for (ReconstructionMethod m : kPiecewisePolynomialFilters) {
    RenderSettings fine = isoSettings(g, {{0.36, {}, {}}});
    fine.sampleDistance = 0.1 * g.spacing.minCoeff();
    RenderSettings coarse = fine;
    coarse.sampleDistance = 8.0 * g.spacing.minCoeff();
    const Image a = renderGridIso(g, m, fine), b = renderGridIso(g, m, coarse);
    int hits = 0;
    for (size_t i = 0; i < a.depth.size(); ++i) {
      ASSERT_EQ(std::isnan(a.depth[i]), std::isnan(b.depth[i])) << methodName(m) << " " << i;
      if (!std::isnan(a.depth[i])) {
        ASSERT_EQ(a.depth[i], b.depth[i]) << methodName(m) << " " << i;
        ++hits;
      }
    }
    EXPECT_GT(hits, 100) << methodName(m);
  }

  StructuredGrid linear = g;
  const Vec3d gradient(1.0, 2.0, -1.5);
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
        linear.at(i, j, k) = float(gradient.dot(g.position(i, j, k)));
  const double c = 0.2, diagonal = (g.boxMax() - g.boxMin()).norm();
  for (ReconstructionMethod m : {ReconstructionMethod::Trilinear, ReconstructionMethod::Tricubic,
                                 ReconstructionMethod::CatmullRom}) {
    RenderSettings s = isoSettings(linear, {{c, {}, {}}});
    s.sampleDistance = 4.0 * g.spacing.minCoeff();
    const Image image = renderGridIso(linear, m, s);
    const HitErrors e = hitErrors(image, s, diagonal, [&](const Vec3d& o, const Vec3d& d) {
      const double t = (c - gradient.dot(o)) / gradient.dot(d);
      const Vec3d p = o + t * d;
      // Inside the box, away from its faces (where a ray may graze the plane's edge).
      const Vec3d margin = 0.05 * (g.boxMax() - g.boxMin());
      const bool inside = (p.array() > (g.boxMin() + margin).array()).all() &&
                          (p.array() < (g.boxMax() - margin).array()).all();
      return inside ? t : NAN;
    });
    EXPECT_GT(e.rays, 50) << methodName(m);
    EXPECT_LT(e.worst, 1e-5) << methodName(m);  // a miss is infinite
    std::printf("%s, plane: %d rays, worst hit error %.2e of the diagonal\n",
                methodName(m).c_str(), e.rays, e.worst);
  }
}

// A single raised sample in a zero grid: trilinear's level set 0.5 around it is a blob a few
// tenths of a spacing across, found at a step of eight spacings; nearest, which has no pieces
// and is sampled, misses its larger cube at that step.
TEST(IsoSurface, GridFiltersFindABlobSmallerThanTheStep) {
  StructuredGrid g;
  g.dims = {9, 9, 9};
  g.origin = Vec3d(0, 0, 0);
  g.spacing = Vec3d(0.25, 0.25, 0.25);
  g.values.assign(size_t(g.sampleCount()), 0.0f);
  g.at(4, 4, 4) = 1.0f;
  RenderSettings s = isoSettings(g, {{0.5, {}, {}}});
  s.camera.focalPoint = g.position(4, 4, 4);
  s.camera.zoom(6.0);
  s.sampleDistance = 8.0 * g.spacing.minCoeff();
  int hits = 0, nearestHits = 0;
  for (float t : renderGridIso(g, ReconstructionMethod::Trilinear, s).depth) hits += !std::isnan(t);
  for (float t : renderGridIso(g, ReconstructionMethod::Nearest, s).depth)
    nearestHits += !std::isnan(t);
  std::printf("blob: trilinear %d hits, nearest %d\n", hits, nearestHits);
  EXPECT_GT(hits, 20);
  EXPECT_LT(nearestHits, hits / 4);
}

// Two concentric spheres of opacity 0.5 each: a ray through the centre crosses four surfaces,
// composited in depth order (1 - 0.5^4); the colours are the surfaces' own.
TEST(IsoSurface, SeveralSemiTransparentSurfacesCompositeInDepthOrder) {
  const StructuredGrid g = quadratic(false);
  const Model model = fitStructured(g, StructuredFitOptions{});
  RenderSettings s = isoSettings(
      g, {{0.09, Vec3f(1, 0, 0), 0.5f}, {0.49, Vec3f(0, 0, 1), 0.5f}});  // radii 0.3, 0.7
  s.earlyTerminationOpacity = 2.0;
  s.camera.focalPoint = kCentre;
  s.camera.position = kCentre + Vec3d(0.3, 0.2, 5.0);
  s.camera.parallelProjection = true;
  s.camera.parallelScale = 0.05;
  s.camera.validate();
  const Image image = renderIso(model, s);
  const float* p = image.pixel(s.width / 2, s.height / 2);
  EXPECT_NEAR(p[3], 1.0 - std::pow(0.5, 4), 1e-5);
  // Front to back: blue (outer) 0.5, red 0.25, red 0.125, blue 0.0625.
  EXPECT_NEAR(p[0], 0.25 + 0.125, 1e-5);
  EXPECT_NEAR(p[2], 0.5 + 0.0625, 1e-5);
}

TEST(IsoSurface, SettingsNeedIsovalues) {
  const StructuredGrid g = quadratic(false);
  RenderSettings s = isoSettings(g, {});
  EXPECT_ANY_THROW(s.validate());
  s.isoSurfaces.assign(kMaxIsoValues + 1, IsoSurface{});
  EXPECT_ANY_THROW(s.validate());
}

}  // namespace
}  // namespace mfadvr
