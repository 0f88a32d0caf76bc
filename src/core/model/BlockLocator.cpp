#include "core/model/BlockLocator.h"

#include <algorithm>

#include "core/util/Error.h"

namespace mfadvr {

DomainBox regionsBox(std::span<const ModelBlock> blocks) {
  DomainBox box = blocks.front().region;
  for (const ModelBlock& b : blocks) {
    box.min = box.min.cwiseMin(b.region.min);
    box.max = box.max.cwiseMax(b.region.max);
  }
  return box;
}

BlockLocator::BlockLocator(std::span<const ModelBlock> blocks, const Index3& grid) : grid_(grid) {
  if (grid[0] < 1 || grid[1] < 1 || grid[2] < 1 ||
      static_cast<std::int64_t>(blocks.size()) != grid[0] * grid[1] * grid[2])
    throw Error("a multi-block model of " + std::to_string(blocks.size()) +
                " blocks is not a grid of " + std::to_string(grid[0]) + "x" +
                std::to_string(grid[1]) + "x" + std::to_string(grid[2]));
  const std::int64_t stride[3] = {1, grid[0], grid[0] * grid[1]};
  for (int a = 0; a < 3; ++a)
    for (std::int64_t i = 1; i < grid[a]; ++i) {
      const double lower = blocks[static_cast<size_t>(i * stride[a])].region.min[a];
      if (!lower_[a].empty() && !(lower > lower_[a].back()))
        throw Error("the blocks' regions do not follow one another along axis " +
                    std::to_string(a));
      lower_[a].push_back(lower);
    }
}

std::int64_t BlockLocator::axisBlock(int a, double x) const {
  return std::upper_bound(lower_[a].begin(), lower_[a].end(), x) - lower_[a].begin();
}

size_t BlockLocator::blockOf(const Vec3d& x) const {
  return static_cast<size_t>(axisBlock(0, x[0]) +
                             grid_[0] * (axisBlock(1, x[1]) + grid_[1] * axisBlock(2, x[2])));
}

}  // namespace mfadvr
