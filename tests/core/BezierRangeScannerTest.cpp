// The Bezier ranges of a spline's cells (BezierRangeScanner): exact for a spline that is a
// linear function (uneven knots, mixed degrees), containing every value the kernel computes in
// the cell, never wider than the control points' range, and much narrower on noisy control
// points; and the range that empty-space skipping classifies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/render/EmptySpaceGrid.h"
#include "core/spline/BezierRangeScanner.h"
#include "core/spline/SpanRanges.h"
#include "core/spline/SplineKernel.h"
#include "core/spline/TensorBSpline.h"

namespace mfadvr {
namespace {

// Clamped knots for `count` control points of degree p, interior knots at uneven random places
// (some repeated up to p times when `repeat`).
KnotVector unevenKnots(int p, int count, unsigned seed, bool repeat) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uni(0.02, 0.98);
  std::vector<double> interior;
  while (static_cast<int>(interior.size()) < count - p - 1) {
    const double u = uni(rng);
    const int copies = repeat && interior.size() % 3 == 1 ? p : 1;
    for (int c = 0; c < copies && static_cast<int>(interior.size()) < count - p - 1; ++c)
      interior.push_back(u);
  }
  std::sort(interior.begin(), interior.end());
  std::vector<double> knots(static_cast<size_t>(p + 1), 0.0);
  knots.insert(knots.end(), interior.begin(), interior.end());
  knots.insert(knots.end(), static_cast<size_t>(p + 1), 1.0);
  return KnotVector::fromKnots(p, knots);
}

struct Ranges {
  std::vector<float> lo, hi, bezierLo, bezierHi;
  double rounding = 0.0;
};

Ranges allRanges(const TensorBSpline& spline) {
  const SplineView v = spline.view();
  std::int64_t cells[3];
  for (int a = 0; a < 3; ++a) cells[a] = v.axis[a].count - v.axis[a].degree;
  const std::int64_t plane = cells[0] * cells[1];
  Ranges r;
  for (auto* b : {&r.lo, &r.hi, &r.bezierLo, &r.bezierHi})
    b->resize(static_cast<size_t>(plane * cells[2]));
  SpanRangeScanner hull(v);
  BezierRangeScanner bezier(v);
  r.rounding = bezier.relativeRounding();
  // Planes out of order: each is computed on its own.
  for (std::int64_t z = cells[2] - 1; z >= 0; --z) {
    hull.plane(z, &r.lo[z * plane], &r.hi[z * plane]);
    bezier.plane(z, &r.bezierLo[z * plane], &r.bezierHi[z * plane]);
  }
  return r;
}

double greville(const KnotVector& k, int i) {
  const int p = k.degree();
  double sum = 0.0;
  for (int j = 1; j <= p; ++j) sum += k.knots()[static_cast<size_t>(i + j)];
  return sum / p;
}

// f(u) = u0 + 2 u1 - u2 is reproduced by control points at the Greville abscissae; over a cell
// its range is attained at the cell's corners, and so is its Bezier coefficients' range
// (every coefficient of a linear function lies between the corners' values). The control
// points' range is wider.
TEST(BezierRangeScanner, IsTheRangeOfALinearFunctionOverEachCell) {
  const int degree[3] = {1, 2, 3}, count[3] = {9, 11, 14};
  const std::array<KnotVector, 3> knots = {unevenKnots(degree[0], count[0], 1, false),
                                           unevenKnots(degree[1], count[1], 2, true),
                                           unevenKnots(degree[2], count[2], 3, true)};
  std::vector<float> ctrl;
  for (int k = 0; k < count[2]; ++k)
    for (int j = 0; j < count[1]; ++j)
      for (int i = 0; i < count[0]; ++i)
        ctrl.push_back(static_cast<float>(greville(knots[0], i) + 2.0 * greville(knots[1], j) -
                                          greville(knots[2], k)));
  const TensorBSpline spline(knots, ctrl);
  const Ranges r = allRanges(spline);
  EXPECT_GT(r.rounding, 0.0);
  EXPECT_LT(r.rounding, 1e-5);
  int narrower = 0, nonEmptySpans = 0;
  size_t cell = 0;
  for (int c2 = 0; c2 < count[2] - degree[2]; ++c2)
    for (int c1 = 0; c1 < count[1] - degree[1]; ++c1)
      for (int c0 = 0; c0 < count[0] - degree[0]; ++c0, ++cell) {
        const double* U[3] = {knots[0].data(), knots[1].data(), knots[2].data()};
        const int s[3] = {c0 + degree[0], c1 + degree[1], c2 + degree[2]};
        bool spansAreEmpty = false;
        for (int a = 0; a < 3; ++a) spansAreEmpty |= !(U[a][s[a] + 1] > U[a][s[a]]);
        if (spansAreEmpty) {  // no point lies in the cell; its axis keeps the control points
          EXPECT_LE(r.lo[cell], r.bezierLo[cell] + 1e-6f);
          EXPECT_GE(r.hi[cell], r.bezierHi[cell] - 1e-6f);
          continue;
        }
        ++nonEmptySpans;
        const double lo = U[0][s[0]] + 2.0 * U[1][s[1]] - U[2][s[2] + 1];
        const double hi = U[0][s[0] + 1] + 2.0 * U[1][s[1] + 1] - U[2][s[2]];
        EXPECT_NEAR(r.bezierLo[cell], lo, 2e-6) << c0 << " " << c1 << " " << c2;
        EXPECT_NEAR(r.bezierHi[cell], hi, 2e-6) << c0 << " " << c1 << " " << c2;
        EXPECT_LE(r.lo[cell], r.bezierLo[cell] + 1e-6f);
        EXPECT_GE(r.hi[cell], r.bezierHi[cell] - 1e-6f);
        if (r.hi[cell] - r.lo[cell] > r.bezierHi[cell] - r.bezierLo[cell] + 1e-3f) ++narrower;
      }
  EXPECT_GT(nonEmptySpans, 100);
  EXPECT_GT(narrower, nonEmptySpans / 2);
}

// Random control points: every value the kernel computes in a cell lies in the cell's Bezier
// range widened by the bound (the flags' exactness rests on this), the Bezier range lies within
// the control points' range, and it is much narrower on average.
TEST(BezierRangeScanner, BoundsEveryComputedValueAndIsNarrowerThanTheControlPoints) {
  for (const bool uneven : {false, true}) {
    const int degree[3] = {3, 2, 3}, count[3] = {12, 9, 10};
    std::array<KnotVector, 3> knots;
    for (int a = 0; a < 3; ++a)
      knots[a] = uneven ? unevenKnots(degree[a], count[a], 10 + a, a == 1)
                        : KnotVector::clampedUniform(degree[a], count[a]);
    std::mt19937 rng(uneven ? 7 : 8);
    std::uniform_real_distribution<float> uni(-100.0f, 300.0f);
    std::vector<float> ctrl(static_cast<size_t>(count[0] * count[1] * count[2]));
    for (float& c : ctrl) c = uni(rng);
    const TensorBSpline spline(knots, ctrl);
    const SplineView v = spline.view();
    const Ranges r = allRanges(spline);
    int cells[3];
    for (int a = 0; a < 3; ++a) cells[a] = count[a] - degree[a];
    double hullWidth = 0.0, bezierWidth = 0.0;
    for (size_t q = 0; q < r.lo.size(); ++q) {
      EXPECT_LE(r.lo[q], r.bezierLo[q] + 1e-3f);
      EXPECT_GE(r.hi[q], r.bezierHi[q] - 1e-3f);
      hullWidth += r.hi[q] - r.lo[q];
      bezierWidth += r.bezierHi[q] - r.bezierLo[q];
    }
    EXPECT_LT(bezierWidth, 0.6 * hullWidth) << "uneven " << uneven;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int t = 0; t < 20000; ++t) {
      double u[3] = {unit(rng), unit(rng), unit(rng)};
      if (t % 4 == 0) u[t % 3] = knots[t % 3].knots()[static_cast<size_t>(degree[t % 3] + 2)];
      AxisLocation loc[3];
      locatePoint(v, u, loc);
      const size_t cell = static_cast<size_t>(
          (loc[0].span - degree[0]) +
          cells[0] * ((loc[1].span - degree[1]) + cells[1] * (loc[2].span - degree[2])));
      const float value = splineValue<0>(v, u);
      const float magnitude = std::max(std::abs(r.lo[cell]), std::abs(r.hi[cell]));
      const float slack =
          static_cast<float>((r.rounding + spline.spanRanges()->relativeRounding) * magnitude);
      EXPECT_GE(value, r.bezierLo[cell] - slack) << "uneven " << uneven << " cell " << cell;
      EXPECT_LE(value, r.bezierHi[cell] + slack) << "uneven " << uneven << " cell " << cell;
    }
  }
}

// The centre values are the spline at each cell's centre; a plane asked for some cells only
// gives those cells the ranges of the full computation and leaves the others as they were.
TEST(BezierRangeScanner, CentresAndCellsAskedFor) {
  const int degree[3] = {2, 3, 1}, count[3] = {21, 10, 8};
  const std::array<KnotVector, 3> knots = {unevenKnots(degree[0], count[0], 21, false),
                                           unevenKnots(degree[1], count[1], 22, true),
                                           KnotVector::clampedUniform(degree[2], count[2])};
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
  std::vector<float> ctrl(static_cast<size_t>(count[0] * count[1] * count[2]));
  for (float& c : ctrl) c = uni(rng);
  const TensorBSpline spline(knots, ctrl);
  const SplineView v = spline.view();
  int cells[3];
  for (int a = 0; a < 3; ++a) cells[a] = count[a] - degree[a];
  const int plane = cells[0] * cells[1];
  const Ranges all = allRanges(spline);
  BezierRangeScanner scan(v);
  std::vector<float> centre(static_cast<size_t>(plane));
  std::vector<std::uint8_t> need(static_cast<size_t>(plane));
  int asked = 0, untouched = 0, checkedCentres = 0;
  for (int z = 0; z < cells[2]; ++z) {
    scan.centres(z, centre.data());
    for (int y = 0; y < cells[1]; ++y)
      for (int x = 0; x < cells[0]; ++x) {
        const int c[3] = {x, y, z};
        double u[3];
        bool spanEmpty = false;
        for (int a = 0; a < 3; ++a) {
          const double* U = knots[a].data();
          const int s = c[a] + degree[a];
          spanEmpty |= !(U[s + 1] > U[s]);
          u[a] = 0.5 * (U[s] + U[s + 1]);
        }
        if (spanEmpty) continue;  // no point lies in the cell: its centre is not asked for
        ++checkedCentres;
        EXPECT_NEAR(centre[static_cast<size_t>(x + cells[0] * y)], splineValue<0>(v, u), 1e-5f)
            << x << " " << y << " " << z;
      }
    for (int q = 0; q < plane; ++q) need[static_cast<size_t>(q)] = (q * 7 + z) % 23 == 0;
    std::vector<float> lo(static_cast<size_t>(plane), 42.0f), hi(lo.size(), 42.0f);
    scan.plane(z, lo.data(), hi.data(), need.data());
    for (int q = 0; q < plane; ++q) {
      const size_t i = static_cast<size_t>(q), cell = static_cast<size_t>(z * plane + q);
      if (need[i]) {
        ++asked;
        EXPECT_EQ(lo[i], all.bezierLo[cell]);
        EXPECT_EQ(hi[i], all.bezierHi[cell]);
      } else {
        // A block of 16 cells of a row with no cell asked for is not computed.
        const int x = q % cells[0], start = q - x + x / 16 * 16;
        bool blockAsked = false;
        for (int b = start; b < std::min(start + 16, q - x + cells[0]); ++b)
          blockAsked |= need[static_cast<size_t>(b)] != 0;
        if (!blockAsked) {
          ++untouched;
          EXPECT_EQ(lo[i], 42.0f);
          EXPECT_EQ(hi[i], 42.0f);
        }
      }
    }
  }
  EXPECT_GT(asked, 5);
  EXPECT_GT(untouched, 100);
  EXPECT_GT(checkedCentres, 500);
}

// What skipping classifies: the control points' range narrowed to the Bezier range (widened by
// its rounding) and widened by the kernel's margin; nothing for a cell with a NaN.
TEST(BezierRangeScanner, SkippingRangeNarrowsTheControlPointRange) {
  SpanRanges r;
  r.relativeRounding = 1e-5;
  float lo, hi;
  ASSERT_TRUE(skippingRange(r, 1e-6, 0.0f, 100.0f, 40.0f, 60.0f, lo, hi));
  EXPECT_LT(lo, 40.0f);
  EXPECT_GT(lo, 39.9f);
  EXPECT_GT(hi, 60.0f);
  EXPECT_LT(hi, 60.1f);
  // A Bezier range outside the control points' (it cannot be; a NaN) keeps the latter.
  ASSERT_TRUE(skippingRange(r, 1e-6, 0.0f, 100.0f, NAN, NAN, lo, hi));
  EXPECT_LT(lo, 0.0f);
  EXPECT_GT(hi, 100.0f);
  ASSERT_TRUE(skippingRange(r, 1e-6, 0.0f, 100.0f, -50.0f, 150.0f, lo, hi));
  EXPECT_LT(lo, 0.0f);
  EXPECT_GT(hi, 100.0f);
  EXPECT_LT(hi, 100.1f);
  EXPECT_FALSE(skippingRange(r, 1e-6, -INFINITY, INFINITY, 0.0f, 1.0f, lo, hi));
  // Beyond the magnitude limit the float sums could overflow: the control points' range.
  ASSERT_TRUE(skippingRange(r, 1e-6, 0.0f, 3e37f, 1e37f, 2e37f, lo, hi));
  EXPECT_LE(lo, 0.0f);
  EXPECT_GE(hi, 3e37f);
}

}  // namespace
}  // namespace mfadvr
