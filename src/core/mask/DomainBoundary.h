#pragma once
// A mesh's exact boundary: the triangles where its tetrahedra meet the outside, oriented
// outward, with a bounding-volume hierarchy over them (docs/architecture.md, Domains and masks).
//
// A voxel mask (DomainMask.h) draws a curved mesh boundary as the level set of a trilinear
// interpolation of node bits: within half a node spacing of the truth, and in a zoomed picture a
// staircase. The boundary surface is the truth: the renderer finds each ray's stretches inside
// it (BoundaryView.h) and samples only there; point queries test it by a line through the
// point. Holes, cavities and separate parts are all boundary like the outer hull.
//
// The hierarchy is built when the boundary is made or read (not stored): median splits of the
// triangles' centroids along the longest axis, at most 4 triangles a leaf, so that its depth
// stays within the traversal stack for any mesh up to 2^31 triangles.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/mask/BoundaryView.h"
#include "core/mesh/ScatteredData.h"
#include "core/util/Vec.h"

namespace mfadvr {

using BoundaryTriangle = std::array<std::uint32_t, 3>;  // vertex indices, outward order

// Limits on a stored boundary, so that sizes cannot overflow: 2^26 vertices and triangles.
inline constexpr std::int64_t kMaxBoundaryElements = std::int64_t(1) << 26;

class DomainBoundary {
 public:
  DomainBoundary() = default;
  // Throws mfadvr::Error for counts beyond the limit, an index out of range or a coordinate
  // that is NaN or infinite.
  DomainBoundary(std::vector<Vec3f> vertices, std::vector<BoundaryTriangle> triangles);

  bool empty() const { return triangles_.empty(); }
  const std::vector<Vec3f>& vertices() const { return vertices_; }
  const std::vector<BoundaryTriangle>& triangles() const { return triangles_; }

  // The plain view the renderer reads; valid while this boundary lives.
  BoundaryView view() const;
  // Whether x lies inside (winding number of the boundary about x above 0). Points on the
  // boundary may go either way. True for an empty boundary.
  bool contains(const Vec3d& x) const;

 private:
  std::vector<Vec3f> vertices_;
  std::vector<BoundaryTriangle> triangles_;
  std::vector<BoundaryNode> nodes_;
  std::vector<double> leafTriangles_;  // 9 per triangle, in the order of the leaves
  double scale_ = 1.0;
};

// The boundary of a tetrahedral mesh: the faces that belong to one tetrahedron only, after
// points at identical positions are taken as one (meshes of several blocks repeat the points
// of the faces where blocks meet, and those faces are not boundary). Each face is oriented away
// from the rest of its tetrahedron. Tetrahedra of zero volume are left out. Throws mfadvr::Error
// for an index out of range or more boundary elements than the limit.
DomainBoundary boundaryOfTetrahedra(std::span<const Vec3d> points,
                                    std::span<const Tetrahedron> tets);

}  // namespace mfadvr
