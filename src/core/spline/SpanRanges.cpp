#include "core/spline/SpanRanges.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mfadvr {
namespace {

// Largest sum of |coefficients| of one span's basis polynomials: bounds both sum |N_r| and
// the magnitude of every partial sum in Horner's rule.
double basisCoefficientSum(const KnotAxisView& a) {
  const int w = a.degree + 1;
  double worst = 1.0;
  for (int s = a.degree; s < a.count; ++s) {
    double sum = 0.0;
    for (int i = 0; i < w * w; ++i) sum += std::abs(a.poly[static_cast<size_t>(s) * w * w + i]);
    worst = std::max(worst, sum);
  }
  return worst;
}

}  // namespace

SpanRanges SpanRanges::compute(const SplineView& v) {
  SpanRanges r;
  std::int64_t dims[3];
  for (int a = 0; a < 3; ++a) {
    dims[a] = v.axis[a].count;
    r.cells[a] = v.axis[a].count - v.axis[a].degree;
  }
  if (r.cellCount() <= 0) return r;

  // The whole range (NaN anywhere makes it NaN).
  struct Extremes {
    float lowest = INFINITY, highest = -INFINITY;
    bool nan = false;
  };
  const Extremes whole = tbb::parallel_reduce(
      tbb::blocked_range<std::int64_t>(0, dims[0] * dims[1] * dims[2], 1 << 16), Extremes{},
      [&](const auto& range, Extremes e) {
        for (std::int64_t i = range.begin(); i < range.end(); ++i) {
          const float c = v.ctrl[i];
          if (c != c) {
            e.nan = true;
            continue;
          }
          e.lowest = std::min(e.lowest, c);
          e.highest = std::max(e.highest, c);
        }
        return e;
      },
      [](Extremes a, const Extremes& b) {
        a.lowest = std::min(a.lowest, b.lowest);
        a.highest = std::max(a.highest, b.highest);
        a.nan = a.nan || b.nan;
        return a;
      });
  r.lowest = whole.nan ? NAN : whole.lowest;
  r.highest = whole.nan ? NAN : whole.highest;

  // Float rounding of the kernel: each basis value carries about (p+2) roundings of partial
  // sums bounded by the coefficient sum S, and the contraction (p+1)^3 roundings of sums bounded
  // by M (1 + e)^3; a factor 4 on top keeps the bound safe.
  constexpr double eps = 0x1p-24;
  double basis = 1.0;
  int terms = 1;
  for (int a = 0; a < 3; ++a) {
    const int p = v.axis[a].degree;
    basis *= 1.0 + (p + 2) * basisCoefficientSum(v.axis[a]) * eps;
    terms *= p + 1;
  }
  r.relativeRounding = 4.0 * ((basis - 1.0) + 3.0 * terms * basis * eps);
  return r;
}

namespace {

// dst[i] = min(dst[i], src[i]) and the maximum: written as the compare-and-select that SIMD
// min and max instructions perform, so that the loops vectorize (no NaN reaches them).
void minInto(float* dst, const float* src, std::int64_t n) {
  for (std::int64_t i = 0; i < n; ++i) dst[i] = src[i] < dst[i] ? src[i] : dst[i];
}
void maxInto(float* dst, const float* src, std::int64_t n) {
  for (std::int64_t i = 0; i < n; ++i) dst[i] = src[i] > dst[i] ? src[i] : dst[i];
}

// loOut[i] = min and hiOut[i] = max of lo[i + w * stride] and hi[i + w * stride] over
// w = 0 .. window - 1, for i < n.
void slideWindow(const float* lo, const float* hi, std::int64_t stride, int window, std::int64_t n,
                 float* loOut, float* hiOut) {
  std::copy_n(lo, n, loOut);
  std::copy_n(hi, n, hiOut);
  for (int w = 1; w < window; ++w) {
    minInto(loOut, lo + w * stride, n);
    maxInto(hiOut, hi + w * stride, n);
  }
}

}  // namespace

SpanRangeScanner::SpanRangeScanner(const SplineView& v) : v_(v) {
  for (int a = 0; a < 3; ++a) {
    n_[a] = v.axis[a].count;
    w_[a] = v.axis[a].degree + 1;
    cells_[a] = std::max<std::int64_t>(0, n_[a] - v.axis[a].degree);
  }
  const std::int64_t plane = cells_[0] * cells_[1];
  rowLo_.resize(static_cast<size_t>(n_[0]));
  rowHi_.resize(rowLo_.size());
  lx_.resize(static_cast<size_t>(cells_[0] * n_[1]));
  hx_.resize(lx_.size());
  ringLo_.resize(static_cast<size_t>(plane * w_[2]));
  ringHi_.resize(ringLo_.size());
}

void SpanRangeScanner::addControlPlane(std::int64_t k) {
  const std::int64_t N0 = n_[0], N1 = n_[1], X = cells_[0], Y = cells_[1];
  const float* c = v_.ctrl + k * N0 * N1;
  for (std::int64_t j = 0; j < N1; ++j) {
    // A value that is not finite widens its cells' bounds to the whole line, which no transfer
    // function can make transparent.
    const float* row = c + N0 * j;
    for (std::int64_t i = 0; i < N0; ++i) {
      const bool finite = std::abs(row[i]) <= std::numeric_limits<float>::max();
      rowLo_[i] = finite ? row[i] : -INFINITY;
      rowHi_[i] = finite ? row[i] : INFINITY;
    }
    slideWindow(rowLo_.data(), rowHi_.data(), 1, w_[0], X, lx_.data() + X * j, hx_.data() + X * j);
  }
  const std::int64_t plane = X * Y, slot = (k % w_[2]) * plane;
  slideWindow(lx_.data(), hx_.data(), X, w_[1], plane, ringLo_.data() + slot,
              ringHi_.data() + slot);
}

void SpanRangeScanner::plane(std::int64_t z, float* lo, float* hi) {
  if (next_ < z || next_ > z + w_[2]) next_ = z;  // the first plane, or a jump: refill the ring
  for (; next_ < z + w_[2]; ++next_) addControlPlane(next_);
  const std::int64_t plane = cells_[0] * cells_[1];
  std::copy_n(ringLo_.data() + (z % w_[2]) * plane, plane, lo);
  std::copy_n(ringHi_.data() + (z % w_[2]) * plane, plane, hi);
  for (int w = 1; w < w_[2]; ++w) {
    minInto(lo, ringLo_.data() + ((z + w) % w_[2]) * plane, plane);
    maxInto(hi, ringHi_.data() + ((z + w) % w_[2]) * plane, plane);
  }
}

}  // namespace mfadvr
