#pragma once
// Principal curvatures of the level set through a point, from the field's gradient and Hessian
// (Kindlmann, Whitaker, Tasdizen, Moller: "Curvature-based transfer functions for direct volume
// rendering", IEEE Visualization 2003, section 3):
//   n = -g / |g|,  P = I - n n^T,  G = -P H P / |g|,  T = trace G,  F = |G| (Frobenius),
//   k1,2 = (T +- sqrt(2 F^2 - T^2)) / 2,  k1 >= k2.
// Sign: n points toward lower values, so a surface that bends around higher values is positive:
// a sphere of radius r around a maximum (a bright blob) has k1 = k2 = 1 / r, around a minimum
// -1 / r; a cylinder of radius r around a ridge line has (1 / r, 0). Host and device; one copy of
// the formula for queries, rendering and the grid filters.
#include <cmath>

#include "core/util/HostDevice.h"

namespace mfadvr {

struct PrincipalCurvatures {
  double k1 = 0.0, k2 = 0.0;  // k1 >= k2; NaN where the gradient is zero
};

// The curvature tensor of the level set through a point: n = -g / |g| and G = -P H P / |g|
// (row-major 3 x 3). g: gradient (x, y, z); h: Hessian xx, xy, xz, yy, yz, zz. False (n and G
// untouched) where the gradient is zero.
template <class T>
MFADVR_HD MFADVR_INLINE bool curvatureTensor(const T g[3], const T h[6], double n[3],
                                             double G[3][3]) {
  const double gx = g[0], gy = g[1], gz = g[2];
  const double length = sqrt(gx * gx + gy * gy + gz * gz);
  if (!(length > 0.0)) return false;
  n[0] = -gx / length;
  n[1] = -gy / length;
  n[2] = -gz / length;
  const double H[3][3] = {{h[0], h[1], h[2]}, {h[1], h[3], h[4]}, {h[2], h[4], h[5]}};
  double P[3][3], PH[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P[i][j] = (i == j ? 1.0 : 0.0) - n[i] * n[j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int l = 0; l < 3; ++l) s += P[i][l] * H[l][j];
      PH[i][j] = s;
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int l = 0; l < 3; ++l) s += PH[i][l] * P[l][j];
      G[i][j] = -s / length;
    }
  return true;
}

// k1 >= k2 from the curvature tensor: T = trace G, F = |G|, k1,2 = (T +- sqrt(2 F^2 - T^2)) / 2.
MFADVR_HD MFADVR_INLINE PrincipalCurvatures principalCurvaturesOf(const double G[3][3]) {
  double trace = 0.0, frobenius2 = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) frobenius2 += G[i][j] * G[i][j];
  for (int i = 0; i < 3; ++i) trace += G[i][i];
  double root = 2.0 * frobenius2 - trace * trace;
  root = root > 0.0 ? sqrt(root) : 0.0;  // rounding can take an umbilic point below zero
  PrincipalCurvatures k;
  k.k1 = 0.5 * (trace + root);
  k.k2 = 0.5 * (trace - root);
  return k;
}

// The normal curvature of the level set along the direction v projected into its tangent plane:
// kappa_v = v^T G v / v^T P v (Kindlmann et al. 2003, section 5); 0 where v is along n.
MFADVR_HD MFADVR_INLINE double normalCurvature(const double n[3], const double G[3][3],
                                               const double v[3]) {
  const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  const double vPv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - vn * vn;
  if (!(vPv > 1e-12)) return 0.0;
  double vGv = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) vGv += v[i] * G[i][j] * v[j];
  return vGv / vPv;
}

template <class T>
MFADVR_HD MFADVR_INLINE PrincipalCurvatures principalCurvatures(const T g[3], const T h[6]) {
  double n[3], G[3][3];
  if (!curvatureTensor(g, h, n, G)) {
    PrincipalCurvatures k;
    k.k1 = k.k2 = NAN;
    return k;
  }
  return principalCurvaturesOf(G);
}

}  // namespace mfadvr
