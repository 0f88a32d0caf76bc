#include "core/spline/SpanRanges.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

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
  const std::int64_t N0 = dims[0], N1 = dims[1], N2 = dims[2];
  const std::int64_t X = r.cells[0], Y = r.cells[1], Z = r.cells[2], plane = X * Y;
  const int w0 = v.axis[0].degree + 1, w1 = v.axis[1].degree + 1, w2 = v.axis[2].degree + 1;
  if (plane * Z <= 0) return r;

  // The whole range (NaN anywhere makes it NaN), and the finite one that the levels cover.
  struct Extremes {
    float lowest = INFINITY, highest = -INFINITY, finiteLow = INFINITY, finiteHigh = -INFINITY;
    bool nan = false;
  };
  const Extremes whole = tbb::parallel_reduce(
      tbb::blocked_range<std::int64_t>(0, N0 * N1 * N2, 1 << 16), Extremes{},
      [&](const auto& range, Extremes e) {
        for (std::int64_t i = range.begin(); i < range.end(); ++i) {
          const float c = v.ctrl[i];
          if (c != c) {
            e.nan = true;
            continue;
          }
          e.lowest = std::min(e.lowest, c);
          e.highest = std::max(e.highest, c);
          if (std::isfinite(c)) {
            e.finiteLow = std::min(e.finiteLow, c);
            e.finiteHigh = std::max(e.finiteHigh, c);
          }
        }
        return e;
      },
      [](Extremes a, const Extremes& b) {
        a.lowest = std::min(a.lowest, b.lowest);
        a.highest = std::max(a.highest, b.highest);
        a.finiteLow = std::min(a.finiteLow, b.finiteLow);
        a.finiteHigh = std::max(a.finiteHigh, b.finiteHigh);
        a.nan = a.nan || b.nan;
        return a;
      });
  r.lowest = whole.nan ? NAN : whole.lowest;
  r.highest = whole.nan ? NAN : whole.highest;
  const bool anyFinite = whole.finiteLow <= whole.finiteHigh;
  r.levelBase = anyFinite ? whole.finiteLow : 0.0f;
  r.levelTop = anyFinite ? whole.finiteHigh : 0.0f;
  r.levelStep = (static_cast<double>(r.levelTop) - r.levelBase) / kTop;
  // The highest level at or below lo and the lowest at or above hi (checked on the very levels
  // bounds() gives, whatever the rounding of the division).
  const auto lowLevel = [&r](float lo) {
    int q = r.levelStep > 0.0
                ? static_cast<int>(std::clamp(std::floor((lo - double(r.levelBase)) / r.levelStep),
                                              0.0, double(kTop)))
                : 0;
    while (q > 0 && r.level(q) > lo) --q;
    return static_cast<std::uint16_t>(q);
  };
  const auto highLevel = [&r](float hi) {
    int q = r.levelStep > 0.0
                ? static_cast<int>(std::clamp(std::ceil((hi - double(r.levelBase)) / r.levelStep),
                                              0.0, double(kTop)))
                : 0;
    while (q < kTop && r.level(q) < hi) ++q;
    return static_cast<std::uint16_t>(q);
  };

  // The least of lo and the greatest of hi over `window` entries `stride` apart, into out;
  // written so that a NaN among them makes the result NaN (std::min would drop it).
  auto slide = [](const float* lo, const float* hi, std::int64_t stride, int window, float* loOut,
                  float* hiOut) {
    float l = lo[0], h = hi[0];
    for (int w = 1; w < window; ++w) {
      const float a = lo[w * stride], b = hi[w * stride];
      l = a < l || a != a ? a : l;
      h = b > h || b != b ? b : h;
    }
    *loOut = l;
    *hiOut = h;
  };
  r.low.resize(static_cast<size_t>(plane * Z));
  r.high.resize(r.low.size());
  // Slabs of cell planes, one per task: control-point planes slid along x and y into a ring of
  // w2 planes, which a cell plane then slides along z.
  const std::int64_t slab = std::max<std::int64_t>(4, Z / 64);
  tbb::parallel_for(std::int64_t(0), (Z + slab - 1) / slab, [&](std::int64_t task) {
    const std::int64_t z0 = task * slab, z1 = std::min(Z, z0 + slab);
    std::vector<float> lx(static_cast<size_t>(X * N1)), hx(lx.size());
    std::vector<float> ringLo(static_cast<size_t>(plane * w2)), ringHi(ringLo.size());
    std::int64_t ready = z0;  // control planes z0 .. ready - 1 are in the ring
    for (std::int64_t z = z0; z < z1; ++z) {
      for (; ready < std::min(N2, z + w2); ++ready) {
        const float* c = v.ctrl + ready * N0 * N1;
        for (std::int64_t j = 0; j < N1; ++j)
          for (std::int64_t i = 0; i < X; ++i) {
            const std::int64_t at = i + X * j;
            slide(c + i + N0 * j, c + i + N0 * j, 1, w0, &lx[at], &hx[at]);
          }
        float* lo = ringLo.data() + (ready % w2) * plane;
        float* hi = ringHi.data() + (ready % w2) * plane;
        for (std::int64_t j = 0; j < Y; ++j)
          for (std::int64_t i = 0; i < X; ++i) {
            const std::int64_t at = i + X * j;
            slide(&lx[at], &hx[at], X, w1, lo + at, hi + at);
          }
      }
      for (std::int64_t q = 0; q < plane; ++q) {
        float l = ringLo[static_cast<size_t>((z % w2) * plane + q)];
        float h = ringHi[static_cast<size_t>((z % w2) * plane + q)];
        for (int w = 1; w < w2; ++w) {
          const size_t at = static_cast<size_t>(((z + w) % w2) * plane + q);
          l = ringLo[at] < l || ringLo[at] != ringLo[at] ? ringLo[at] : l;
          h = ringHi[at] > h || ringHi[at] != ringHi[at] ? ringHi[at] : h;
        }
        const size_t cell = static_cast<size_t>(q + plane * z);
        if (std::isfinite(l) && std::isfinite(h)) {
          r.low[cell] = lowLevel(l);
          r.high[cell] = highLevel(h);
        } else {
          r.low[cell] = kTop;  // no bounds
          r.high[cell] = 0;
        }
      }
    }
  });

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
