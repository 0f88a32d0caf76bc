#pragma once
// The 1-D pieces of every separable fit: the basis functions of one axis at its samples, the
// penalized least-squares solve of all lines along that axis, and the evaluation back at the
// samples. The grid encoder (StructuredEncoder.cpp) applies them per spatial axis to equally
// spaced samples; the time-series encoder (TimeSeriesEncoder.cpp) applies them to the time axis,
// whose samples (the steps' times) need not be equally spaced.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <cstdint>
#include <span>
#include <vector>

#include "core/spline/KnotVector.h"

namespace mfadvr {

// The non-zero basis functions at each sample of one axis: sample i touches control points
// first[i] .. first[i] + p with weights w[i*(p+1) ..].
struct AxisSampling {
  KnotVector knots;
  int degree = 0;
  int controlCount = 0;
  std::int64_t samples = 0;
  std::vector<int> first;
  std::vector<double> weights;
};

// `samples` equally spaced samples: parameters i / (samples - 1).
AxisSampling sampleAxis(const KnotVector& kv, std::int64_t samples);
// Samples at the given parameters (in [0, 1], non-decreasing).
AxisSampling sampleAxisAt(const KnotVector& kv, std::span<const double> parameters);

// Least-squares fit of every line of one axis: solves (N^T N + m mu D^T D) c = N^T f, where m is
// the sample count, D the axis's penalty of order p + 1 (core/spline/DerivativePenalty.h) and
// mu = penaltyWeight(lambda, p + 1): the 1-D form of the mean squared error plus lambda's
// penalty. The tensor product of these solves is the separable smoother; to first order in
// lambda it minimizes the scattered fit's objective (the penalty of each axis weighted by the
// other axes' data terms), plus products of two or three axes' penalties.
class AxisFitter {
 public:
  explicit AxisFitter(AxisSampling s, double smoothing = 0.0);

  // The trace of the axis's hat matrix N (N^T N + m mu D^T D)^-1 N^T: its effective number of
  // parameters (the control count without smoothing).
  double hatTrace() const;

  // Fits each column of `lines` (samples x lines) into a column of `out` (controls x lines).
  void operator()(const Eigen::Map<const Eigen::MatrixXd>& lines, Eigen::MatrixXd& out) const;
  // Replaces each column of `rhs` (controls x columns), a right-hand side N^T f accumulated by
  // the caller (sampling() gives N's rows), by the solution c.
  void solveNormal(Eigen::MatrixXd& rhs) const { rhs = llt_.solve(rhs); }
  const AxisSampling& sampling() const { return s_; }

 private:
  AxisSampling s_;
  // Natural ordering keeps the band: the factor has the bandwidth of the degree.
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> llt_;
};

// Evaluates the spline on the samples of one axis: y_i = sum_r N_r(u_i) c_{first_i + r}.
class AxisEvaluator {
 public:
  explicit AxisEvaluator(const AxisSampling& s) : s_(s) {}
  void operator()(const Eigen::Map<const Eigen::MatrixXd>& coeffs, Eigen::MatrixXd& out) const;

 private:
  const AxisSampling& s_;
};

}  // namespace mfadvr
