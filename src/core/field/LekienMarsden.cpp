#include "core/field/LekienMarsden.h"

#include <Eigen/Dense>
#include <cmath>

namespace mfadvr {

const std::array<double, 64 * 64>& lekienMarsdenMatrix() {
  static const std::array<double, 64 * 64> m = [] {
    // Derivative `order` (0 or 1) of t^power at t = at (0 or 1).
    auto monomialDerivative = [](int power, int order, int at) -> double {
      if (order == 0) return power == 0 ? 1.0 : (at == 0 ? 0.0 : 1.0);
      if (power == 0) return 0.0;
      return power == 1 ? 1.0 : (at == 0 ? 0.0 : double(power));
    };
    Eigen::MatrixXd constraints(64, 64);
    for (int d = 0; d < 8; ++d)
      for (int c = 0; c < 8; ++c)
        for (int k = 0; k < 4; ++k)
          for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
              constraints(d * 8 + c, i + 4 * j + 16 * k) =
                  monomialDerivative(i, d & 1, c & 1) *
                  monomialDerivative(j, (d >> 1) & 1, (c >> 1) & 1) *
                  monomialDerivative(k, (d >> 2) & 1, (c >> 2) & 1);
    const Eigen::MatrixXd inverse = constraints.fullPivLu().inverse();
    std::array<double, 64 * 64> rounded;
    for (int r = 0; r < 64; ++r)
      for (int c = 0; c < 64; ++c) rounded[r * 64 + c] = std::round(inverse(r, c));
    return rounded;
  }();
  return m;
}

void lekienMarsdenCoefficients(const double b[64], double a[64]) {
  // Per axis, the input index q = corner + 2 * derivative orders (f0, f1, f'0, f'1); the cubic
  // Hermite matrix turns them into the coefficients of 1, t, t^2, t^3.
  static constexpr double H[4][4] = {{1, 0, 0, 0}, {0, 0, 1, 0}, {-3, 3, -2, -1}, {2, -2, 1, 1}};
  double t[4][4][4];  // [qz][qy][qx]
  for (int d = 0; d < 8; ++d)
    for (int c = 0; c < 8; ++c) {
      const int qx = (c & 1) + 2 * (d & 1), qy = ((c >> 1) & 1) + 2 * ((d >> 1) & 1),
                qz = ((c >> 2) & 1) + 2 * ((d >> 2) & 1);
      t[qz][qy][qx] = b[d * 8 + c];
    }
  double u[4][4][4];
  for (int z = 0; z < 4; ++z)  // x: t[z][y][q] -> u[z][y][i]
    for (int y = 0; y < 4; ++y)
      for (int i = 0; i < 4; ++i)
        u[z][y][i] = H[i][0] * t[z][y][0] + H[i][1] * t[z][y][1] + H[i][2] * t[z][y][2] +
                     H[i][3] * t[z][y][3];
  for (int z = 0; z < 4; ++z)  // y: u[z][q][i] -> t[z][j][i]
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        t[z][j][i] = H[j][0] * u[z][0][i] + H[j][1] * u[z][1][i] + H[j][2] * u[z][2][i] +
                     H[j][3] * u[z][3][i];
  for (int k = 0; k < 4; ++k)  // z: t[q][j][i] -> a
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        a[i + 4 * j + 16 * k] = H[k][0] * t[0][j][i] + H[k][1] * t[1][j][i] + H[k][2] * t[2][j][i] +
                                H[k][3] * t[3][j][i];
}

}  // namespace mfadvr
