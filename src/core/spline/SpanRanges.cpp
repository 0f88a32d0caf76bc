#include "core/spline/SpanRanges.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace mfadvr {
namespace {

// Windows of `window` consecutive entries along one axis of a 3-D array of dims `in`, for every
// window start 0..out-1: out has dims `in` with that axis replaced by the number of windows.
void slideAxis(const float* lo, const float* hi, const std::int64_t in[3], int axis, int window,
               std::vector<float>& loOut, std::vector<float>& hiOut) {
  std::int64_t out[3] = {in[0], in[1], in[2]};
  out[axis] = in[axis] - window + 1;
  loOut.assign(static_cast<size_t>(out[0] * out[1] * out[2]), 0.0f);
  hiOut.assign(loOut.size(), 0.0f);
  const std::int64_t strideIn[3] = {1, in[0], in[0] * in[1]};
  const std::int64_t strideOut[3] = {1, out[0], out[0] * out[1]};
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  tbb::parallel_for(std::int64_t(0), out[a2], [&](std::int64_t y) {
    for (std::int64_t x = 0; x < out[a1]; ++x) {
      const std::int64_t bi = x * strideIn[a1] + y * strideIn[a2];
      const std::int64_t bo = x * strideOut[a1] + y * strideOut[a2];
      for (std::int64_t c = 0; c < out[axis]; ++c) {
        float l = lo[bi + c * strideIn[axis]], h = hi[bi + c * strideIn[axis]];
        for (int w = 1; w < window; ++w) {
          l = std::min(l, lo[bi + (c + w) * strideIn[axis]]);
          h = std::max(h, hi[bi + (c + w) * strideIn[axis]]);
        }
        loOut[bo + c * strideOut[axis]] = l;
        hiOut[bo + c * strideOut[axis]] = h;
      }
    }
  });
}

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
  std::vector<float> lo1, hi1, lo2, hi2;
  slideAxis(v.ctrl, v.ctrl, dims, 0, v.axis[0].degree + 1, lo1, hi1);
  dims[0] = r.cells[0];
  slideAxis(lo1.data(), hi1.data(), dims, 1, v.axis[1].degree + 1, lo2, hi2);
  dims[1] = r.cells[1];
  slideAxis(lo2.data(), hi2.data(), dims, 2, v.axis[2].degree + 1, r.min, r.max);

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
