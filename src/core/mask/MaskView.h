#pragma once
// A domain mask as a plain view (host and device): 0/1 node values on a regular grid over the
// parameter cube; a point is inside where their trilinear interpolation is at least 1/2
// (DomainMask.h owns the nodes and explains the choice). nodes == nullptr: everything inside.
#include <cstdint>

#include "core/util/HostDevice.h"

namespace mfadvr {

struct MaskView {
  const std::uint8_t* nodes = nullptr;
  std::int64_t dims[3] = {0, 0, 0};
  double scale[3] = {0.0, 0.0, 0.0};  // dims - 1
};

// u: parameter in [0,1]^3 (clamped; NaN counts as 0).
MFADVR_HD MFADVR_INLINE bool insideMask(const MaskView& m, const double u[3]) {
  if (!m.nodes) return true;
  std::int64_t i[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double ua = !(u[a] > 0.0) ? 0.0 : (u[a] > 1.0 ? 1.0 : u[a]);
    const double t = ua * m.scale[a];
    std::int64_t c = static_cast<std::int64_t>(t);
    if (c > m.dims[a] - 2) c = m.dims[a] - 2;
    i[a] = c;
    f[a] = t - static_cast<double>(c);
  }
  const std::int64_t sx = 1, sy = m.dims[0], sz = m.dims[0] * m.dims[1];
  const std::uint8_t* n = m.nodes + i[0] * sx + i[1] * sy + i[2] * sz;
  // Fast paths: all eight corners agree (the common case away from the boundary).
  const int sum =
      n[0] + n[sx] + n[sy] + n[sx + sy] + n[sz] + n[sx + sz] + n[sy + sz] + n[sx + sy + sz];
  if (sum == 0) return false;
  if (sum == 8) return true;
  const double x0 = (1 - f[0]) * n[0] + f[0] * n[sx];
  const double x1 = (1 - f[0]) * n[sy] + f[0] * n[sx + sy];
  const double x2 = (1 - f[0]) * n[sz] + f[0] * n[sx + sz];
  const double x3 = (1 - f[0]) * n[sy + sz] + f[0] * n[sx + sy + sz];
  const double y0 = (1 - f[1]) * x0 + f[1] * x1;
  const double y1 = (1 - f[1]) * x2 + f[1] * x3;
  return (1 - f[2]) * y0 + f[2] * y1 >= 0.5;
}

}  // namespace mfadvr
