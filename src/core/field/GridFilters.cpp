#include "core/field/GridFilters.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

#include "core/field/LekienMarsden.h"

namespace mfadvr {

void TricubicFilter::loadCell(const std::int64_t c[3]) {
  // The 4x4x4 samples around the cell (the ghost layer covers the boundary cells).
  double f[4][4][4];  // [k][j][i], offsets -1..2
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j) {
      const float* row = g_->pointer(c[0] - 1, c[1] - 1 + j, c[2] - 1 + k);
      for (int i = 0; i < 4; ++i) f[k][j][i] = row[i];
    }
  // Corner data by central differences, in index units: for derivative bits d (x=1, y=2, z=4),
  // the product of 0.5 (f(+1) - f(-1)) along each set axis.
  double b[64];
  for (int corner = 0; corner < 8; ++corner) {
    const int i = 1 + (corner & 1), j = 1 + ((corner >> 1) & 1), k = 1 + ((corner >> 2) & 1);
    auto dx = [&](int kk, int jj) { return 0.5 * (f[kk][jj][i + 1] - f[kk][jj][i - 1]); };
    auto dxy = [&](int kk) { return 0.5 * (dx(kk, j + 1) - dx(kk, j - 1)); };
    auto dy = [&](int kk) { return 0.5 * (f[kk][j + 1][i] - f[kk][j - 1][i]); };
    b[0 * 8 + corner] = f[k][j][i];
    b[1 * 8 + corner] = dx(k, j);
    b[2 * 8 + corner] = dy(k);
    b[3 * 8 + corner] = dxy(k);
    b[4 * 8 + corner] = 0.5 * (f[k + 1][j][i] - f[k - 1][j][i]);
    b[5 * 8 + corner] = 0.5 * (dx(k + 1, j) - dx(k - 1, j));
    b[6 * 8 + corner] = 0.5 * (dy(k + 1) - dy(k - 1));
    b[7 * 8 + corner] = 0.5 * (dxy(k + 1) - dxy(k - 1));
  }
  lekienMarsdenCoefficients(b, a_.data());
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
  std::vector<double> c(grid.values.begin(), grid.values.end());
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
