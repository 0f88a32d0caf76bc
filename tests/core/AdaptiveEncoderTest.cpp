#include "core/encode/AdaptiveEncoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/model/ModelFile.h"

namespace mfadvr {
namespace {

// Largest |model - sample| over every grid sample, measured independently of the encoder.
double maxErrorOverGrid(const Model& m, const StructuredGrid& g) {
  double worst = 0.0;
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
        worst = std::max(worst, std::abs(double(m.value(g.position(i, j, k))) - g.at(i, j, k)));
  return worst;
}

void expectClampedValidKnots(const Model& m) {
  for (int a = 0; a < 3; ++a) {
    const KnotVector& kv = m.spline().knots(a);
    const int p = kv.degree();
    const auto& u = kv.knots();
    for (int i = 0; i <= p; ++i) {
      EXPECT_EQ(u[static_cast<size_t>(i)], 0.0);
      EXPECT_EQ(u[u.size() - 1 - static_cast<size_t>(i)], 1.0);
    }
    EXPECT_TRUE(std::is_sorted(u.begin(), u.end()));
    // fromKnots re-checks clamping, range and multiplicity.
    EXPECT_NO_THROW(KnotVector::fromKnots(p, u));
  }
}

AdaptiveOptions bound(double e) {
  AdaptiveOptions o;
  o.maxRelativeError = e;
  return o;
}

TEST(AdaptiveEncoder, BoundHoldsOnMarschnerLobbAndTighterBoundsNeedMoreControlPoints) {
  // 41^3 is the classic sampling, but so close to Nyquist that any bound needs every sample.
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:81");
  std::int64_t previousCount = 0;
  for (double e : {5e-2, 1e-2, 2e-3}) {
    FitReport r;
    std::vector<AdaptiveRound> rounds;
    AdaptiveOptions o = bound(e);
    o.onRound = [&](const AdaptiveRound& round) { rounds.push_back(round); };
    const Model m = fitStructuredAdaptive(g, StructuredFitOptions{}, o, &r);
    EXPECT_TRUE(r.reachedTarget) << "E=" << e << ": " << r.stopReason;
    EXPECT_LE(maxErrorOverGrid(m, g), e * r.valueRange() * (1 + 1e-9)) << "E=" << e;
    EXPECT_LE(r.maxRelativeError(), e);
    EXPECT_EQ(r.rounds, static_cast<int>(rounds.size()));
    EXPECT_GT(r.rounds, 1);
    EXPECT_EQ(rounds.back().controlCounts, m.spline().counts());
    expectClampedValidKnots(m);
    const Index3 n = m.spline().counts();
    const std::int64_t count = n[0] * n[1] * n[2];
    EXPECT_GT(count, previousCount) << "E=" << e;
    previousCount = count;
    EXPECT_EQ(m.provenance().encoder, "structured-least-squares-adaptive");
    EXPECT_EQ(r.modelBytes, static_cast<std::int64_t>(serializeModel(m).size()));
  }
}

// Non-uniform knots where the data need them: a sharp feature on one side of the box gets
// more knots there than the smooth rest.
TEST(AdaptiveEncoder, KnotsConcentrateWhereTheDataVary) {
  StructuredGrid g;
  g.dims = {65, 9, 9};
  g.spacing = Vec3d(1.0 / 64, 1.0 / 8, 1.0 / 8);
  g.values.resize(65 * 9 * 9);
  for (std::int64_t k = 0; k < 9; ++k)
    for (std::int64_t j = 0; j < 9; ++j)
      for (std::int64_t i = 0; i < 65; ++i) g.at(i, j, k) = std::tanh((i / 64.0 - 0.8) * 40.0);
  FitReport r;
  const Model m = fitStructuredAdaptive(g, StructuredFitOptions{}, bound(1e-3), &r);
  EXPECT_TRUE(r.reachedTarget) << r.stopReason;
  const auto& u = m.spline().knots(0).knots();
  const auto near = std::count_if(u.begin(), u.end(), [](double x) { return x > 0.6 && x < 1.0; });
  const auto far = std::count_if(u.begin(), u.end(), [](double x) { return x > 0.0 && x < 0.4; });
  EXPECT_GT(near, 2 * far);
  EXPECT_LT(m.spline().counts()[1], 9);  // nothing varies along y
}

TEST(AdaptiveEncoder, LimitsStopRefinementAndReturnTheBestModel) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:41");
  AdaptiveOptions o = bound(1e-4);
  o.maxControlCounts = {12, 12, 12};
  FitReport r;
  const Model m = fitStructuredAdaptive(g, StructuredFitOptions{}, o, &r);
  EXPECT_FALSE(r.reachedTarget);
  EXPECT_NE(r.stopReason.find("limit"), std::string::npos) << r.stopReason;
  for (int a = 0; a < 3; ++a) EXPECT_LE(m.spline().counts()[a], 12);
  EXPECT_NEAR(maxErrorOverGrid(m, g), r.maxError, 1e-6 * r.valueRange());

  AdaptiveOptions two = bound(1e-4);
  two.maxRounds = 2;
  FitReport r2;
  fitStructuredAdaptive(g, StructuredFitOptions{}, two, &r2);
  EXPECT_EQ(r2.rounds, 2);
  EXPECT_NE(r2.stopReason.find("round limit"), std::string::npos) << r2.stopReason;
}

TEST(AdaptiveEncoder, RejectsBadOptions) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:gaussian-beam:16");
  test::expectError([&] { fitStructuredAdaptive(g, StructuredFitOptions{}, bound(0.0)); },
                    {"bound"});
  test::expectError([&] { fitStructuredAdaptive(g, StructuredFitOptions{}, bound(NAN)); },
                    {"bound"});
  AdaptiveOptions o = bound(1e-2);
  o.maxRounds = 0;
  test::expectError([&] { fitStructuredAdaptive(g, StructuredFitOptions{}, o); }, {"round"});
}

// 6000 random points of the Gaussian beam in [-1,1]^3.
ScatteredData beamPoints(unsigned seed) {
  const auto beam = makeBuiltin("gaussian-beam");
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  ScatteredData d;
  for (int i = 0; i < 6000; ++i) {
    const Vec3d x(u(rng), u(rng), u(rng));
    d.points.push_back(x);
    d.values.push_back(beam->value(x));
  }
  return d;
}

TEST(AdaptiveEncoder, ScatteredBoundHolds) {
  const ScatteredData d = beamPoints(3);
  FitReport r;
  const Model m = fitScatteredAdaptive(d, ScatteredFitOptions{}, bound(1e-2), &r);
  EXPECT_TRUE(r.reachedTarget) << r.stopReason;
  EXPECT_GT(r.rounds, 1);
  double worst = 0.0;
  for (size_t i = 0; i < d.points.size(); ++i)
    worst = std::max(worst, std::abs(double(m.value(d.points[i])) - d.values[i]));
  EXPECT_LE(worst, 1e-2 * r.valueRange() * (1 + 1e-9));
  expectClampedValidKnots(m);
  EXPECT_EQ(m.provenance().encoder, "scattered-least-squares-adaptive");
}

// The memory estimate of a scattered fit: a first round that does not fit is refused before it
// starts; a later round that would not fit stops the refinement with the best model so far.
TEST(AdaptiveEncoder, ScatteredRefinementStopsAtTheMemoryLimit) {
  const ScatteredData d = beamPoints(5);
  const Degree3 cubic{3, 3, 3};
  // More control points need more, and 256^3 of them gigabytes whatever the points.
  EXPECT_LT(scatteredFitPeakBytes(6000, {5, 5, 5}, cubic),
            scatteredFitPeakBytes(6000, {9, 9, 9}, cubic));
  EXPECT_GT(scatteredFitPeakBytes(100000, {256, 256, 256}, cubic), std::int64_t{4'000'000'000});
  struct Limit {
    explicit Limit(std::int64_t bytes) {
      setenv("MFADVR_MEMORY_LIMIT", std::to_string(bytes).c_str(), 1);
    }
    ~Limit() { unsetenv("MFADVR_MEMORY_LIMIT"); }
  };
  const std::int64_t first = scatteredFitPeakBytes(6000, {5, 5, 5}, cubic);
  {
    const Limit limit(first + 200'000);  // the first round and little more
    FitReport r;
    const Model m = fitScatteredAdaptive(d, ScatteredFitOptions{}, bound(1e-5), &r);
    EXPECT_FALSE(r.reachedTarget);
    EXPECT_NE(r.stopReason.find("memory limit: the next round ("), std::string::npos)
        << r.stopReason;
    EXPECT_GE(r.rounds, 1);
    expectClampedValidKnots(m);
    // A fixed fit that needs more is refused before it starts, with advice.
    ScatteredFitOptions big;
    big.controlCounts = {40, 40, 40};
    test::expectError([&] { fitScattered(d, big); }, {"40x40x40 control points", "--ctrl"});
  }
  {
    const Limit limit(first / 2);
    test::expectError([&] { fitScatteredAdaptive(d, ScatteredFitOptions{}, bound(1e-2)); },
                      {"first round of the adaptive fit", "5x5x5"});
  }
}

}  // namespace
}  // namespace mfadvr
