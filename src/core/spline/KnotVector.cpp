#include "core/spline/KnotVector.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/spline/BasisFunctions.h"
#include "core/spline/SplineKernel.h"
#include "core/util/Error.h"

namespace mfadvr {

static_assert(kSplineMaxDegree == kMaxDegree, "the kernel's degree bound must match");

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
  if (degree_ >= 1 && n > degree_) buildBasisPolynomials();
}

KnotAxisView KnotVector::view() const {
  KnotAxisView v;
  v.knots = knots_.data();
  v.poly = poly_.data();
  v.inverseLength = inverseLength_.data();
  v.degree = degree_;
  v.count = controlCount();
  v.regular = regular_;
  v.firstInterior = firstInterior_;
  v.inverseSpacing = inverseSpacing_;
  v.interiorSpans = regular_ ? static_cast<double>(controlCount() - degree_ - 2) : 0.0;
  v.sharedFirst = sharedFirst_;
  v.sharedLast = sharedLast_;
  return v;
}

// The Taylor expansion at the span's midpoint m is exact for a polynomial of degree p:
// N_r(m + tau h) = sum_k N_r^(k)(m) h^k / k! tau^k, tau in [-1/2, 1/2], with A2.3's derivatives.
// About the midpoint the powers of tau stay below 2^-k, which keeps float Horner sums accurate
// for high degrees (at the left end, degree 7 lost a few more bits).
void KnotVector::buildBasisPolynomials() {
  const int p = degree_, w = p + 1, n = controlCount();
  // The padding lets the kernel load any row as one full SIMD vector (SplineKernel.h).
  poly_.assign(static_cast<size_t>(n) * w * w + kSplineRowPadding, 0.0f);
  inverseLength_.assign(static_cast<size_t>(n), 0.0);
  double ders[(kMaxDegree + 1) * (kMaxDegree + 1)];
  for (int s = p; s < n; ++s) {
    const double h = knots_[s + 1] - knots_[s];
    if (!(h > 0.0)) continue;  // an empty span is never found
    inverseLength_[s] = 1.0 / h;
    basisDerivatives(*this, p, s, knots_[s] + 0.5 * h, p, ders);
    double scale = 1.0;  // h^k / k!
    for (int k = 0; k <= p; ++k) {
      for (int r = 0; r < w; ++r)
        poly_[(static_cast<size_t>(s) * w + k) * w + r] =
            static_cast<float>(ders[k * w + r] * scale);
      scale *= h / (k + 1);
    }
  }
  // On a regular axis, spans 2p+1 .. n-p-2 see only equally spaced knots: their polynomials in
  // the local coordinate are the same function (the uniform B-spline's), and differ here only
  // by the rounding of each span's own knots (a float ulp). One copy, the first span's, makes
  // them equal bit for bit, so that every evaluation path reads identical coefficients.
  if (regular_ && 2 * p + 1 <= n - p - 2) {
    sharedFirst_ = 2 * p + 1;
    sharedLast_ = n - p - 2;
    const size_t block = static_cast<size_t>(w) * w;
    const auto first = poly_.begin() + static_cast<std::ptrdiff_t>(sharedFirst_ * block);
    for (int s = sharedFirst_ + 1; s <= sharedLast_; ++s) {
      std::copy(first, first + static_cast<std::ptrdiff_t>(block),
                poly_.begin() + static_cast<std::ptrdiff_t>(s * block));
      inverseLength_[s] = inverseLength_[sharedFirst_];
    }
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

KnotVector KnotVector::withInsertedKnot(double u) const {
  if (!(u > 0.0 && u < 1.0)) throw Error("inserted knot must lie strictly inside (0,1)");
  std::vector<double> k = knots_;
  k.insert(std::upper_bound(k.begin(), k.end(), u), u);
  return fromKnots(degree_, std::move(k));
}

}  // namespace mfadvr
