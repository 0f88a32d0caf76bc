// The eight-lane spline kernel against the per-point kernel, bit for bit: values and gradients
// for degrees 1..3, on uniform knots (lanes in and out of the shared spans), irregular knots (no
// shared spans), partly filled batches and batches that reach the array's last cells. Also the
// shared spans' invariant: identical coefficients, and the uniform B-spline's values.
#include "core/spline/SplineLaneKernel.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "RandomSpline.h"
#include "core/spline/BasisFunctions.h"
#include "core/spline/TensorBSpline.h"

namespace mfadvr {
namespace {

[[maybe_unused]] bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(SplineLaneKernel, SharedSpansHaveIdenticalCoefficientsAndTheUniformBasis) {
  for (int p = 1; p <= kMaxDegree; ++p) {
    const KnotVector k = KnotVector::clampedUniform(p, 40);
    const KnotAxisView a = k.view();
    ASSERT_EQ(a.sharedFirst, 2 * p + 1);
    ASSERT_EQ(a.sharedLast, 40 - p - 2);
    const int w = p + 1;
    for (int s = a.sharedFirst; s <= a.sharedLast; ++s) {
      EXPECT_EQ(std::memcmp(a.poly + s * w * w, a.poly + a.sharedFirst * w * w, w * w * 4), 0)
          << "p " << p << " span " << s;
      EXPECT_EQ(a.inverseLength[s], a.inverseLength[a.sharedFirst]);
    }
    // The shared coefficients still give each span its own basis functions.
    for (int s : {a.sharedFirst, (a.sharedFirst + a.sharedLast) / 2, a.sharedLast})
      for (double f : {0.1, 0.5, 0.77}) {
        const double u = k.knots()[s] + f * (k.knots()[s + 1] - k.knots()[s]);
        double ders[kMaxDegree + 1];
        basisDerivatives(k, p, s, u, 0, ders);
        float n[8], unused[8];
        axisBasis<0, 0>(a, locateOnAxis<0>(a, u), n, unused, unused);
        for (int r = 0; r <= p; ++r) EXPECT_NEAR(n[r], ders[r], 1e-6) << "p " << p;
      }
  }
  // Irregular knots share nothing.
  const KnotVector irregular = KnotVector::fromKnots(2, {0, 0, 0, 0.1, 0.5, 0.55, 1, 1, 1});
  EXPECT_GT(irregular.view().sharedFirst, irregular.view().sharedLast);
}

#if defined(MFADVR_SPLINE_LANE_KERNEL)

// Batches of eight points along short random segments (as ray samples are), some near the
// domain's faces and corners; each lane against splineValue / splineValueGradient.
template <int P>
void expectLanesMatchPoints(const TensorBSpline& s, unsigned seed, int* evaluated) {
  const SplineView v = s.view();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int batch = 0; batch < 400; ++batch) {
    double start[3], step[3];
    for (int a = 0; a < 3; ++a) {
      // Every fourth batch starts at a face (ends of the array included).
      start[a] = batch % 4 == 0 ? (batch % 8 == 0 ? 0.999 : 0.001) : uni(rng);
      step[a] = (uni(rng) - 0.5) * 0.08;
    }
    const int n = 1 + batch % 8;
    int span[3][8];
    float tau[3][8];
    double u[8][3];
    for (int i = 0; i < 8; ++i) {
      AxisLocation loc[3];
      for (int a = 0; a < 3; ++a) u[i][a] = start[a] + i * step[a];
      locatePoint<P>(v, u[i], loc);
      for (int a = 0; a < 3; ++a) {
        // Lanes past n hold garbage the kernel must not read.
        span[a][i] = i < n ? loc[a].span : -1000000;
        tau[a][i] = i < n ? loc[a].tau : 1e30f;
      }
    }
    float value[8], grad[3][8], valueOnly[8], unused[3][8];
    if (!evaluateLanes<P, 1>(v, span, tau, n, value, grad)) continue;  // the last cells
    ASSERT_TRUE((evaluateLanes<P, 0>(v, span, tau, n, valueOnly, unused)));
    ++*evaluated;
    for (int i = 0; i < n; ++i) {
      float expected[4];
      splineValueGradient<P>(v, u[i], expected);
      const float point = splineValue<P>(v, u[i]);
      EXPECT_TRUE(sameBits(valueOnly[i], point))
          << "P " << P << " lane " << i << ": " << valueOnly[i] << " vs " << point;
      EXPECT_TRUE(sameBits(value[i], expected[0])) << "P " << P << " lane " << i;
      for (int a = 0; a < 3; ++a)
        EXPECT_TRUE(sameBits(grad[a][i], expected[1 + a]))
            << "P " << P << " lane " << i << " axis " << a << ": " << grad[a][i] << " vs "
            << expected[1 + a];
    }
  }
}

TEST(SplineLaneKernel, LanesEqualThePerPointKernelBitForBit) {
  int evaluated = 0;
  expectLanesMatchPoints<1>(randomSpline({1, 1, 1}, {20, 17, 23}, 1), 2, &evaluated);
  expectLanesMatchPoints<2>(randomSpline({2, 2, 2}, {21, 18, 25}, 3), 4, &evaluated);
  expectLanesMatchPoints<3>(randomSpline({3, 3, 3}, {19, 24, 16}, 5), 6, &evaluated);
  // Few control points: no shared spans on any axis.
  expectLanesMatchPoints<2>(randomSpline({2, 2, 2}, {5, 4, 6}, 7), 8, &evaluated);
  TensorBSpline irregular = randomSpline({2, 2, 2}, {12, 11, 13}, 9);
  irregular = irregular.withInsertedKnot(0, 0.123).withInsertedKnot(1, 0.61);
  expectLanesMatchPoints<2>(irregular, 10, &evaluated);
  EXPECT_GT(evaluated, 1500);  // most batches take the lane kernel
}

TEST(SplineLaneKernel, DeclinesBatchesThatReachTheArraysLastCells) {
  const TensorBSpline s = randomSpline({2, 2, 2}, {9, 9, 9}, 11);
  const SplineView v = s.view();
  const double corner[3] = {1.0, 1.0, 1.0};
  AxisLocation loc[3];
  locatePoint<2>(v, corner, loc);
  int span[3][8];
  float tau[3][8];
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 8; ++i) {
      span[a][i] = loc[a].span;
      tau[a][i] = loc[a].tau;
    }
  float value[8], grad[3][8];
  EXPECT_FALSE((evaluateLanes<2, 0>(v, span, tau, 8, value, grad)));
}

#else

TEST(SplineLaneKernel, LanesEqualThePerPointKernelBitForBit) {
  GTEST_SKIP() << "no eight-lane kernel on this build (needs AVX2 and FMA)";
}

#endif

}  // namespace
}  // namespace mfadvr
