#include "core/encode/ScatteredEncoder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/KnotPlacement.h"
#include "core/model/ModelFile.h"

namespace mfadvr {
namespace {

// n points uniformly at random in box [lo, hi]^3 (and the 8 corners, so the box is exact).
std::vector<Vec3d> randomPoints(int n, double lo, double hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<Vec3d> pts;
  for (int c = 0; c < 8; ++c) pts.emplace_back(c & 1 ? hi : lo, c & 2 ? hi : lo, c & 4 ? hi : lo);
  for (int i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  return pts;
}

template <class F>
ScatteredData sample(const std::vector<Vec3d>& pts, F&& f) {
  ScatteredData d;
  d.points = pts;
  for (const Vec3d& p : pts) d.values.push_back(f(p));
  d.source = "test points";
  d.kind = "point cloud";
  return d;
}

ScatteredFitOptions options(int p, std::int64_t n, double smoothing = kDefaultSmoothing) {
  ScatteredFitOptions o;
  o.degree = {p, p, p};
  o.controlCounts = {n, n, n};
  o.smoothing = smoothing;
  return o;
}

// A smooth built-in at 20,000 random points, 16^3 cubic control points: the model is within
// 2% of the value range of the truth everywhere in the box, and its reported errors are the
// real errors at the input points.
TEST(ScatteredEncoder, RecoversSmoothFunctionFromRandomPoints) {
  const auto beam = makeBuiltin("gaussian-beam");
  const ScatteredData d =
      sample(randomPoints(20000, -1, 1, 1), [&](const Vec3d& x) { return beam->value(x); });
  FitReport r;
  ScatteredFitOptions o = options(3, 16);
  o.tolerance = 1e-6;  // the solve's own accuracy is checked below
  const Model m = fitScattered(d, o, &r);
  EXPECT_EQ(m.spline().counts(), (Index3{16, 16, 16}));
  EXPECT_EQ(r.points, d.pointCount());
  EXPECT_GT(r.solverIterations, 0);
  EXPECT_LT(r.solverResidual, 1e-6);
  const double range = r.valueRange();
  EXPECT_LT(r.maxRelativeError(), 0.02);
  double worst = 0.0;
  for (const Vec3d& x : randomPoints(5000, -1, 1, 2))
    worst = std::max(worst, std::abs(m.value(x) - beam->value(x)));
  EXPECT_LT(worst / range, 0.02);
  double maxAtInputs = 0.0;
  for (size_t i = 0; i < d.points.size(); ++i)
    maxAtInputs = std::max(maxAtInputs, std::abs(m.value(d.points[i]) - d.values[i]));
  EXPECT_NEAR(maxAtInputs, r.maxError, 1e-6 * range);
  EXPECT_EQ(r.modelBytes, static_cast<std::int64_t>(serializeModel(m).size()));
  EXPECT_EQ(m.provenance().inputPoints, d.pointCount());
  EXPECT_EQ(m.provenance().encoder, "scattered-least-squares");
}

// A tensor polynomial of degree <= p in each variable lies in the spline space: without
// smoothing the fit reproduces it, and a small smoothing weight moves it only slightly (the
// penalty acts on curvature, so the default weight on a 3-span grid biases it by design).
TEST(ScatteredEncoder, ReproducesTensorPolynomials) {
  const auto poly = [](const Vec3d& x) {
    return 1.0 + 2.0 * x[0] - x[1] * x[1] + 0.5 * x[0] * x[1] * x[2] + x[2] * x[2] * x[2] -
           0.7 * x[0] * x[0] * x[1] * x[2] * x[2];
  };
  const ScatteredData d = sample(randomPoints(6000, -1, 1, 3), poly);
  ScatteredFitOptions exactOptions = options(3, 6, 0.0);
  exactOptions.tolerance = 1e-12;
  const Model exact = fitScattered(d, exactOptions);
  ScatteredFitOptions smoothOptions = options(3, 6, 1e-6);
  smoothOptions.tolerance = 1e-6;  // lambda 1e-6 leaves the system nearly singular
  const Model smooth = fitScattered(d, smoothOptions);
  double worstExact = 0.0, worstSmooth = 0.0;
  for (const Vec3d& x : randomPoints(2000, -1, 1, 4)) {
    worstExact = std::max(worstExact, std::abs(exact.value(x) - poly(x)));
    worstSmooth = std::max(worstSmooth, std::abs(smooth.value(x) - poly(x)));
  }
  EXPECT_LT(worstExact, 1e-5);  // float32 control points
  EXPECT_LT(worstSmooth, 1e-3);

  // Multilinear functions carry no smoothing penalty: reproduced even with heavy smoothing.
  const auto bilinear = [](const Vec3d& x) { return 3.0 - x[0] + 2.0 * x[1] * x[2]; };
  ScatteredFitOptions heavyOptions = options(3, 8, 1.0);
  heavyOptions.tolerance = 1e-6;
  const Model heavy = fitScattered(sample(randomPoints(3000, -1, 1, 5), bilinear), heavyOptions);
  for (const Vec3d& x : randomPoints(500, -1, 1, 6)) EXPECT_NEAR(heavy.value(x), bilinear(x), 1e-4);
}

// Points only in the lower half (z < 0) of the box: the upper half has no data, and the
// smoothing keeps the model there bounded (within one value range of the data) and finite.
TEST(ScatteredEncoder, SmoothingKeepsEmptyRegionsBounded) {
  const auto beam = makeBuiltin("marschner-lobb");
  std::vector<Vec3d> pts = randomPoints(8000, -1, 1, 7);
  std::erase_if(pts, [](const Vec3d& x) { return x[2] > -0.2; });
  pts.emplace_back(1.0, 1.0, 1.0);  // one point at the top keeps the box the full cube
  const ScatteredData d = sample(pts, [&](const Vec3d& x) { return beam->value(x); });
  FitReport r;
  const Model m = fitScattered(d, options(3, 20), &r);
  const double lo = r.valueMin - r.valueRange(), hi = r.valueMax + r.valueRange();
  for (const Vec3d& x : randomPoints(4000, -1, 1, 8)) {
    const float v = m.value(x);
    ASSERT_TRUE(std::isfinite(v));
    EXPECT_GE(v, lo);
    EXPECT_LE(v, hi);
  }
}

// Knots that follow the points' density: uniform at weight 0; towards 1 the spans hold equal
// shares of the points, never narrower than the uniform share allows.
TEST(ScatteredEncoder, KnotsFollowThePointsDensity) {
  std::vector<double> u;
  for (int i = 0; i < 900; ++i) u.push_back(0.1 * i / 899.0);  // 90 % of the points in [0, 0.1]
  for (int i = 0; i < 100; ++i) u.push_back(0.1 + 0.9 * (i + 1) / 100.0);
  std::sort(u.begin(), u.end());
  const KnotVector uniform = knotsFollowingDensity(3, 13, u, 0.0);
  const KnotVector reference = KnotVector::clampedUniform(3, 13);
  ASSERT_EQ(uniform.knots().size(), reference.knots().size());
  for (size_t i = 0; i < uniform.knots().size(); ++i)
    EXPECT_NEAR(uniform.knots()[i], reference.knots()[i], 1e-12);
  const KnotVector dense = knotsFollowingDensity(3, 13, u, 0.75);
  const auto& k = dense.knots();
  int below = 0;
  for (size_t i = 4; i + 4 < k.size(); ++i) {
    below += k[i] < 0.35;
    EXPECT_GE(k[i] - k[i - 1], 0.25 / 10 - 1e-12);  // (1 - weight) / spans
  }
  EXPECT_GE(below, 7);  // of the 9 interior knots (uniform: 3)
  EXPECT_THROW(knotsFollowingDensity(3, 13, u, 1.0), Error);
  EXPECT_THROW(knotsFollowingDensity(3, 13, {}, 0.5), Error);
}

// Where the points gather around a sharp feature (as a mesh is refined where its field varies),
// knots that follow them fit it better than uniform ones with the same control points.
TEST(ScatteredEncoder, DensityKnotsFitARefinedFeatureBetter) {
  std::mt19937 rng(21);
  std::normal_distribution<double> near(0.0, 0.12);
  std::vector<Vec3d> pts = randomPoints(3000, -1, 1, 22);
  for (int i = 0; i < 9000; ++i) {
    const Vec3d p(std::clamp(near(rng), -1.0, 1.0), std::clamp(near(rng), -1.0, 1.0),
                  std::clamp(near(rng), -1.0, 1.0));
    pts.push_back(p);
  }
  const ScatteredData d = sample(pts, [](const Vec3d& x) {
    return std::tanh(12.0 * (x.norm() - 0.15));  // a sharp shell inside the dense region
  });
  ScatteredFitOptions o = options(3, 14, 1e-4);
  FitReport uniform, dense;
  fitScattered(d, o, &uniform);
  o.knotDensity = 0.75;
  fitScattered(d, o, &dense);
  EXPECT_LT(dense.rmsError, 0.8 * uniform.rmsError)
      << "uniform " << uniform.rmsError << ", density " << dense.rmsError;
}

// The coarse-to-fine cascade and one direct solve agree: the cascade only speeds up the solve.
TEST(ScatteredEncoder, CascadeMatchesDirectSolve) {
  const auto beam = makeBuiltin("gaussian-beam");
  const ScatteredData d =
      sample(randomPoints(4000, -1, 1, 9), [&](const Vec3d& x) { return beam->value(x); });
  ScatteredFitOptions o = options(2, 12);
  o.tolerance = 1e-10;
  o.maxIterations = 20000;
  const Model cascade = fitScattered(d, o);
  std::array<KnotVector, 3> knots;
  for (auto& k : knots) k = KnotVector::clampedUniform(2, 12);
  const Model direct = fitScatteredWithKnots(d, knots, o, nullptr);
  for (const Vec3d& x : randomPoints(500, -1, 1, 10))
    EXPECT_NEAR(cascade.value(x), direct.value(x), 1e-3 * 255);
}

TEST(ScatteredEncoder, RejectsBadInput) {
  ScatteredData d = sample(randomPoints(100, 0, 1, 11), [](const Vec3d& x) { return x[0]; });
  test::expectError([&] { fitScattered(d, options(0, 8)); }, {"degree 0"});
  test::expectError([&] { fitScattered(d, options(3, 3)); }, {"too few", "at least 4"});
  test::expectError([&] { fitScattered(d, options(3, 8, -1.0)); }, {"smoothing"});
  ScatteredData flat = d;
  for (Vec3d& p : flat.points) p[2] = 0.5;
  test::expectError([&] { fitScattered(flat, options(3, 8)); }, {"no extent", "z"});
  ScatteredData nan = d;
  nan.values[17] = std::nan("");
  test::expectError([&] { fitScattered(nan, options(3, 8)); }, {"point 17"});
  test::expectError([&] { fitScattered(ScatteredData{}, options(3, 8)); }, {"no points"});
  // Without smoothing, control points that no point touches leave the system singular.
  ScatteredData few = sample(randomPoints(20, 0, 1, 12), [](const Vec3d& x) { return x[0]; });
  test::expectError([&] { fitScattered(few, options(3, 20, 0.0)); }, {"--smooth"});
}

}  // namespace
}  // namespace mfadvr
