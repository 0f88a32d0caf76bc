#pragma once
// Searches over zfp tolerances 2^k. ZFP keeps the bit planes down to 2^floor(log2 tolerance), so
// only powers of two differ; the coded size falls and the error grows with k, so that a target
// on either is met by bisection over k. Shared by the grid encoder's coding choice
// (CodingChoice.cpp) and the time-series encoder's budgets (TimeSeriesEncoder.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace mfadvr {

// A number for the coding notes of reports, printf-formatted.
inline std::string numberText(double v, const char* format = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// How reports name the tolerance 2^exponent: "2^-3 = 0.125".
inline std::string tolerancePhrase(int exponent) {
  return "2^" + std::to_string(exponent) + " = " + numberText(std::ldexp(1.0, exponent));
}

// The exponents worth trying for values of this extent: from far below float32 resolution (where
// coding no longer adds error) to the extent itself (where every block is nearly empty).
inline std::pair<int, int> toleranceExponentRange(double valueMin, double valueMax) {
  const double scale =
      std::max({std::abs(valueMin), std::abs(valueMax), valueMax - valueMin, 1e-30});
  const int top = static_cast<int>(std::ceil(std::log2(scale)));
  return {top - 26, top + 1};
}

// Largest k in [lo, hi] with pass(k), for pass true up to some k* and false after; lo - 1 when
// none passes.
template <class Pass>
int largestPassing(int lo, int hi, Pass pass) {
  if (!pass(lo)) return lo - 1;
  while (lo < hi) {
    const int mid = lo + (hi - lo + 1) / 2;
    if (pass(mid))
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

// Smallest k in [lo, hi] with pass(k), for pass false up to some k* and true after; hi + 1 when
// none passes.
template <class Pass>
int smallestPassing(int lo, int hi, Pass pass) {
  if (!pass(hi)) return hi + 1;
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (pass(mid))
      hi = mid;
    else
      lo = mid + 1;
  }
  return hi;
}

}  // namespace mfadvr
