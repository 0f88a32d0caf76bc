#include "core/encode/AxisFit.h"

#include <utility>

#include "core/spline/BasisFunctions.h"
#include "core/spline/DerivativePenalty.h"
#include "core/util/Error.h"

namespace mfadvr {

AxisSampling sampleAxis(const KnotVector& kv, std::int64_t samples) {
  std::vector<double> u(static_cast<size_t>(samples));
  // Grid samples are equally spaced in physical space, hence in parameter space.
  for (std::int64_t i = 0; i < samples; ++i)
    u[static_cast<size_t>(i)] = static_cast<double>(i) / static_cast<double>(samples - 1);
  return sampleAxisAt(kv, u);
}

AxisSampling sampleAxisAt(const KnotVector& kv, std::span<const double> parameters) {
  AxisSampling s;
  s.knots = kv;
  s.degree = kv.degree();
  s.controlCount = kv.controlCount();
  s.samples = static_cast<std::int64_t>(parameters.size());
  const int w = s.degree + 1;
  s.first.resize(parameters.size());
  s.weights.resize(parameters.size() * static_cast<size_t>(w));
  for (size_t i = 0; i < parameters.size(); ++i) {
    const double u = parameters[i];
    const int span = kv.findSpan(u);
    s.first[i] = span - s.degree;
    basisFunctions(kv, s.degree, span, u, &s.weights[i * static_cast<size_t>(w)]);
  }
  return s;
}

AxisFitter::AxisFitter(AxisSampling s, double smoothing) : s_(std::move(s)) {
  const int w = s_.degree + 1;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(s_.samples * w * w));
  for (std::int64_t i = 0; i < s_.samples; ++i) {
    const double* wi = &s_.weights[static_cast<size_t>(i * w)];
    for (int r = 0; r < w; ++r)
      for (int q = 0; q < w; ++q) t.emplace_back(s_.first[i] + r, s_.first[i] + q, wi[r] * wi[q]);
  }
  const int n = s_.controlCount;
  if (smoothing > 0.0) {
    const DerivativePenalty d = derivativePenalty(s_.knots, s_.degree + 1);
    const double mu = static_cast<double>(s_.samples) * penaltyWeight(smoothing, d.order);
    const int k = d.order + 1;
    for (int r = 0; r < d.rows(); ++r) {
      const double* dr = &d.weights[static_cast<size_t>(r * k)];
      const int f = d.first[static_cast<size_t>(r)];
      for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) t.emplace_back(f + a, f + b, mu * dr[a] * dr[b]);
    }
  } else {
    // A vanishing second-difference penalty (1e-10 of the mean diagonal) keeps the system
    // definite when sample and knot phases drift against each other (n just below N) and
    // a basis function is seen only at the tails of its support; on well-conditioned systems
    // it changes the fit far below float32 resolution.
    double trace = 0.0;
    for (const auto& e : t)
      if (e.row() == e.col()) trace += e.value();
    const double lambda = 1e-10 * trace / s_.controlCount;
    for (int r = 1; r + 1 < n; ++r) {
      const int idx[3] = {r - 1, r, r + 1};
      const double d[3] = {1.0, -2.0, 1.0};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) t.emplace_back(idx[a], idx[b], lambda * d[a] * d[b]);
    }
  }
  Eigen::SparseMatrix<double> normal(n, n);
  normal.setFromTriplets(t.begin(), t.end());
  llt_.compute(normal);
  if (llt_.info() != Eigen::Success)
    throw Error("the least-squares system is singular (too few samples per knot span)");
}

double AxisFitter::hatTrace() const {
  const int w = s_.degree + 1, n = s_.controlCount;
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(n, n);
  for (std::int64_t i = 0; i < s_.samples; ++i) {
    const double* wi = &s_.weights[static_cast<size_t>(i * w)];
    for (int r = 0; r < w; ++r)
      for (int q = 0; q < w; ++q) gram(s_.first[i] + r, s_.first[i] + q) += wi[r] * wi[q];
  }
  return llt_.solve(gram).trace();
}

void AxisFitter::operator()(const Eigen::Map<const Eigen::MatrixXd>& lines,
                            Eigen::MatrixXd& out) const {
  // rhs = N^T f, one column (one contiguous grid line) at a time.
  const int w = s_.degree + 1;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(s_.controlCount, lines.cols());
  for (Eigen::Index b = 0; b < lines.cols(); ++b) {
    const double* f = lines.col(b).data();
    double* r = rhs.col(b).data();
    for (std::int64_t i = 0; i < s_.samples; ++i) {
      const double* wi = &s_.weights[static_cast<size_t>(i * w)];
      double* ri = r + s_.first[i];
      for (int k = 0; k < w; ++k) ri[k] += wi[k] * f[i];
    }
  }
  out = llt_.solve(rhs);
}

void AxisEvaluator::operator()(const Eigen::Map<const Eigen::MatrixXd>& coeffs,
                               Eigen::MatrixXd& out) const {
  const int w = s_.degree + 1;
  for (Eigen::Index b = 0; b < coeffs.cols(); ++b) {
    const double* c = coeffs.col(b).data();
    double* y = out.col(b).data();
    for (std::int64_t i = 0; i < s_.samples; ++i) {
      const double* wi = &s_.weights[static_cast<size_t>(i * w)];
      const double* ci = c + s_.first[i];
      double v = 0.0;
      for (int k = 0; k < w; ++k) v += wi[k] * ci[k];
      y[i] = v;
    }
  }
}

}  // namespace mfadvr
