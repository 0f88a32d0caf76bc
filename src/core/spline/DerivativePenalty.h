#pragma once
// The roughness penalty of a 1-D B-spline, shared by every fit that smooths (grids and
// scattered data), so that one smoothing weight lambda means the same everywhere.
//
// For control points c of a spline s of degree p on a clamped knot vector, the rows D satisfy
//   |D c|^2  ~=  h^(2q) * integral over [0,1] of (d^q s / du^q)^2,   h = 1 / (n - p),
// h being the mean knot span. For q <= p the q-th derivative is a spline of degree p - q whose
// coefficients are divided differences of c (the B-spline derivative formula) and the integral
// is mass-lumped (each squared coefficient times the integral of its basis function). For
// q = p + 1 the p-th derivative is constant per span and the penalty sums its squared jumps at
// the interior knots, each divided by the mean length of the two spans it separates (the
// difference quotient of the p-th derivative over that length, squared and integrated).
// Polynomials of degree < q carry no penalty; q = p + 1 leaves every polynomial the spline can
// represent unbiased (on uniform knots it is the (p+1)-th difference penalty of P-splines).
//
// Weighted by penaltyWeight(lambda, q) = lambda^(q/2) and added to a data term that is a mean
// of squared errors, the penalty makes a smoother whose half-power frequency is
// 1 / (h lambda^(1/4)) radians per unit parameter for every order: lambda = 1 keeps
// wavelengths above about 2 pi knot spans, lambda = 1e-4 above about 0.6 spans. The order only
// sets how sharp the cut-off is.
#include <cmath>
#include <vector>

#include "core/spline/KnotVector.h"

namespace mfadvr {

// Rows of D in band form: row r touches control points first[r] .. first[r] + order with the
// weights weights[r * (order + 1) + k]. Rows whose knot differences vanish are left out.
struct DerivativePenalty {
  int order = 0;
  std::vector<int> first;
  std::vector<double> weights;
  int rows() const { return static_cast<int>(first.size()); }
};

// 1 <= order <= degree + 1; an axis with too few control points for the order has no rows.
DerivativePenalty derivativePenalty(const KnotVector& kv, int order);

inline double penaltyWeight(double lambda, int order) {
  return std::pow(lambda, 0.5 * order);
}

}  // namespace mfadvr
