#include "core/encode/KnotPlacement.h"

#include <cmath>
#include <vector>

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

}  // namespace mfadvr
