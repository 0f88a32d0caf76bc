#include "core/spline/KnotVector.h"

#include <gtest/gtest.h>

#include <random>

#include "core/spline/BasisFunctions.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

TEST(KnotVector, ClampedUniformLayout) {
  const KnotVector k = KnotVector::clampedUniform(3, 7);
  ASSERT_EQ(k.knots().size(), 11u);
  EXPECT_EQ(k.controlCount(), 7);
  EXPECT_TRUE(k.isUniform());
  for (int i = 0; i <= 3; ++i) {
    EXPECT_EQ(k.knots()[i], 0.0);
    EXPECT_EQ(k.knots()[7 + i], 1.0);
  }
  EXPECT_DOUBLE_EQ(k.knots()[4], 0.25);
  EXPECT_DOUBLE_EQ(k.knots()[6], 0.75);
}

TEST(KnotVector, RejectsBadParameters) {
  EXPECT_THROW(KnotVector::clampedUniform(0, 5), Error);
  EXPECT_THROW(KnotVector::clampedUniform(8, 20), Error);
  EXPECT_THROW(KnotVector::clampedUniform(3, 3), Error);
  EXPECT_THROW(KnotVector::fromKnots(2, {0, 0, 0.5, 1, 1, 1}), Error);            // not clamped
  EXPECT_THROW(KnotVector::fromKnots(2, {0, 0, 0, 0.7, 0.5, 1, 1, 1}), Error);    // decreasing
  EXPECT_THROW(KnotVector::fromKnots(2, {0, 0, 0, .5, .5, .5, 1, 1, 1}), Error);  // multiplicity
  EXPECT_NO_THROW(KnotVector::fromKnots(2, {0, 0, 0, .5, .5, 1, 1, 1}));
  EXPECT_THROW(KnotVector::fromKnots(2, {0, 0, 0, 0, 1, 1, 1}), Error);  // empty end span
  EXPECT_THROW(KnotVector::fromKnots(2, {0, 0, 0, 1, 1, 1, 1}), Error);
}

// The O(1) uniform lookup must agree with the definition u_s <= u < u_{s+1} everywhere,
// including exactly at knots.
TEST(KnotVector, SpanLookupMatchesDefinition) {
  for (int p = 1; p <= 7; ++p) {
    for (int n : {p + 1, p + 2, 13, 64, 257}) {
      const KnotVector k = KnotVector::clampedUniform(p, n);
      const auto& U = k.knots();
      std::vector<double> probes = {0.0, 1.0, 1e-300, 1.0 - 1e-16};
      for (int s = 0; s <= n - p; ++s) probes.push_back(static_cast<double>(s) / (n - p));
      std::mt19937 rng(p * 1000 + n);
      std::uniform_real_distribution<double> uni(0.0, 1.0);
      for (int i = 0; i < 200; ++i) probes.push_back(uni(rng));
      for (double u : probes) {
        const int s = k.findSpan(u);
        ASSERT_GE(s, p);
        ASSERT_LE(s, n - 1);
        if (u < 1.0) {
          EXPECT_LE(U[s], u) << "p=" << p << " n=" << n << " u=" << u;
          EXPECT_LT(u, U[s + 1]) << "p=" << p << " n=" << n << " u=" << u;
        }
      }
    }
  }
}

TEST(KnotVector, NonUniformSpanLookup) {
  const KnotVector k = KnotVector::fromKnots(2, {0, 0, 0, 0.1, 0.1, 0.35, 0.9, 1, 1, 1});
  EXPECT_FALSE(k.isUniform());
  EXPECT_EQ(k.findSpan(0.05), 2);
  EXPECT_EQ(k.findSpan(0.1), 4);
  EXPECT_EQ(k.findSpan(0.2), 4);
  EXPECT_EQ(k.findSpan(0.35), 5);
  EXPECT_EQ(k.findSpan(0.95), 6);
  EXPECT_EQ(k.findSpan(1.0), 6);
}

TEST(BasisFunctions, PartitionOfUnityAndDerivativesSumToZero) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int p = 1; p <= 7; ++p) {
    std::vector<double> knots(p + 1, 0.0);
    double t = 0;
    for (int i = 0; i < 6; ++i) knots.push_back(t += 0.1 + uni(rng) * 0.05);
    for (double& v : knots) v = std::min(v, 1.0);
    for (int i = 0; i <= p; ++i) knots.push_back(1.0);
    for (size_t i = p + 1; i + p + 1 < knots.size(); ++i) knots[i] /= (t + 0.2);
    const KnotVector k = KnotVector::fromKnots(p, knots);
    for (int trial = 0; trial < 100; ++trial) {
      const double u = uni(rng);
      const int s = k.findSpan(u);
      double d[3 * (kMaxDegree + 1)];
      basisDerivatives(k, p, s, u, 2, d);
      double sum0 = 0, sum1 = 0, sum2 = 0;
      for (int r = 0; r <= p; ++r) {
        EXPECT_GE(d[r], -1e-15);
        sum0 += d[r];
        sum1 += d[(p + 1) + r];
        sum2 += d[2 * (p + 1) + r];
      }
      EXPECT_NEAR(sum0, 1.0, 1e-13);
      EXPECT_NEAR(sum1, 0.0, 1e-9);
      EXPECT_NEAR(sum2, 0.0, 1e-6);
      double N[kMaxDegree + 1];
      basisFunctions(k, p, s, u, N);
      for (int r = 0; r <= p; ++r) EXPECT_NEAR(N[r], d[r], 1e-15);
    }
  }
}

// Derivatives against central differences of the basis values.
TEST(BasisFunctions, DerivativesMatchFiniteDifferences) {
  for (int p = 1; p <= 5; ++p) {
    const KnotVector k = KnotVector::clampedUniform(p, p + 4);
    for (double u : {0.13, 0.37, 0.61, 0.88}) {
      const int s = k.findSpan(u);
      const double h = 1e-6;
      ASSERT_EQ(k.findSpan(u - h), s);
      ASSERT_EQ(k.findSpan(u + h), s);
      double d[2 * (kMaxDegree + 1)], lo[kMaxDegree + 1], hi[kMaxDegree + 1];
      basisDerivatives(k, p, s, u, 1, d);
      basisFunctions(k, p, s, u - h, lo);
      basisFunctions(k, p, s, u + h, hi);
      for (int r = 0; r <= p; ++r) EXPECT_NEAR(d[p + 1 + r], (hi[r] - lo[r]) / (2 * h), 1e-5);
    }
  }
}

}  // namespace
}  // namespace mfadvr
