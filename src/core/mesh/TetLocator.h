#pragma once
// The field a tetrahedral mesh defines: linear in each tetrahedron (barycentric interpolation of
// its four vertex values), what VTK's tetrahedral ray casters (Bunyk, ZSweep, projected
// tetrahedra) render. A point is located in its tetrahedron through a uniform grid of bins, each
// listing the tetrahedra whose bounding box overlaps it; each tetrahedron keeps the affine map to
// its barycentric coordinates and the (constant) gradient of its linear piece.
//
// It lets the renderer sample the mesh itself through the same ray caster as the models
// (MeshField.h, --method mesh): a reference without a second renderer's differences.
#include <cstdint>
#include <vector>

#include "core/mesh/ScatteredData.h"
#include "core/spline/TensorBSpline.h"  // ValueGradient
#include "core/util/Vec.h"

namespace mfadvr {

class TetLocator {
 public:
  // Throws mfadvr::Error for data without tetrahedra (a point cloud) and for invalid data
  // (ScatteredData::validate). Flat tetrahedra (zero volume) are left out: they hold no point
  // that another tetrahedron does not.
  explicit TetLocator(const ScatteredData& mesh);

  Vec3d boxMin() const { return boxMin_; }
  Vec3d boxMax() const { return boxMax_; }
  std::int64_t tetCount() const { return static_cast<std::int64_t>(tets_.size()); }
  std::int64_t binCount() const { return static_cast<std::int64_t>(binStart_.size()) - 1; }

  // A tetrahedron (index into the kept ones) holding x, or -1 when x lies outside the mesh.
  // `hint` (a previous answer, or -1) is tried first: consecutive samples of a ray mostly lie in
  // one tetrahedron. Points on a face shared by two tetrahedra get either (the field is
  // continuous there).
  std::int64_t locate(const Vec3d& x, std::int64_t hint = -1) const;
  // The linear piece of tetrahedron `tet` at x, with its gradient.
  ValueGradient linear(std::int64_t tet, const Vec3d& x) const;

 private:
  // x -> barycentric coordinates 1..3 is inverse * (x - origin); coordinate 0 is 1 - their sum.
  // The field is value0 + gradient . (x - origin).
  struct Piece {
    Vec3d origin;
    Eigen::Matrix3d inverse;
    Vec3d gradient;
    double value0;
  };
  bool contains(const Piece& p, const Vec3d& x) const;
  // The bin along axis a of a point in the box.
  std::int64_t binIndex(const Vec3d& x, int a) const;

  std::vector<Piece> tets_;
  Vec3d boxMin_, boxMax_;
  Index3 bins_{1, 1, 1};
  Vec3d binScale_;                      // bins per unit length, per axis
  std::vector<std::int64_t> binStart_;  // tetrahedra of bin b: binTets_[binStart_[b] .. b + 1)
  std::vector<std::uint32_t> binTets_;
};

}  // namespace mfadvr
