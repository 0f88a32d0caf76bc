#include "core/spline/SpanRanges.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

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
  // Sliding minimum and maximum over p + 1 control points per axis: x and y plane by plane (a
  // plane's x windows in a per-task buffer) into r.min / r.max, then z in place along those
  // arrays (a window's result goes where its first entry was, which no later window reads), so
  // that only the result's 8 bytes per cell are held.
  const std::int64_t N0 = dims[0], N1 = dims[1], N2 = dims[2];
  const std::int64_t X = r.cells[0], Y = r.cells[1], Z = r.cells[2], plane = X * Y;
  const int w0 = v.axis[0].degree + 1, w1 = v.axis[1].degree + 1, w2 = v.axis[2].degree + 1;
  r.min.resize(static_cast<size_t>(plane * N2));
  r.max.resize(r.min.size());
  // The least of lo and the greatest of hi over `window` entries `stride` apart, into out.
  auto slide = [](const float* lo, const float* hi, std::int64_t stride, int window, float* loOut,
                  float* hiOut) {
    float l = lo[0], h = hi[0];
    for (int w = 1; w < window; ++w) {
      l = std::min(l, lo[w * stride]);
      h = std::max(h, hi[w * stride]);
    }
    *loOut = l;
    *hiOut = h;
  };
  tbb::parallel_for(std::int64_t(0), N2, [&](std::int64_t k) {
    const float* c = v.ctrl + k * N0 * N1;
    std::vector<float> lx(static_cast<size_t>(X * N1)), hx(lx.size());
    for (std::int64_t j = 0; j < N1; ++j)
      for (std::int64_t i = 0; i < X; ++i) {
        const std::int64_t at = i + X * j;
        slide(c + i + N0 * j, c + i + N0 * j, 1, w0, &lx[at], &hx[at]);
      }
    float* lo = r.min.data() + k * plane;
    float* hi = r.max.data() + k * plane;
    for (std::int64_t j = 0; j < Y; ++j)
      for (std::int64_t i = 0; i < X; ++i) {
        const std::int64_t at = i + X * j;
        slide(&lx[at], &hx[at], X, w1, lo + at, hi + at);
      }
  });
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, plane, 1024), [&](const auto& range) {
    float* lo = r.min.data();
    float* hi = r.max.data();
    for (std::int64_t z = 0; z < Z; ++z)
      for (std::int64_t q = range.begin(); q < range.end(); ++q) {
        const std::int64_t at = q + plane * z;
        slide(lo + at, hi + at, plane, w2, lo + at, hi + at);
      }
  });
  r.min.resize(static_cast<size_t>(plane * Z));
  r.max.resize(r.min.size());

  if (!r.min.empty()) {
    r.lowest = r.min[0];
    r.highest = r.max[0];
    for (size_t i = 0; i < r.min.size(); ++i) {
      // Written so that a NaN anywhere makes the result NaN (std::min would drop it).
      r.lowest = r.min[i] < r.lowest || r.min[i] != r.min[i] ? r.min[i] : r.lowest;
      r.highest = r.max[i] > r.highest || r.max[i] != r.max[i] ? r.max[i] : r.highest;
    }
  }

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

}  // namespace mfadvr
