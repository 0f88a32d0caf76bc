#pragma once
// Which block of a multi-block model holds a point: the blocks' regions tile their box as a
// grid (x fastest), so a point's block is, along each axis, the number of block boundaries at or
// below its coordinate. A point on a shared face belongs to the block above it; a point outside
// the box to the nearest block along each axis (whose model extends past its region by its
// ghost layers, and is evaluated there as any model is outside its domain).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/model/BlockModelFile.h"

namespace mfadvr {

// The union of the blocks' regions (blocks non-empty).
DomainBox regionsBox(std::span<const ModelBlock> blocks);

class BlockLocator {
 public:
  // `grid` blocks per axis, blocks in file order; throws mfadvr::Error when their number or their
  // regions do not form that grid.
  BlockLocator(std::span<const ModelBlock> blocks, const Index3& grid);

  // Along axis a, the block (0 .. grid[a] - 1) whose slab holds coordinate x.
  std::int64_t axisBlock(int a, double x) const;
  // The index (x fastest) of the block holding x.
  size_t blockOf(const Vec3d& x) const;
  const Index3& grid() const { return grid_; }

 private:
  Index3 grid_;
  std::array<std::vector<double>, 3> lower_;  // per axis: the regions' lower faces above the first
};

}  // namespace mfadvr
