// The local reconstruction filters: interpolation of the samples, exact reproduction of linear
// fields up to the boundary, analytic gradients, and tricubic == Catmull-Rom.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "core/field/DerivedFields.h"
#include "core/field/GridField.h"
#include "core/field/GridFilters.h"
#include "core/field/LekienMarsden.h"
#include "core/field/PaddedGrid.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

StructuredGrid makeGrid(const Index3& dims, const Vec3d& origin, const Vec3d& spacing,
                        const std::function<double(const Vec3d&)>& f) {
  StructuredGrid g;
  g.dims = dims;
  g.origin = origin;
  g.spacing = spacing;
  g.values.resize(static_cast<size_t>(g.sampleCount()));
  for (std::int64_t k = 0; k < dims[2]; ++k)
    for (std::int64_t j = 0; j < dims[1]; ++j)
      for (std::int64_t i = 0; i < dims[0]; ++i) g.at(i, j, k) = f(g.position(i, j, k));
  return g;
}

double linear(const Vec3d& x) {
  return 1.0 + 2.0 * x[0] - 3.0 * x[1] + 0.5 * x[2];
}

std::vector<Vec3d> randomPoints(const Vec3d& lo, const Vec3d& hi, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3d> points;
  for (int i = 0; i < n; ++i)
    points.push_back(lo + Vec3d(u(rng), u(rng), u(rng)).cwiseProduct(hi - lo));
  // The corners and faces are where boundary handling shows.
  points.push_back(lo);
  points.push_back(hi);
  points.push_back(Vec3d(lo[0], hi[1], 0.5 * (lo[2] + hi[2])));
  return points;
}

template <class Filter>
void expectLinearReproduced(bool valueExact) {
  // Anisotropic, non-cubic, offset grid.
  const StructuredGrid g = makeGrid({5, 6, 7}, Vec3d(-1, 2, 3), Vec3d(0.5, 1.0, 2.0), linear);
  const GridField<Filter> field(g);
  auto s = field.sampler();
  for (const Vec3d& x : randomPoints(field.boxMin(), field.boxMax(), 300, 7)) {
    const ValueGradient vg = s.valueGradient(x);
    if (valueExact) {
      EXPECT_NEAR(vg.value, linear(x), 2e-5 * 20) << x.transpose();
      EXPECT_NEAR(s.value(x), linear(x), 2e-5 * 20) << x.transpose();
    }
    EXPECT_NEAR(vg.gradient[0], 2.0, 1e-4) << x.transpose();
    EXPECT_NEAR(vg.gradient[1], -3.0, 1e-4) << x.transpose();
    EXPECT_NEAR(vg.gradient[2], 0.5, 1e-4) << x.transpose();
  }
}

TEST(GridFilters, ReproduceLinearFieldsExactly) {
  expectLinearReproduced<TrilinearFilter>(true);
  expectLinearReproduced<CatmullRomFilter>(true);
  expectLinearReproduced<TricubicFilter>(true);
  expectLinearReproduced<BSplineFilter>(true);
  // Nearest is piecewise constant: only its (central-difference) gradient is exact.
  expectLinearReproduced<NearestFilter>(false);
}

template <class Filter>
void expectInterpolates(const StructuredGrid& g) {
  const GridField<Filter> field(g);
  auto s = field.sampler();
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
        ASSERT_NEAR(s.value(g.position(i, j, k)), g.at(i, j, k), 2e-5) << i << " " << j << " " << k;
}

StructuredGrid randomGrid(const Index3& dims, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return makeGrid(dims, Vec3d(0.25, -1, 0), Vec3d(0.7, 0.3, 1.1),
                  [&](const Vec3d&) { return u(rng); });
}

TEST(GridFilters, InterpolateTheSamples) {
  const StructuredGrid g = randomGrid({6, 5, 4}, 3);
  expectInterpolates<NearestFilter>(g);
  expectInterpolates<TrilinearFilter>(g);
  expectInterpolates<CatmullRomFilter>(g);
  expectInterpolates<TricubicFilter>(g);
  expectInterpolates<BSplineFilter>(g);
}

TEST(GridFilters, TricubicWithCentralDifferencesIsCatmullRom) {
  const StructuredGrid g = randomGrid({7, 6, 5}, 11);
  const GridField<TricubicFilter> tricubic(g);
  const GridField<CatmullRomFilter> catmullRom(g);
  auto a = tricubic.sampler();
  auto b = catmullRom.sampler();
  for (const Vec3d& x : randomPoints(tricubic.boxMin(), tricubic.boxMax(), 500, 5)) {
    const ValueGradient va = a.valueGradient(x), vb = b.valueGradient(x);
    EXPECT_NEAR(va.value, vb.value, 1e-5);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(va.gradient[d], vb.gradient[d], 1e-4);
  }
}

// Analytic gradients agree with central differences of the filter's own values.
template <class Filter>
void expectGradientMatchesValues(const StructuredGrid& g) {
  const GridField<Filter> field(g);
  auto s = field.sampler();
  const double h = 1e-4;
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int n = 0; n < 200; ++n) {
    const Vec3d x = field.boxMin() +
                    Vec3d(u(rng), u(rng), u(rng)).cwiseProduct(field.boxMax() - field.boxMin());
    const ValueGradient vg = s.valueGradient(x);
    for (int d = 0; d < 3; ++d) {
      Vec3d p = x, m = x;
      p[d] += h;
      m[d] -= h;
      const double fd = (double(s.value(p)) - double(s.value(m))) / (2 * h);
      EXPECT_NEAR(vg.gradient[d], fd, 2e-2 * (1.0 + std::abs(fd))) << "axis " << d;
    }
  }
}

TEST(GridFilters, AnalyticGradientsMatchTheirValues) {
  const StructuredGrid g = makeGrid(
      {9, 8, 7}, Vec3d(0, 0, 0), Vec3d(0.5, 0.6, 0.7),
      [](const Vec3d& x) { return std::sin(x[0]) * std::cos(0.7 * x[1]) + 0.3 * x[2] * x[2]; });
  expectGradientMatchesValues<TrilinearFilter>(g);
  expectGradientMatchesValues<CatmullRomFilter>(g);
  expectGradientMatchesValues<TricubicFilter>(g);
  expectGradientMatchesValues<BSplineFilter>(g);
}

TEST(GridFilters, BSplineIsSmootherThanCatmullRomOnAQuadratic) {
  // A cubic spline with natural ends is exact for linear data and close for smooth data: check
  // that it is at least as close as Catmull-Rom away from the boundary on a quadratic.
  auto q = [](const Vec3d& x) { return x[0] * x[0] + 0.5 * x[1] * x[1] - x[2] * x[2]; };
  const StructuredGrid g = makeGrid({12, 12, 12}, Vec3d(0, 0, 0), Vec3d(1, 1, 1), q);
  const GridField<BSplineFilter> bs(g);
  auto s = bs.sampler();
  double worst = 0.0;
  for (const Vec3d& x : randomPoints(Vec3d(3, 3, 3), Vec3d(8, 8, 8), 200, 9))
    worst = std::max(worst, std::abs(s.value(x) - q(x)));
  EXPECT_LT(worst, 0.02);
}

TEST(GridFilters, CentralDifferenceFieldGivesExactGradientOfLinear) {
  const StructuredGrid g = makeGrid({5, 5, 5}, Vec3d(0, 0, 0), Vec3d(1, 1, 1), linear);
  const CentralDifferenceField cd(GridField<TrilinearFilter>(g), Vec3d(1, 1, 1));
  auto s = cd.sampler();
  for (const Vec3d& x : randomPoints(cd.boxMin(), cd.boxMax(), 100, 4)) {
    const ValueGradient vg = s.valueGradient(x);
    EXPECT_NEAR(vg.gradient[0], 2.0, 1e-4);
    EXPECT_NEAR(vg.gradient[1], -3.0, 1e-4);
    EXPECT_NEAR(vg.gradient[2], 0.5, 1e-4);
  }
}

TEST(GridFilters, RejectGridsWithoutCells) {
  const StructuredGrid g = makeGrid({1, 4, 4}, Vec3d(0, 0, 0), Vec3d(1, 1, 1), linear);
  EXPECT_THROW(GridField<TrilinearFilter>{g}, Error);
  EXPECT_THROW(GridField<BSplineFilter>{g}, Error);
}

}  // namespace
}  // namespace mfadvr

namespace mfadvr {
namespace {

TEST(LekienMarsden, FactoredProductEqualsTheFullMatrix) {
  const auto& m = lekienMarsdenMatrix();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 20; ++trial) {
    double b[64], a[64];
    for (double& v : b) v = u(rng);
    lekienMarsdenCoefficients(b, a);
    for (int r = 0; r < 64; ++r) {
      double full = 0.0;
      for (int c = 0; c < 64; ++c) full += m[r * 64 + c] * b[c];
      ASSERT_NEAR(a[r], full, 1e-12) << "row " << r;
    }
  }
  // Spot check against the published matrix: its first row picks f at corner 0, and the row of
  // the x^1 coefficient picks fx at corner 0.
  EXPECT_EQ(m[0 * 64 + 0], 1.0);
  EXPECT_EQ(m[1 * 64 + 8], 1.0);
}

}  // namespace
}  // namespace mfadvr
