#pragma once
// The tables the isosurface walk (kernel/IsoSurfaceWalk.h) turns a ray piece's values into its
// Bernstein coefficients with: for every degree n = 0..kMaxIsoDegree, the n + 1 Chebyshev-
// Lobatto nodes s_j = (1 - cos(pi j / n)) / 2 of [0, 1] (s_0 = 0 for n = 0) and the inverse of
// the collocation matrix A_ji = B_i^n(s_j) (row-major, (n + 1)^2 entries): b = A^-1 f for the
// values f_j at the nodes. Chebyshev-Lobatto nodes keep A far better conditioned than equally
// spaced ones at the degrees a tricubic cell gives a ray (9). The blocks of degree n start at
// n (n + 1) / 2 (nodes) and n (n + 1) (2n + 1) / 6 (bases), degree after degree.
#include <vector>

namespace mfadvr {

// Degree 7 on every axis: 21 along a ray (kernel/IsoSurfaceWalk.h: kMaxIsoCoefficients - 1).
inline constexpr int kMaxIsoDegree = 21;

struct IsoBasisTables {
  std::vector<double> nodes;  // sum over n of n + 1
  std::vector<double> basis;  // sum over n of (n + 1)^2
};

// Computed once, on first use (thread-safe).
const IsoBasisTables& isoBasisTables();

}  // namespace mfadvr
