#include "core/encode/KnotPlacement.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/util/Error.h"

namespace mfadvr {

KnotVector knotsForSamples(int degree, int controlCount, std::int64_t sampleCount) {
  const int p = degree, n = controlCount;
  const double last = static_cast<double>(sampleCount - 1);
  std::vector<double> knots(static_cast<size_t>(n + p + 1), 0.0);
  for (int i = 0; i <= p; ++i) knots[n + i] = 1.0;
  if (n == sampleCount) {
    // Average of p consecutive parameters: (j + (p - 1) / 2) / (N - 1).
    for (int j = 1; j < n - p; ++j) knots[p + j] = (j + (p - 1) / 2.0) / last;
  } else {
    const double d = static_cast<double>(sampleCount) / (n - p);
    for (int j = 1; j < n - p; ++j) knots[p + j] = (j * d - 1.0) / last;
  }
  return KnotVector::fromKnots(p, std::move(knots));
}

KnotVector knotsForParameters(int degree, int controlCount, std::span<const double> t) {
  const int p = degree, n = controlCount;
  const auto N = static_cast<std::int64_t>(t.size());
  if (n < p + 1 || N < n)
    throw Error("a spline of degree " + std::to_string(p) + " with " + std::to_string(n) +
                " control points needs at least " + std::to_string(std::max(n, p + 1)) +
                " samples, not " + std::to_string(N));
  std::vector<double> knots(static_cast<size_t>(n + p + 1), 0.0);
  for (int i = 0; i <= p; ++i) knots[static_cast<size_t>(n + i)] = 1.0;
  if (n == N) {
    for (int j = 1; j < n - p; ++j) {
      double sum = 0.0;
      for (int i = j; i < j + p; ++i) sum += t[static_cast<size_t>(i)];
      knots[static_cast<size_t>(p + j)] = sum / p;
    }
  } else {
    const double d = static_cast<double>(N) / (n - p);
    for (int j = 1; j < n - p; ++j) {
      const auto i = static_cast<std::int64_t>(std::floor(j * d));
      const double a = j * d - static_cast<double>(i);
      knots[static_cast<size_t>(p + j)] = (1.0 - a) * t[static_cast<size_t>(i - 1)] +
                                          a * t[static_cast<size_t>(std::min(i, N - 1))];
    }
  }
  return KnotVector::fromKnots(p, std::move(knots));
}

KnotVector knotsFollowingDensity(int degree, int controlCount, std::span<const double> sorted,
                                 double weight) {
  if (!(weight >= 0.0 && weight < 1.0))
    throw Error("the knot density weight must lie in [0, 1), got " + std::to_string(weight));
  if (sorted.empty()) throw Error("knots following the points' density need points");
  const int spans = controlCount - degree;
  if (degree < 1 || spans < 1)
    throw Error(std::to_string(controlCount) + " control points cannot carry degree " +
                std::to_string(degree));
  std::vector<double> u(static_cast<size_t>(degree + 1), 0.0);
  const double last = static_cast<double>(sorted.size() - 1);
  for (int j = 1; j < spans; ++j) {
    const double share = static_cast<double>(j) / spans;
    const double q = std::clamp(sorted[static_cast<size_t>(std::llround(share * last))], 0.0, 1.0);
    u.push_back((1.0 - weight) * share + weight * q);
  }
  u.insert(u.end(), static_cast<size_t>(degree + 1), 1.0);
  return KnotVector::fromKnots(degree, std::move(u));
}

}  // namespace mfadvr
