#pragma once
// Plain views of a tensor-product B-spline: raw pointers into the arrays that KnotVector and
// TensorBSpline own, counts and degrees. The evaluation kernel (SplineKernel.h) works on these
// alone, so that the same code runs on the host and, later, in a CUDA kernel. A view is valid as
// long as the spline it came from is alive and unchanged.
#include <cstdint>

#include "core/util/HostDevice.h"

namespace mfadvr {

// Floats a SIMD row load may read past the p+1 it uses (8-lane vectors, rows of 2 or more).
inline constexpr int kSplineRowPadding = 8;

// One parametric axis: a clamped knot vector on [0,1] and its per-span basis polynomials.
struct KnotAxisView {
  const double* knots = nullptr;  // count + degree + 1 knots
  // Per span s (indexed from 0; spans p..count-1 are the non-empty candidates): the p+1 basis
  // functions N_{s-p+r}, r = 0..p, as polynomials in the span's local coordinate
  // tau = (u - knots[s]) / (knots[s+1] - knots[s]) - 1/2 in [-1/2, 1/2]: coefficient of tau^k
  // of function r at poly[(s * (p+1) + k) * (p+1) + r] (k-major, so Horner's rule runs over all
  // r at once). The array holds kSplineRowPadding floats more after the last span, so that a
  // row can be read as one whole SIMD vector.
  const float* poly = nullptr;
  const double* inverseLength = nullptr;  // per span: 1 / (knots[s+1] - knots[s]), 0 if empty
  int degree = 0;
  int count = 0;  // control points
  // Interior knots equally spaced: O(1) span lookup from these two; else binary search.
  bool regular = false;
  double firstInterior = 1.0;   // knots[p+1]
  double inverseSpacing = 0.0;  // 1 / (knots[p+2] - knots[p+1])
  double interiorSpans = 0.0;   // count - p - 2: the equally long spans p+1 .. count-2
  // Spans sharedFirst .. sharedLast (none when sharedLast < sharedFirst) have the same basis
  // polynomials and inverse length, bit for bit: on a regular axis the spans whose p+1 basis
  // functions see only equally spaced knots (2p+1 .. count-p-2). Eight-lane evaluation
  // (SplineLaneKernel.h) then takes their basis from one set of coefficients.
  int sharedFirst = 1;
  int sharedLast = 0;
};

// The span s in [p, count-1] with knots[s] <= u < knots[s+1]; u outside (0,1) or NaN maps to
// the first or last span, and u = 1 belongs to the last non-empty span. P > 0: the degree, known
// at compile time (it must equal a.degree); 0: read from a.
template <int P = 0>
MFADVR_HD MFADVR_INLINE int findSpan(const KnotAxisView& a, double u) {
  const int p = P > 0 ? P : a.degree;
  if (!(u > 0.0)) return p;  // also NaN
  const int last = a.count - 1;
  if (u >= 1.0) return last;
  const double* U = a.knots;
  if (a.regular) {
    // Compare in double before converting: a tiny spacing makes t too large for an int.
    const double t = (u - a.firstInterior) * a.inverseSpacing;
    int s = !(t >= 0.0)                              ? p
            : t >= static_cast<double>(last - p - 1) ? last
                                                     : p + 1 + static_cast<int>(t);
    // Rounding can put u one span off at a boundary.
    while (s > p && u < U[s]) --s;
    while (s < last && u >= U[s + 1]) ++s;
    return s;
  }
  // Last index s in [p, last] with U[s] <= u (u is inside (0,1) here, so U[p] = 0 <= u).
  int lo = p, hi = last;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (U[mid] <= u)
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

// The whole spline over [0,1]^3; control points x fastest: ctrl[i + n0 * (j + n1 * k)].
struct SplineView {
  const float* ctrl = nullptr;
  KnotAxisView axis[3];
};

}  // namespace mfadvr
