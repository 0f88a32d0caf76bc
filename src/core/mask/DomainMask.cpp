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

MaskView DomainMask::view() const {
  MaskView v;
  if (nodes_.empty()) return v;
  v.nodes = nodes_.data();
  for (int a = 0; a < 3; ++a) {
    v.dims[a] = dims_[a];
    v.scale[a] = scale_[a];
  }
  return v;
}

}  // namespace mfadvr
