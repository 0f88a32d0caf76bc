#pragma once
// Grid samples (float) with one ghost layer on every side, filled by linear extrapolation
// (ghost = 2 * edge - neighbour, axis by axis). The ghosts let every filter use its full stencil
// in boundary cells without branches, and linear extrapolation is what makes every filter
// reproduce a linear field exactly up to the boundary: Catmull-Rom and tricubic get one-sided
// differences there, and the prefiltered B-spline gets natural end conditions.
#include <cmath>
#include <vector>

#include "core/grid/StructuredGrid.h"
#include "core/render/kernel/TrilinearKernel.h"
#include "core/util/Vec.h"

namespace mfadvr {

class PaddedGrid {
 public:
  PaddedGrid() = default;
  // Requires at least 2 samples per axis (a filter needs a cell); throws mfadvr::Error otherwise.
  // `values` (x fastest, dims[0]*dims[1]*dims[2]) replace the grid's samples when non-null.
  explicit PaddedGrid(const StructuredGrid& grid, const std::vector<double>* values = nullptr);

  const Index3& dims() const { return dims_; }
  Vec3d boxMin() const { return origin_; }
  Vec3d boxMax() const { return boxMax_; }
  const Vec3d& spacing() const { return spacing_; }
  const Vec3d& inverseSpacing() const { return invSpacing_; }

  // Sample (i, j, k), each index in [-1, n]: -1 and n are the ghosts.
  float at(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return data_[static_cast<size_t>((i + 1) + sy_ * (j + 1) + sz_ * (k + 1))];
  }
  const float* pointer(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return data_.data() + ((i + 1) + sy_ * (j + 1) + sz_ * (k + 1));
  }
  std::int64_t strideY() const { return sy_; }
  std::int64_t strideZ() const { return sz_; }
  // The plain view of the trilinear kernel (render/kernel/TrilinearKernel.h); valid while this
  // grid lives.
  GridView view() const {
    GridView v;
    v.data = data_.data();
    v.sy = sy_;
    v.sz = sz_;
    for (int a = 0; a < 3; ++a) {
      v.dims[a] = dims_[a];
      v.origin[a] = origin_[a];
      v.inverseSpacing[a] = invSpacing_[a];
    }
    return v;
  }
  // Number of floats in the padded array (view().data).
  size_t paddedSize() const { return data_.size(); }

  // Continuous index of physical point x, clamped to [0, n-1] per axis (the lookup of
  // render/kernel/TrilinearKernel.h, shared with the GPU).
  [[gnu::always_inline]] Vec3d continuousIndex(const Vec3d& x) const {
    Vec3d u;
    for (int a = 0; a < 3; ++a) u[a] = gridIndex(x[a], origin_[a], invSpacing_[a], dims_[a]);
    return u;
  }
  // Cell of a continuous index: i in [0, n-2] and the fraction t in [0, 1].
  [[gnu::always_inline]] void cell(const Vec3d& u, std::int64_t i[3], double t[3]) const {
    for (int a = 0; a < 3; ++a) gridCellOf(u[a], dims_[a], i[a], t[a]);
  }

 private:
  Index3 dims_{0, 0, 0};
  Vec3d origin_ = Vec3d::Zero(), boxMax_ = Vec3d::Zero();
  Vec3d spacing_ = Vec3d::Ones(), invSpacing_ = Vec3d::Ones();
  std::int64_t sy_ = 0, sz_ = 0;
  std::vector<float> data_;
};

}  // namespace mfadvr
