#include "core/spline/DerivativePenalty.h"

#include "core/util/Error.h"

namespace mfadvr {

DerivativePenalty derivativePenalty(const KnotVector& kv, int order) {
  const int p = kv.degree(), n = kv.controlCount();
  if (order < 1 || order > p + 1) throw Error("derivativePenalty: order must be in 1..degree+1");
  const auto& u = kv.knots();
  // rows[i]: the current coefficient i as weights over c_i .. c_{i+k} (k: derivatives taken).
  std::vector<std::vector<double>> rows(static_cast<size_t>(n), std::vector<double>{1.0});
  std::vector<bool> valid(static_cast<size_t>(n), true);
  const int steps = std::min(order, p);
  for (int k = 1; k <= steps; ++k) {
    // d^(k)_i = (p - k + 1) (d^(k-1)_{i+1} - d^(k-1)_i) / (u_{i+p+1} - u_{i+k}).
    std::vector<std::vector<double>> next;
    std::vector<bool> nextValid;
    for (int i = 0; i + 1 < static_cast<int>(rows.size()); ++i) {
      const double du = u[static_cast<size_t>(i + p + 1)] - u[static_cast<size_t>(i + k)];
      std::vector<double> w(static_cast<size_t>(k + 1), 0.0);
      const bool ok =
          du > 0.0 && valid[static_cast<size_t>(i)] && valid[static_cast<size_t>(i + 1)];
      if (ok) {
        const double f = (p - k + 1) / du;
        for (int e = 0; e < k; ++e) {
          w[static_cast<size_t>(e)] -= f * rows[static_cast<size_t>(i)][static_cast<size_t>(e)];
          w[static_cast<size_t>(e + 1)] +=
              f * rows[static_cast<size_t>(i + 1)][static_cast<size_t>(e)];
        }
      }
      next.push_back(std::move(w));
      nextValid.push_back(ok);
    }
    rows.swap(next);
    valid.swap(nextValid);
  }
  // Coefficient i of the degree p - steps derivative has the basis integral
  // (u_{i+p+1} - u_{i+steps}) / (p - steps + 1).
  std::vector<double> mass(rows.size());
  for (size_t i = 0; i < rows.size(); ++i)
    mass[i] =
        (u[i + static_cast<size_t>(p + 1)] - u[i + static_cast<size_t>(steps)]) / (p - steps + 1);
  if (order == p + 1) {
    // Jumps of the piecewise-constant p-th derivative over the mean length of adjacent spans.
    std::vector<std::vector<double>> next;
    std::vector<bool> nextValid;
    std::vector<double> nextMass;
    for (size_t i = 0; i + 1 < rows.size(); ++i) {
      const double l = 0.5 * (mass[i] + mass[i + 1]);
      std::vector<double> w(static_cast<size_t>(order + 1), 0.0);
      const bool ok = l > 0.0 && mass[i] > 0.0 && mass[i + 1] > 0.0 && valid[i] && valid[i + 1];
      if (ok)
        for (int e = 0; e < order; ++e) {
          w[static_cast<size_t>(e)] -= rows[i][static_cast<size_t>(e)] / l;
          w[static_cast<size_t>(e + 1)] += rows[i + 1][static_cast<size_t>(e)] / l;
        }
      next.push_back(std::move(w));
      nextValid.push_back(ok);
      nextMass.push_back(l);
    }
    rows.swap(next);
    valid.swap(nextValid);
    mass.swap(nextMass);
  }
  DerivativePenalty d;
  d.order = order;
  const double h = 1.0 / static_cast<double>(n - p);
  const double hq = std::pow(h, order);
  for (size_t i = 0; i < rows.size(); ++i) {
    if (!valid[i] || !(mass[i] > 0.0)) continue;
    const double scale = hq * std::sqrt(mass[i]);
    d.first.push_back(static_cast<int>(i));
    for (double w : rows[i]) d.weights.push_back(scale * w);
  }
  return d;
}

}  // namespace mfadvr
