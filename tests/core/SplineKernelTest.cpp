// The header-only spline kernel against a direct double-precision evaluation from The NURBS
// Book's basis derivatives (A2.3), on uniform, irregular (inserted knots) and mixed-degree
// splines; the span lookup of the plain view against a linear search.
#include "core/spline/SplineKernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "RandomSpline.h"
#include "core/spline/BasisFunctions.h"
#include "core/spline/TensorBSpline.h"

namespace mfadvr {
namespace {

// Value, gradient and Hessian by the triple sum over all control points, in double.
void reference(const TensorBSpline& s, const Vec3d& u, double out[10]) {
  double d[3][3][kMaxDegree + 1] = {};
  int span[3], p[3];
  for (int a = 0; a < 3; ++a) {
    const KnotVector& kv = s.knots(a);
    p[a] = kv.degree();
    span[a] = kv.findSpan(u[a]);
    double ders[3 * (kMaxDegree + 1)];
    basisDerivatives(kv, p[a], span[a], u[a], 2, ders);
    for (int o = 0; o < 3; ++o)
      for (int r = 0; r <= p[a]; ++r) d[a][o][r] = ders[o * (p[a] + 1) + r];
  }
  const Index3 n = s.counts();
  const int orders[10][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0},
                             {1, 1, 0}, {1, 0, 1}, {0, 2, 0}, {0, 1, 1}, {0, 0, 2}};
  for (int q = 0; q < 10; ++q) {
    double sum = 0.0;
    for (int k = 0; k <= p[2]; ++k)
      for (int j = 0; j <= p[1]; ++j)
        for (int i = 0; i <= p[0]; ++i) {
          const std::int64_t idx =
              (span[0] - p[0] + i) + n[0] * ((span[1] - p[1] + j) + n[1] * (span[2] - p[2] + k));
          sum += s.controlPoints()[idx] * d[0][orders[q][0]][i] * d[1][orders[q][1]][j] *
                 d[2][orders[q][2]][k];
        }
    out[q] = sum;
  }
}

void expectMatchesReference(const TensorBSpline& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const SplineView v = s.view();
  for (int t = 0; t < 300; ++t) {
    const Vec3d u(uni(rng), uni(rng), uni(rng));
    const double x[3] = {u[0], u[1], u[2]};
    double ref[10];
    reference(s, u, ref);
    // Scales: control points are in [-1, 1]; derivatives grow with the knot density.
    double scale1 = 1.0, scale2 = 1.0;
    for (int a = 0; a < 3; ++a) {
      const double density = s.counts()[a] * s.knots(a).degree();
      scale1 = std::max(scale1, density);
      scale2 = std::max(scale2, density * density);
    }
    float value = 0.0f, vg[4], vgh[10];
    splineDegreeSwitch(v, [&]<int P>() {
      value = splineValue<P>(v, x);
      splineValueGradient<P>(v, x, vg);
      splineValueGradientHessian<P>(v, x, vgh);
    });
    EXPECT_NEAR(value, ref[0], 2e-5) << "u = " << u.transpose();
    EXPECT_NEAR(vg[0], ref[0], 2e-5);
    EXPECT_NEAR(vgh[0], ref[0], 2e-5);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(vg[1 + a], ref[1 + a], 2e-5 * scale1) << "axis " << a;
      EXPECT_NEAR(vgh[1 + a], ref[1 + a], 2e-5 * scale1) << "axis " << a;
    }
    for (int h = 0; h < 6; ++h) EXPECT_NEAR(vgh[4 + h], ref[4 + h], 1e-4 * scale2) << "entry " << h;
    // The degree-generic path (P = 0) computes the same function.
    const float generic = splineValue<0>(v, x);
    EXPECT_NEAR(generic, ref[0], 2e-5);
  }
}

TEST(SplineKernel, MatchesDirectEvaluationForEveryDegree) {
  for (int p = 1; p <= kMaxDegree; ++p)
    expectMatchesReference(randomSpline({p, p, p}, {p + 5, p + 3, p + 9}, 10 + p), 100 + p);
}

TEST(SplineKernel, MatchesDirectEvaluationForMixedDegrees) {
  expectMatchesReference(randomSpline({1, 3, 2}, {7, 9, 5}, 3), 4);
  expectMatchesReference(randomSpline({2, 5, 7}, {9, 8, 12}, 5), 6);
}

TEST(SplineKernel, MatchesDirectEvaluationOnIrregularKnots) {
  TensorBSpline s = randomSpline({3, 3, 3}, {8, 7, 9}, 7);
  s = s.withInsertedKnot(0, 0.123).withInsertedKnot(0, 0.13).withInsertedKnot(1, 0.61);
  s = s.withInsertedKnot(2, 0.5).withInsertedKnot(2, 0.5);  // a double knot
  EXPECT_FALSE(s.knots(0).hasRegularInterior());
  expectMatchesReference(s, 8);
}

TEST(SplineKernel, EndpointsAndOutsideCoordinatesClamp) {
  const TensorBSpline s = randomSpline({3, 2, 1}, {6, 5, 4}, 9);
  const SplineView v = s.view();
  const double corners[][3] = {{0, 0, 0}, {1, 1, 1}, {-0.5, 2.0, 1.0}, {NAN, 0.5, 0.5}};
  const Vec3d clamped[] = {{0, 0, 0}, {1, 1, 1}, {0, 1, 1}, {0, 0.5, 0.5}};
  for (int c = 0; c < 4; ++c) {
    double ref[10];
    reference(s, clamped[c], ref);
    EXPECT_NEAR(splineValue<0>(v, corners[c]), ref[0], 2e-5) << "corner " << c;
  }
}

TEST(SplineKernel, SpanLookupMatchesLinearSearch) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int p = 1; p <= 4; ++p) {
    KnotVector kv = KnotVector::clampedUniform(p, 40);
    kv = kv.withInsertedKnot(0.3333).withInsertedKnot(0.9);
    for (const KnotVector& k : {KnotVector::clampedUniform(p, 40), kv}) {
      const KnotAxisView a = k.view();
      for (int t = 0; t < 2000; ++t) {
        // Mostly random, sometimes exactly on a knot.
        double u = uni(rng);
        if (t % 5 == 0) u = k.knots()[p + (t / 5) % (k.controlCount() - p)];
        int expected = p;
        for (int s = p; s < k.controlCount(); ++s)
          if (k.knots()[s] <= u && k.knots()[s] < k.knots()[s + 1]) expected = s;
        if (u >= 1.0) expected = k.controlCount() - 1;
        EXPECT_EQ(findSpan(a, u), expected) << "u = " << u << ", degree " << p;
      }
    }
  }
}

// The per-span polynomials are the basis: they sum to one and meet continuously at the knots.
TEST(SplineKernel, BasisPolynomialsArePartitionOfUnityAndContinuous) {
  for (int p = 1; p <= kMaxDegree; ++p) {
    const KnotVector k = KnotVector::clampedUniform(p, p + 6).withInsertedKnot(0.41);
    const KnotAxisView a = k.view();
    float N[kMaxDegree + 1], D1[kMaxDegree + 1], D2[kMaxDegree + 1];
    for (int s = p; s < k.controlCount(); ++s) {
      for (float tau : {-0.5f, -0.13f, 0.5f}) {
        axisBasis<0, 0>(a, {s, tau}, N, D1, D2);
        double sum = 0.0;
        for (int r = 0; r <= p; ++r) sum += N[r];
        EXPECT_NEAR(sum, 1.0, 1e-5) << "degree " << p << " span " << s;
      }
      if (s + 1 < k.controlCount()) {
        // End of span s = start of span s + 1, shifted by one function.
        float end[kMaxDegree + 1], start[kMaxDegree + 1];
        axisBasis<0, 0>(a, {s, 0.5f}, end, D1, D2);
        axisBasis<0, 0>(a, {s + 1, -0.5f}, start, D1, D2);
        for (int r = 1; r <= p; ++r) EXPECT_NEAR(end[r], start[r - 1], 1e-5);
        EXPECT_NEAR(end[0], 0.0, 1e-5);
      }
    }
  }
}

}  // namespace
}  // namespace mfadvr
