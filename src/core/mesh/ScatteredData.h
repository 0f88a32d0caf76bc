#pragma once
// Values at scattered points, optionally with the tetrahedral cells that connect them: the input
// of the scattered encoder. Meshes (.vtu, legacy unstructured .vtk, curvilinear .vts) carry their
// cells, split into tetrahedra, so that the encoder can voxelize an occupancy mask; point clouds
// (.vtp, CSV, text) carry none and get a coverage mask instead.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/util/Vec.h"

namespace mfadvr {

using Tetrahedron = std::array<std::int64_t, 4>;  // indices into ScatteredData::points

struct ScatteredData {
  std::vector<Vec3d> points;
  std::vector<double> values;     // one per point
  std::vector<Tetrahedron> tets;  // empty for point clouds

  std::string source;            // input path
  std::string fieldName;         // scalar array name ("value" for text files without a header)
  std::string fieldAssociation;  // how values reached the points, e.g. "point data" or
                                 // "cell data averaged to points"
  std::string kind;              // "tetrahedral mesh", "mixed-cell mesh", "curvilinear grid",
                                 // "point cloud"
  std::string sampleType;        // storage type of the source values (float32, ...)
  std::int64_t inputBytes = 0;   // bytes of the values in their source type
  std::int64_t inputCells = 0;   // cells in the source before splitting into tetrahedra

  std::int64_t pointCount() const { return static_cast<std::int64_t>(points.size()); }
  bool hasCells() const { return !tets.empty(); }
  Vec3d boxMin() const;
  Vec3d boxMax() const;
  // Six times the signed volume of tetrahedron t (the triple product of its edges from t[0]);
  // 0 for a flat one. Its indices must be valid (validate()).
  double volume6(const Tetrahedron& t) const;

  // Throws mfadvr::Error for: no points, values not one per point, a NaN/Inf coordinate or
  // value (naming the first), a box of zero extent on some axis, a tetrahedron index out of
  // range. The message names `source`.
  void validate() const;
};

}  // namespace mfadvr
