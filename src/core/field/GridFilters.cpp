#include "core/field/GridFilters.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

namespace mfadvr {

namespace {

// Lekien & Marsden's 64x64 matrix: coefficients a (a[i + 4j + 16k] of tx^i ty^j tz^k) from the
// corner data b (for each derivative order (dx,dy,dz) in {0,1}^3, for each corner in {0,1}^3).
// Built here as the inverse of the constraint matrix rather than typed in: row (d, c) of the
// constraint matrix is the derivative d of each monomial at corner c. Its inverse has integer
// entries, so rounding removes the inversion's rounding error.
// Row-major 64x64.
using Matrix64 = std::array<double, 64 * 64>;

const Matrix64& lekienMarsdenMatrix() {
  static const Matrix64 m = [] {
    auto monomialDerivative = [](int power, int order, int at) -> double {
      if (order == 0) return power == 0 ? 1.0 : (at == 0 ? 0.0 : 1.0);
      if (power == 0) return 0.0;
      return power == 1 ? 1.0 : (at == 0 ? 0.0 : double(power));
    };
    Eigen::MatrixXd b(64, 64);
    for (int d = 0; d < 8; ++d)
      for (int c = 0; c < 8; ++c)
        for (int k = 0; k < 4; ++k)
          for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
              b(d * 8 + c, i + 4 * j + 16 * k) = monomialDerivative(i, d & 1, c & 1) *
                                                 monomialDerivative(j, (d >> 1) & 1, (c >> 1) & 1) *
                                                 monomialDerivative(k, (d >> 2) & 1, (c >> 2) & 1);
    const Eigen::MatrixXd inv = b.fullPivLu().inverse();
    Matrix64 rounded;
    for (int r = 0; r < 64; ++r)
      for (int c = 0; c < 64; ++c) rounded[r * 64 + c] = std::round(inv(r, c));
    return rounded;
  }();
  return m;
}

}  // namespace

void TricubicFilter::loadCell(const std::int64_t c[3]) {
  // Corner data by central differences of the samples (the ghost layer makes them one-sided on
  // the boundary), in index units: f, fx, fy, fxy, fz, fxz, fyz, fxyz (bit d: x=1, y=2, z=4).
  double b[64];
  const PaddedGrid& g = *g_;
  for (int corner = 0; corner < 8; ++corner) {
    const std::int64_t i = c[0] + (corner & 1), j = c[1] + ((corner >> 1) & 1),
                       k = c[2] + ((corner >> 2) & 1);
    for (int d = 0; d < 8; ++d) {
      // Apply the central difference 0.5 (f(+1) - f(-1)) along each axis whose bit is set.
      double sum = 0.0;
      const int ox = d & 1, oy = (d >> 1) & 1, oz = (d >> 2) & 1;
      for (int sz = -oz; sz <= oz; sz += 2 * oz + (oz == 0))
        for (int sy = -oy; sy <= oy; sy += 2 * oy + (oy == 0))
          for (int sx = -ox; sx <= ox; sx += 2 * ox + (ox == 0)) {
            const double sign =
                (sx < 0 ? -1.0 : 1.0) * (sy < 0 ? -1.0 : 1.0) * (sz < 0 ? -1.0 : 1.0);
            sum += sign * g.at(i + sx, j + sy, k + sz);
          }
      b[d * 8 + corner] = sum / double(1 << (ox + oy + oz));
    }
  }
  const Matrix64& m = lekienMarsdenMatrix();
  for (int r = 0; r < 64; ++r) {
    double sum = 0.0;
    for (int c = 0; c < 64; ++c) sum += m[r * 64 + c] * b[c];
    a_[r] = sum;
  }
  for (int a = 0; a < 3; ++a) cached_[a] = c[a];
}

ValueGradient TricubicFilter::evaluate(const Vec3d& x, bool gradient) {
  std::int64_t c[3];
  double t[3];
  g_->cell(g_->continuousIndex(x), c, t);
  if (c[0] != cached_[0] || c[1] != cached_[1] || c[2] != cached_[2]) loadCell(c);
  double py[4] = {1, t[1], t[1] * t[1], t[1] * t[1] * t[1]};
  double pz[4] = {1, t[2], t[2] * t[2], t[2] * t[2] * t[2]};
  double dx[4] = {0, 1, 2 * t[0], 3 * t[0] * t[0]};
  double dy[4] = {0, 1, 2 * t[1], 3 * t[1] * t[1]};
  double dz[4] = {0, 1, 2 * t[2], 3 * t[2] * t[2]};
  double v = 0, gx = 0, gy = 0, gz = 0;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j) {
      const double* a = a_.data() + 4 * j + 16 * k;
      const double lv = a[0] + t[0] * (a[1] + t[0] * (a[2] + t[0] * a[3]));
      v += lv * py[j] * pz[k];
      if (gradient) {
        const double lx = a[1] * dx[1] + a[2] * dx[2] + a[3] * dx[3];
        gx += lx * py[j] * pz[k];
        gy += lv * dy[j] * pz[k];
        gz += lv * py[j] * dz[k];
      }
    }
  ValueGradient r;
  r.value = static_cast<float>(v);
  if (gradient) {
    const Vec3d& s = g_->inverseSpacing();
    r.gradient = Vec3f(gx * s[0], gy * s[1], gz * s[2]);
  }
  return r;
}

PaddedGrid BSplineFilter::prepare(const StructuredGrid& grid) {
  const Index3 n = grid.dims;
  for (int a = 0; a < 3; ++a)
    if (n[a] < 2) return PaddedGrid(grid);  // PaddedGrid reports the error
  std::vector<double> c = grid.values;
  const std::int64_t stride[3] = {1, n[0], n[0] * n[1]};
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t len = n[axis];
    if (len < 3) continue;  // two samples: the coefficients are the samples
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const std::int64_t lines = n[a1] * n[a2];
    // Interior equations c[k-1] + 4 c[k] + c[k+1] = 6 s[k], k = 1..len-2, with the end
    // coefficients equal to the end samples (natural end conditions). Thomas algorithm; the
    // forward-elimination factors are the same for every line.
    std::vector<double> factor(static_cast<size_t>(len), 0.0);
    {
      double diag = 4.0;
      factor[1] = 1.0 / diag;
      for (std::int64_t k = 2; k < len - 1; ++k) {
        diag = 4.0 - factor[k - 1];
        factor[k] = 1.0 / diag;
      }
    }
    tbb::parallel_for(std::int64_t(0), lines, [&](std::int64_t line) {
      const std::int64_t start = (line % n[a1]) * stride[a1] + (line / n[a1]) * stride[a2];
      const std::int64_t s = stride[axis];
      auto at = [&](std::int64_t k) -> double& { return c[static_cast<size_t>(start + k * s)]; };
      std::vector<double> rhs(static_cast<size_t>(len));
      for (std::int64_t k = 1; k < len - 1; ++k) rhs[k] = 6.0 * at(k);
      rhs[1] -= at(0);
      rhs[len - 2] -= at(len - 1);
      // Forward sweep: y[k] = (rhs[k] - y[k-1]) * factor[k].
      rhs[1] *= factor[1];
      for (std::int64_t k = 2; k < len - 1; ++k) rhs[k] = (rhs[k] - rhs[k - 1]) * factor[k];
      // Back substitution: c[k] = y[k] - factor[k] * c[k+1].
      at(len - 2) = rhs[len - 2];
      for (std::int64_t k = len - 3; k >= 1; --k) at(k) = rhs[k] - factor[k] * at(k + 1);
    });
  }
  return PaddedGrid(grid, &c);
}

}  // namespace mfadvr
