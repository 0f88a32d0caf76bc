#include "core/render/IsoBasis.h"

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "core/render/kernel/IsoSurfaceWalk.h"

namespace mfadvr {

static_assert(kMaxIsoDegree + 1 == kMaxIsoCoefficients);

namespace {

double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

IsoBasisTables build() {
  IsoBasisTables t;
  for (int n = 0; n <= kMaxIsoDegree; ++n) {
    std::vector<double> s(n + 1);
    for (int j = 0; j <= n; ++j)
      s[j] = n == 0 ? 0.0 : 0.5 * (1.0 - std::cos(std::numbers::pi * j / n));
    Eigen::MatrixXd a(n + 1, n + 1);
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        a(j, i) = binomial(n, i) * std::pow(s[j], i) * std::pow(1.0 - s[j], n - i);
    const Eigen::MatrixXd inverse = a.fullPivLu().inverse();
    t.nodes.insert(t.nodes.end(), s.begin(), s.end());
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) t.basis.push_back(inverse(i, j));
  }
  return t;
}

}  // namespace

const IsoBasisTables& isoBasisTables() {
  static const IsoBasisTables tables = build();
  return tables;
}

}  // namespace mfadvr
