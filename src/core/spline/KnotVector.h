#pragma once
// A clamped knot vector on [0,1] for one parametric axis of a B-spline.
//
// Knots u_0..u_{n+p}: the first p+1 are 0, the last p+1 are 1, the rest non-decreasing in
// between. Vectors whose interior knots are equally spaced (uniform ones, and the fitted
// placements whose end spans differ) get an O(1) span lookup; every routine also works for the
// irregular vectors that knot insertion produces (binary search).
#include <cstddef>
#include <vector>

#include "core/spline/SplineView.h"

namespace mfadvr {

inline constexpr int kMaxDegree = 7;

class KnotVector {
 public:
  KnotVector() = default;

  // Clamped, uniformly spaced knots for `count` control points of degree `degree`.
  static KnotVector clampedUniform(int degree, int count);
  // Validates clamping, monotonicity, range and multiplicity (interior knots at most p).
  static KnotVector fromKnots(int degree, std::vector<double> knots);

  int degree() const { return degree_; }
  int controlCount() const { return static_cast<int>(knots_.size()) - degree_ - 1; }
  // All spans equally long.
  bool isUniform() const { return uniform_; }
  // Interior knots equally spaced (end spans may differ): span lookup is O(1).
  bool hasRegularInterior() const { return regular_; }
  const std::vector<double>& knots() const { return knots_; }
  const double* data() const { return knots_.data(); }
  // 1 / (u_{s+r+1} - u_{s+1-j+r}) for j = 1..p, r = 0..j-1 at index j(j-1)/2 + r: the
  // denominators of the basis recurrences of span s (in [p, n-1]), so that evaluation
  // multiplies instead of dividing (divisions were the slowest part of a query).
  const double* reciprocalDifferences(int span) const {
    return reciprocals_.data() + static_cast<std::size_t>(span) * reciprocalsPerSpan_;
  }

  // The span s in [p, n-1] with u_s <= u < u_{s+1}; u is clamped to [0,1] first and u = 1
  // belongs to the last non-empty span.
  int findSpan(double u) const { return mfadvr::findSpan(view(), u); }

  // The view the evaluation kernel reads (SplineView.h); valid while this vector lives.
  KnotAxisView view() const;
  // Per span, the p+1 basis functions as polynomials in the span's local coordinate, in the
  // layout KnotAxisView::poly describes.
  const std::vector<float>& basisPolynomials() const { return poly_; }

  // A new vector with `u` (strictly inside (0,1)) inserted once.
  KnotVector withInsertedKnot(double u) const;

  bool operator==(const KnotVector& o) const { return degree_ == o.degree_ && knots_ == o.knots_; }

 private:
  KnotVector(int degree, std::vector<double> knots);
  void buildBasisPolynomials();

  int degree_ = 0;
  std::vector<double> knots_;
  bool uniform_ = false;
  bool regular_ = false;
  double firstInterior_ = 1.0;   // u_{p+1}
  double inverseSpacing_ = 0.0;  // 1 / (u_{p+2} - u_{p+1})
  int reciprocalsPerSpan_ = 0;
  std::vector<double> reciprocals_;
  std::vector<float> poly_;
  std::vector<double> inverseLength_;
  int sharedFirst_ = 1, sharedLast_ = 0;  // KnotAxisView::sharedFirst / sharedLast
};

}  // namespace mfadvr
