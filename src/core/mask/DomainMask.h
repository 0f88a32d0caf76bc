#pragma once
// Where a model is defined: an occupancy grid over the model's box.
//
// A spline fitted to a curved mesh or a point cloud is defined on the whole box and extrapolates
// outside the data (docs/architecture.md, Domains and masks). The mask records which part of the
// box the data cover: 0/1 values at the nodes of a regular grid spanning the box (node (i,j,k) at
// parameter (i/(mx-1), j/(my-1), k/(mz-1))). A point is inside where the trilinear interpolation of
// the node values is at least 1/2, so the boundary is a smooth-ish surface within half a node
// spacing of the data's boundary rather than a staircase of voxels.
// An empty mask (the default) means "everything inside": structured grids need none.
#include <cstdint>
#include <string>
#include <vector>

#include "core/mask/MaskView.h"
#include "core/util/Vec.h"

namespace mfadvr {

enum class MaskKind {
  MeshOccupancy,  // nodes inside some cell of the input mesh
  PointCoverage,  // nodes near input points (point clouds)
};
std::string maskKindName(MaskKind kind);          // "mesh-occupancy" / "point-coverage"
MaskKind parseMaskKind(const std::string& name);  // throws mfadvr::Error

// Limits on a mask's grid, so that node counts and file sizes cannot overflow: 2..4096 nodes per
// axis and at most 2^31 nodes in all (2 GiB as bytes in memory, 256 MiB bit-packed in a file).
inline constexpr std::int64_t kMaxMaskNodesPerAxis = 4096;
inline constexpr std::int64_t kMaxMaskNodes = std::int64_t(1) << 31;

class DomainMask {
 public:
  DomainMask() = default;
  // nodes: x fastest, one byte per node, 0 or 1 (any non-zero byte is stored as 1). Throws
  // mfadvr::Error for dims outside the limits above or a size mismatch.
  DomainMask(MaskKind kind, Index3 dims, std::vector<std::uint8_t> nodes);
  // Throws mfadvr::Error unless dims are within the limits above.
  static void validateDims(const Index3& dims);

  bool empty() const { return nodes_.empty(); }
  MaskKind kind() const { return kind_; }
  const Index3& dims() const { return dims_; }
  const std::vector<std::uint8_t>& nodes() const { return nodes_; }
  // Fraction of nodes inside (1 for an empty mask).
  double insideFraction() const;

  // u: parameter in [0,1]^3 (clamped). Always true for an empty mask.
  bool insideParameter(const Vec3d& u) const {
    const double x[3] = {u[0], u[1], u[2]};
    return insideMask(view(), x);
  }
  // The plain view the renderer reads (MaskView.h); valid while this mask lives.
  MaskView view() const;

 private:
  MaskKind kind_ = MaskKind::MeshOccupancy;
  Index3 dims_{0, 0, 0};
  std::vector<std::uint8_t> nodes_;
  Vec3d scale_ = Vec3d::Zero();  // dims - 1
};

}  // namespace mfadvr
