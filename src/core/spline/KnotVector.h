#pragma once
// A clamped knot vector on [0,1] for one parametric axis of a B-spline.
//
// Knots u_0..u_{n+p}: the first p+1 are 0, the last p+1 are 1, the rest non-decreasing in
// between. Vectors whose interior knots are equally spaced (uniform ones, and the fitted
// placements whose end spans differ) get an O(1) span lookup; every routine also works for the
// irregular vectors that knot insertion produces (binary search).
#include <cstddef>
#include <vector>

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
  int findSpan(double u) const {
    if (!(u > 0.0)) return degree_;  // also NaN
    const int last = controlCount() - 1;
    if (u >= 1.0) return last;
    if (regular_) {
      // Compare in double before converting: a tiny spacing makes t too large for an int.
      const double t = (u - firstInterior_) * inverseSpacing_;
      int s = !(t >= 0.0)                                    ? degree_
              : t >= static_cast<double>(last - degree_ - 1) ? last
                                                             : degree_ + 1 + static_cast<int>(t);
      // Rounding can put u one span off at a boundary.
      while (s > degree_ && u < knots_[s]) --s;
      while (s < last && u >= knots_[s + 1]) ++s;
      return s;
    }
    return findSpanBinary(u);
  }

  // A new vector with `u` (strictly inside (0,1)) inserted once.
  KnotVector withInsertedKnot(double u) const;

  bool operator==(const KnotVector& o) const { return degree_ == o.degree_ && knots_ == o.knots_; }

 private:
  KnotVector(int degree, std::vector<double> knots);
  int findSpanBinary(double u) const;

  int degree_ = 0;
  std::vector<double> knots_;
  bool uniform_ = false;
  bool regular_ = false;
  double firstInterior_ = 1.0;   // u_{p+1}
  double inverseSpacing_ = 0.0;  // 1 / (u_{p+2} - u_{p+1})
  int reciprocalsPerSpan_ = 0;
  std::vector<double> reciprocals_;
};

}  // namespace mfadvr
