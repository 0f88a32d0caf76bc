#include "core/spline/TensorBSpline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <thread>

#include "RandomSpline.h"
#include "core/encode/StructuredEncoder.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

std::vector<Vec3d> randomPoints(int count, unsigned seed, double lo = 0.0, double hi = 1.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(lo, hi);
  std::vector<Vec3d> pts;
  for (int i = 0; i < count; ++i) pts.emplace_back(uni(rng), uni(rng), uni(rng));
  return pts;
}

TEST(TensorBSpline, RejectsMismatchedControlArray) {
  EXPECT_THROW(TensorBSpline({KnotVector::clampedUniform(2, 4), KnotVector::clampedUniform(2, 4),
                              KnotVector::clampedUniform(2, 5)},
                             std::vector<float>(4 * 4 * 4)),
               Error);
}

// All control points 1: the basis sums to one, so value 1 and zero derivatives everywhere. The
// kernel evaluates the basis polynomials in float (Horner's rule), so the sum is 1 up to a few
// float roundings per axis: at most 2e-6 for degree 7.
TEST(TensorBSpline, PartitionOfUnity) {
  for (Degree3 p : {Degree3{1, 1, 1}, Degree3{3, 3, 3}, Degree3{2, 5, 7}}) {
    const Index3 n{p[0] + 3, p[1] + 1, p[2] + 6};
    TensorBSpline s({KnotVector::clampedUniform(p[0], static_cast<int>(n[0])),
                     KnotVector::clampedUniform(p[1], static_cast<int>(n[1])),
                     KnotVector::clampedUniform(p[2], static_cast<int>(n[2]))},
                    std::vector<float>(static_cast<size_t>(n[0] * n[1] * n[2]), 1.0f));
    for (const Vec3d& u : randomPoints(200, 3)) {
      EXPECT_NEAR(s.value(u), 1.0f, 2e-6f);
      const ValueGradient g = s.valueGradient(u);
      EXPECT_NEAR(g.value, 1.0f, 2e-6f);
      EXPECT_NEAR(g.gradient.norm(), 0.0f, 1e-4f);
      const ValueGradientHessian h = s.valueGradientHessian(u);
      EXPECT_NEAR(h.value, 1.0f, 2e-6f);
      for (float v : h.hessian) EXPECT_NEAR(v, 0.0f, 2e-2f);
    }
  }
}

// Coordinates outside [0,1] clamp onto the box; NaN gives a finite answer, not a crash.
TEST(TensorBSpline, OutOfRangeAndNaNCoordinates) {
  const TensorBSpline s = randomSpline({3, 3, 3}, {6, 6, 6}, 1);
  EXPECT_EQ(s.value(Vec3d(-5, 0.5, 7)), s.value(Vec3d(0, 0.5, 1)));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isfinite(s.value(Vec3d(nan, 0.5, 0.5))));
  EXPECT_TRUE(s.valueGradient(Vec3d(0.5, nan, nan)).gradient.allFinite());
}

// The degree-specialized and generic evaluators must agree, and all three query kinds must
// agree on the value.
TEST(TensorBSpline, QueryKindsAgree) {
  for (int p = 1; p <= 7; ++p) {
    const TensorBSpline s = randomSpline({p, p, p}, {p + 4, p + 2, p + 3}, 11 + p);
    for (const Vec3d& u : randomPoints(100, 5)) {
      const float v = s.value(u);
      const ValueGradient g = s.valueGradient(u);
      const ValueGradientHessian h = s.valueGradientHessian(u);
      EXPECT_NEAR(v, g.value, 1e-5f);
      EXPECT_NEAR(v, h.value, 1e-5f);
      EXPECT_NEAR((g.gradient - h.gradient).norm(), 0.0f, 1e-3f * (1 + h.gradient.norm()));
    }
  }
}

// Analytic derivatives against central differences of the value.
TEST(TensorBSpline, DerivativesMatchFiniteDifferences) {
  const TensorBSpline s = randomSpline({3, 2, 4}, {9, 7, 8}, 2);
  const double h = 1e-3;
  for (const Vec3d& u : randomPoints(50, 9, 0.05, 0.95)) {
    const ValueGradientHessian q = s.valueGradientHessian(u);
    for (int a = 0; a < 3; ++a) {
      Vec3d lo = u, hi = u;
      lo[a] -= h;
      hi[a] += h;
      // Second derivatives jump at knots (degree 2 here): difference inside one span only.
      if (s.knots(a).findSpan(lo[a]) != s.knots(a).findSpan(hi[a])) continue;
      // Central differences in double from the float-valued spline: tolerance from rounding.
      const double fd = (double(s.value(hi)) - double(s.value(lo))) / (2 * h);
      EXPECT_NEAR(q.gradient[a], fd, 2e-2 * (1 + std::abs(fd)));
      const ValueGradient gl = s.valueGradient(lo), gh = s.valueGradient(hi);
      const int diag[3] = {0, 3, 5};
      EXPECT_NEAR(q.hessian[diag[a]], (gh.gradient[a] - gl.gradient[a]) / (2 * h),
                  5e-2 * (1 + std::abs(q.hessian[diag[a]])));
    }
  }
}

// Inserting a knot changes the representation, not the function.
TEST(TensorBSpline, KnotInsertionPreservesFunction) {
  const TensorBSpline s = randomSpline({3, 2, 1}, {7, 5, 4}, 4);
  TensorBSpline t = s.withInsertedKnot(0, 0.3).withInsertedKnot(1, 0.5).withInsertedKnot(2, 0.77);
  t = t.withInsertedKnot(0, 0.3);  // a second time at the same place: multiplicity 2
  EXPECT_EQ(t.counts(), (Index3{9, 6, 5}));
  EXPECT_FALSE(t.knots(0).isUniform());
  EXPECT_THROW(t.withInsertedKnot(2, 0.77), Error);  // degree-1 axis: multiplicity 2 > p
  for (const Vec3d& u : randomPoints(300, 8)) {
    EXPECT_NEAR(s.value(u), t.value(u), 2e-6f);
    EXPECT_NEAR((s.valueGradient(u).gradient - t.valueGradient(u).gradient).norm(), 0.0f, 1e-4f);
  }
}

// A const spline queried from many threads gives the same bits as a serial pass.
TEST(TensorBSpline, ConcurrentQueriesMatchSerial) {
  const TensorBSpline s = randomSpline({3, 3, 3}, {20, 18, 16}, 21);
  const auto pts = randomPoints(20000, 12);
  std::vector<ValueGradient> serial(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) serial[i] = s.valueGradient(pts[i]);
  std::vector<std::thread> threads;
  std::vector<int> mismatches(8, 0);
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&, t] {
      for (size_t i = t; i < pts.size(); i += 3) {
        const ValueGradient g = s.valueGradient(pts[i]);
        if (g.value != serial[i].value || g.gradient != serial[i].gradient) ++mismatches[t];
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int m : mismatches) EXPECT_EQ(m, 0);
}

}  // namespace
}  // namespace mfadvr
