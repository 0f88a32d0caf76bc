#include "core/encode/ScatteredSmoothingChoice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/analytic/BuiltinFunction.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

std::vector<Vec3d> randomPoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3d> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
  return pts;
}

ScatteredData beamAt(const std::vector<Vec3d>& pts, double noise, unsigned seed) {
  const auto beam = makeBuiltin("gaussian-beam");
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  ScatteredData d;
  d.points = pts;
  for (const Vec3d& p : pts) d.values.push_back(beam->value(p) + gauss(rng));
  d.source = "test points";
  d.kind = "point cloud";
  return d;
}

ScatteredFitOptions cubic(std::int64_t n, double lambda = kDefaultSmoothing) {
  ScatteredFitOptions o;
  o.controlCounts = {n, n, n};
  o.smoothing = lambda;
  return o;
}

// RMS distance of the fit of `d` with `lambda` from the noise-free beam at other points.
double errorAgainstTruth(const ScatteredData& d, double lambda) {
  const auto beam = makeBuiltin("gaussian-beam");
  const Model m = fitScattered(d, cubic(10, lambda));
  double sumSq = 0.0;
  const std::vector<Vec3d> probes = randomPoints(2000, 99);
  for (const Vec3d& x : probes) {
    const double e = m.value(x) - beam->value(x);
    sumSq += e * e;
  }
  return std::sqrt(sumSq / probes.size());
}

// Noise-free samples get little smoothing; the same points with noise of 5 % of the range get
// much more, and the chosen weight predicts the noise-free function better than both ends of
// the search (almost no smoothing follows the noise, lambda 1 flattens the beam).
TEST(ScatteredSmoothingChoice, SmoothsNoisySamplesMoreAndPredictsTheTruthBetter) {
  const std::vector<Vec3d> pts = randomPoints(4000, 1);
  const ScatteredData clean = beamAt(pts, 0.0, 2);
  const ScatteredSmoothingChoice c = chooseScatteredSmoothing(clean, cubic(10));
  double lo = clean.values[0], hi = lo;
  for (double v : clean.values) lo = std::min(lo, v), hi = std::max(hi, v);
  const ScatteredData noisy = beamAt(pts, 0.05 * (hi - lo), 2);
  const ScatteredSmoothingChoice n = chooseScatteredSmoothing(noisy, cubic(10));
  EXPECT_GE(n.lambda, 30.0 * c.lambda) << c.note << " / " << n.note;
  const double chosen = errorAgainstTruth(noisy, n.lambda);
  EXPECT_LT(chosen, 0.8 * errorAgainstTruth(noisy, 1e-6)) << n.note;
  EXPECT_LT(chosen, 0.8 * errorAgainstTruth(noisy, 1.0)) << n.note;
}

// The chosen weight is the one of the smallest held-out error among those tried, about one
// point in eight is held out, and the note says how it was chosen.
TEST(ScatteredSmoothingChoice, ReportsTheCurveItChoseFrom) {
  const ScatteredData d = beamAt(randomPoints(4000, 3), 0.01, 4);
  const ScatteredSmoothingChoice c = chooseScatteredSmoothing(d, cubic(10));
  ASSERT_GE(c.curve.size(), 3u);
  const auto best = std::min_element(c.curve.begin(), c.curve.end(),
                                     [](auto& a, auto& b) { return a.heldOutRms < b.heldOutRms; });
  EXPECT_DOUBLE_EQ(c.lambda, best->lambda);
  EXPECT_DOUBLE_EQ(c.heldOutRms, best->heldOutRms);
  EXPECT_GT(c.heldOutPoints, 4000 / 8 - 100);
  EXPECT_LT(c.heldOutPoints, 4000 / 8 + 100);
  EXPECT_NE(c.note.find("hold-out cross-validation"), std::string::npos) << c.note;
}

TEST(ScatteredSmoothingChoice, TooFewPointsAreAClearError) {
  const ScatteredData d = beamAt(randomPoints(40, 5), 0.0, 6);
  try {
    chooseScatteredSmoothing(d, cubic(4));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at least 64 points"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mfadvr
