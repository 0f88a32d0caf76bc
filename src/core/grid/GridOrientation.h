#pragma once
// Placing a grid stored in a scanner's index order into world axes.
//
// Medical formats (NIfTI's qform/sform, DICOM's patient orientation) store the volume in the
// order the scanner acquired it and give a matrix from the index frame to world coordinates:
// world = R * (i * sx, j * sy, k * sz) + t. Our grids are axis-aligned in world space, so a
// matrix whose columns each point along one world axis (a permutation with flips, e.g. the
// usual LPS or RAS storage orders) is applied exactly by reordering the samples; an oblique
// matrix cannot be, and the grid stays in its index frame with a note saying so.
#include <string>

#include "core/grid/StructuredGrid.h"

namespace mfadvr {

struct GridToWorld {
  double linear[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  // R: row = world axis
  Vec3d offset = Vec3d::Zero();                             // t: world position of sample 0
};

struct OrientationResult {
  bool applied = false;  // the samples are now in world axes, at world positions
  std::string note;      // why not (empty when applied)
  std::string axes;      // the index axes' world directions, e.g. "-x,-y,+z" (or "oblique")
};

// Reorders `grid` (its origin and spacing are the index frame's: sample (i,j,k) sits at
// R * (origin + (i sx, j sy, k sz)) + t in the world) into
// world axes when `toWorld.linear` is a signed permutation up to per-column scale (relative
// off-axis parts below `tolerance`); the spacing becomes |R column| * spacing. Otherwise only
// the origin moves to sample 0's world position and the result carries a note.
OrientationResult orientToWorld(StructuredGrid& grid, const GridToWorld& toWorld,
                                double tolerance = 1e-4);

}  // namespace mfadvr
