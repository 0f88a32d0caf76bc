#include "core/mask/DomainMask.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/util/Error.h"

namespace mfadvr {

std::string maskKindName(MaskKind kind) {
  return kind == MaskKind::MeshOccupancy ? "mesh-occupancy" : "point-coverage";
}

MaskKind parseMaskKind(const std::string& name) {
  if (name == "mesh-occupancy") return MaskKind::MeshOccupancy;
  if (name == "point-coverage") return MaskKind::PointCoverage;
  throw Error("unknown mask kind '" + name + "' (expected mesh-occupancy or point-coverage)");
}

DomainMask::DomainMask(MaskKind kind, Index3 dims, std::vector<std::uint8_t> nodes)
    : kind_(kind), dims_(dims), nodes_(std::move(nodes)) {
  validateDims(dims_);
  if (static_cast<std::int64_t>(nodes_.size()) != dims_[0] * dims_[1] * dims_[2])
    throw Error("domain mask: node count does not match its dimensions");
  for (auto& v : nodes_) v = v ? 1 : 0;
  scale_ = Vec3d(double(dims_[0] - 1), double(dims_[1] - 1), double(dims_[2] - 1));
}

void DomainMask::validateDims(const Index3& dims) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 2 || dims[a] > kMaxMaskNodesPerAxis)
      throw Error("a domain mask needs 2.." + std::to_string(kMaxMaskNodesPerAxis) +
                  " nodes per axis, not " + std::to_string(dims[a]));
  if (dims[0] * dims[1] * dims[2] > kMaxMaskNodes)  // each factor <= 2^12: no overflow
    throw Error("a domain mask may have at most " + std::to_string(kMaxMaskNodes) + " nodes");
}

double DomainMask::insideFraction() const {
  if (nodes_.empty()) return 1.0;
  const auto inside = std::accumulate(nodes_.begin(), nodes_.end(), std::int64_t(0));
  return static_cast<double>(inside) / static_cast<double>(nodes_.size());
}

bool DomainMask::insideParameter(const Vec3d& u) const {
  if (nodes_.empty()) return true;
  std::int64_t i[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double t = std::clamp(u[a], 0.0, 1.0) * scale_[a];  // NaN becomes 0 below
    std::int64_t c = t >= 0.0 ? static_cast<std::int64_t>(t) : 0;
    c = std::min<std::int64_t>(c, dims_[a] - 2);
    i[a] = c;
    f[a] = t >= 0.0 ? t - static_cast<double>(c) : 0.0;
  }
  const std::int64_t sx = 1, sy = dims_[0], sz = dims_[0] * dims_[1];
  const std::uint8_t* n = nodes_.data() + i[0] * sx + i[1] * sy + i[2] * sz;
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
