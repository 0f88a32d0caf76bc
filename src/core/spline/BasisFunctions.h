#pragma once
// B-spline basis functions and their derivatives (The NURBS Book, algorithms A2.2 and A2.3).
//
// The encoders use them to assemble their systems (in double); KnotVector derives from A2.3 the
// per-span basis polynomials that the evaluation kernel (SplineKernel.h) reads. Force-inlined:
// called with a compile-time degree the loops unroll.
#include "core/spline/KnotVector.h"
#include "core/util/HostDevice.h"

namespace mfadvr {

// N[r] = N_{span-p+r, p}(u), r = 0..p; p must be the knot vector's degree.
MFADVR_INLINE void basisFunctions(const KnotVector& kv, int p, int span, double u, double* N) {
  const double* U = kv.data();
  const double* inv = kv.reciprocalDifferences(span);
  double left[kMaxDegree + 1], right[kMaxDegree + 1];
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = N[r] * inv[(j - 1) * j / 2 + r];  // / (right[r+1] + left[j-r])
      N[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    N[j] = saved;
  }
}

// ders[k * (p+1) + r] = k-th derivative of N_{span-p+r, p} at u, for k = 0..order (order <= p
// gives the non-zero derivatives; higher orders are written as zero).
MFADVR_INLINE void basisDerivatives(const KnotVector& kv, int p, int span, double u, int order,
                                    double* ders) {
  const double* U = kv.data();
  const double* inv = kv.reciprocalDifferences(span);
  // As A2.3, except that the lower triangle holds the reciprocals of the knot differences.
  double ndu[kMaxDegree + 1][kMaxDegree + 1];
  double left[kMaxDegree + 1], right[kMaxDegree + 1];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = u - U[span + 1 - j];
    right[j] = U[span + j] - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = inv[(j - 1) * j / 2 + r];  // lower triangle: 1 / knot difference
      const double temp = ndu[r][j - 1] * ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;  // upper triangle: basis values
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  const int w = p + 1;
  for (int r = 0; r <= p; ++r) ders[r] = ndu[r][p];
  const int top = order < p ? order : p;
  for (int k = top + 1; k <= order; ++k)
    for (int r = 0; r <= p; ++r) ders[k * w + r] = 0.0;

  double a[2][kMaxDegree + 1];
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= top; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] * ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) * ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] * ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k * w + r] = d;
      const int t = s1;
      s1 = s2;
      s2 = t;
    }
  }
  int factor = p;
  for (int k = 1; k <= top; ++k) {
    for (int r = 0; r <= p; ++r) ders[k * w + r] *= factor;
    factor *= (p - k);
  }
}

}  // namespace mfadvr
