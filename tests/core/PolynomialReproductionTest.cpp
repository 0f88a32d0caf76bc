// A least-squares fit of degree p reproduces every polynomial of degree <= p per axis exactly
// (the spline space contains it), on non-cubic, anisotropic grids, in value, gradient and
// Hessian, up to float32 rounding of the control points.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/encode/StructuredEncoder.h"

namespace mfadvr {
namespace {

struct Case {
  Degree3 degree;
  Index3 dims;
  Index3 ctrl;  // 0: interpolate
};

// f = sum over a<=px, b<=py, c<=pz of coef(a,b,c) x^a y^b z^c, with exact derivatives.
struct Polynomial {
  Degree3 p;
  double coef[8][8][8] = {};
  explicit Polynomial(Degree3 deg, unsigned seed) : p(deg) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    for (int a = 0; a <= p[0]; ++a)
      for (int b = 0; b <= p[1]; ++b)
        for (int c = 0; c <= p[2]; ++c) coef[a][b][c] = uni(rng);
  }
  // Mixed partial of order (da, db, dc).
  double eval(const Vec3d& x, int da, int db, int dc) const {
    auto term = [](double v, int e, int d) {
      if (d > e) return 0.0;
      double f = 1.0;
      for (int k = 0; k < d; ++k) f *= e - k;
      return f * std::pow(v, e - d);
    };
    double s = 0.0;
    for (int a = 0; a <= p[0]; ++a)
      for (int b = 0; b <= p[1]; ++b)
        for (int c = 0; c <= p[2]; ++c)
          s += coef[a][b][c] * term(x[0], a, da) * term(x[1], b, db) * term(x[2], c, dc);
    return s;
  }
};

class PolynomialReproduction : public ::testing::TestWithParam<Case> {};

TEST_P(PolynomialReproduction, ValuesGradientsHessians) {
  const Case c = GetParam();
  const Polynomial poly(c.degree, 17);
  StructuredGrid g;
  g.dims = c.dims;
  g.origin = Vec3d(-0.8, 0.3, -0.2);
  g.spacing = Vec3d(1.6 / (c.dims[0] - 1), 0.9 / (c.dims[1] - 1), 1.3 / (c.dims[2] - 1));
  g.values.resize(static_cast<size_t>(g.sampleCount()));
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
        g.at(i, j, k) = poly.eval(g.position(i, j, k), 0, 0, 0);
  g.inputBytes = g.sampleCount() * 8;

  StructuredFitOptions o;
  o.degree = c.degree;
  o.controlCounts = c.ctrl;
  FitReport report;
  const Model m = fitStructured(g, o, &report);
  EXPECT_LT(report.maxError, 2e-6) << "fit error at the samples";

  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const Vec3d lo = g.boxMin(), ext = g.boxMax() - g.boxMin();
  for (int t = 0; t < 200; ++t) {
    const Vec3d x = lo + Vec3d(uni(rng), uni(rng), uni(rng)).cwiseProduct(ext);
    const ValueGradientHessian q = m.valueGradientHessian(x);
    const ValueGradient vg = m.valueGradient(x);
    EXPECT_NEAR(m.value(x), poly.eval(x, 0, 0, 0), 2e-5);
    EXPECT_NEAR(q.value, poly.eval(x, 0, 0, 0), 2e-5);
    const double grad[3] = {poly.eval(x, 1, 0, 0), poly.eval(x, 0, 1, 0), poly.eval(x, 0, 0, 1)};
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(vg.gradient[a], grad[a], 2e-4 * (1 + std::abs(grad[a])));
      EXPECT_NEAR(q.gradient[a], grad[a], 2e-4 * (1 + std::abs(grad[a])));
    }
    const double hess[6] = {poly.eval(x, 2, 0, 0), poly.eval(x, 1, 1, 0), poly.eval(x, 1, 0, 1),
                            poly.eval(x, 0, 2, 0), poly.eval(x, 0, 1, 1), poly.eval(x, 0, 0, 2)};
    for (int h = 0; h < 6; ++h)
      EXPECT_NEAR(q.hessian[h], hess[h], 5e-3 * (1 + std::abs(hess[h]))) << "entry " << h;
  }
}

INSTANTIATE_TEST_SUITE_P(Grids, PolynomialReproduction,
                         ::testing::Values(Case{{1, 1, 1}, {5, 4, 3}, {3, 2, 2}},
                                           Case{{3, 2, 1}, {11, 8, 6}, {6, 5, 3}},
                                           Case{{2, 2, 2}, {9, 10, 7}, {3, 3, 3}},
                                           Case{{3, 3, 3}, {10, 8, 7}, {0, 0, 0}},
                                           Case{{4, 3, 5}, {13, 9, 12}, {8, 6, 7}},
                                           Case{{7, 2, 3}, {12, 6, 9}, {10, 4, 0}}));

}  // namespace
}  // namespace mfadvr
