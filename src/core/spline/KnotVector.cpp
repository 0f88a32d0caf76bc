#include "core/spline/KnotVector.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {

KnotVector::KnotVector(int degree, std::vector<double> knots)
    : degree_(degree), knots_(std::move(knots)) {
  const int n = controlCount();
  reciprocalsPerSpan_ = degree_ * (degree_ + 1) / 2;
  if (degree_ >= 1 && n > degree_) {
    reciprocals_.assign(static_cast<size_t>(n) * reciprocalsPerSpan_, 0.0);
    for (int span = degree_; span < n; ++span)
      for (int j = 1; j <= degree_; ++j)
        for (int r = 0; r < j; ++r) {
          const double d = knots_[span + r + 1] - knots_[span + 1 - j + r];
          reciprocals_[static_cast<size_t>(span) * reciprocalsPerSpan_ + (j - 1) * j / 2 + r] =
              d > 0.0 ? 1.0 / d : 0.0;  // zero only where the basis term vanishes anyway
        }
  }
  const int spans = n - degree_;
  uniform_ = true;
  for (int s = 0; s <= spans && uniform_; ++s) {
    const double expected = static_cast<double>(s) / spans;
    if (std::abs(knots_[degree_ + s] - expected) > 1e-12) uniform_ = false;
  }
  // Interior knots are u_{p+1} .. u_{n-1}.
  const int interior = n - degree_ - 1;
  regular_ = true;
  firstInterior_ = interior > 0 ? knots_[degree_ + 1] : 1.0;
  const double h = interior > 1 ? knots_[degree_ + 2] - knots_[degree_ + 1] : 1.0;
  if (!(h > 0.0)) {
    regular_ = false;
  } else {
    inverseSpacing_ = 1.0 / h;
    for (int j = 1; j < interior && regular_; ++j)
      if (std::abs(knots_[degree_ + 1 + j] - (firstInterior_ + j * h)) > 1e-9 * h) regular_ = false;
  }
}

KnotVector KnotVector::clampedUniform(int degree, int count) {
  if (degree < 1 || degree > kMaxDegree)
    throw Error("degree " + std::to_string(degree) + " is outside 1.." +
                std::to_string(kMaxDegree));
  if (count < degree + 1)
    throw Error("control point count " + std::to_string(count) +
                " is below degree + 1 = " + std::to_string(degree + 1));
  std::vector<double> k(static_cast<size_t>(count + degree + 1));
  const int spans = count - degree;
  for (int i = 0; i <= degree; ++i) {
    k[i] = 0.0;
    k[count + i] = 1.0;
  }
  for (int s = 1; s < spans; ++s) k[degree + s] = static_cast<double>(s) / spans;
  return KnotVector(degree, std::move(k));
}

KnotVector KnotVector::fromKnots(int degree, std::vector<double> knots) {
  if (degree < 1 || degree > kMaxDegree)
    throw Error("degree " + std::to_string(degree) + " is outside 1.." +
                std::to_string(kMaxDegree));
  const long m = static_cast<long>(knots.size());
  const long n = m - degree - 1;
  if (n < degree + 1)
    throw Error("knot vector of size " + std::to_string(m) + " is too short for degree " +
                std::to_string(degree));
  for (int i = 0; i <= degree; ++i) {
    if (knots[i] != 0.0 || knots[m - 1 - i] != 1.0)
      throw Error("knot vector is not clamped to [0,1]");
  }
  // Exactly p+1 end knots: more would leave empty spans at the ends of [0,1].
  if (knots[degree + 1] <= 0.0 || knots[m - degree - 2] >= 1.0)
    throw Error("knot vector has more than degree + 1 knots at 0 or at 1");
  int run = 1;
  for (long i = 1; i < m; ++i) {
    if (!(knots[i] >= knots[i - 1]) || !std::isfinite(knots[i]))
      throw Error("knot vector is not non-decreasing");
    run = knots[i] == knots[i - 1] ? run + 1 : 1;
    if (run > degree && knots[i] > 0.0 && knots[i] < 1.0)
      throw Error("interior knot multiplicity exceeds the degree");
  }
  return KnotVector(degree, std::move(knots));
}

int KnotVector::findSpanBinary(double u) const {
  // Last index s in [p, n-1] with knots[s] <= u (u is inside (0,1) here).
  const auto first = knots_.begin() + degree_;
  const auto last = knots_.begin() + controlCount();  // one past index n-1
  const auto it = std::upper_bound(first, last + 1, u);
  return static_cast<int>(it - knots_.begin()) - 1;
}

KnotVector KnotVector::withInsertedKnot(double u) const {
  if (!(u > 0.0 && u < 1.0)) throw Error("inserted knot must lie strictly inside (0,1)");
  std::vector<double> k = knots_;
  k.insert(std::upper_bound(k.begin(), k.end(), u), u);
  return fromKnots(degree_, std::move(k));
}

}  // namespace mfadvr
