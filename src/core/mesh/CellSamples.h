#pragma once
// Samples of a tetrahedral mesh's own field inside its cells. A mesh defines its field between
// the points by linear interpolation in each tetrahedron (what VTK's tetrahedral ray casters
// render); a spline fitted to the points alone is free between them and rings where the points
// are sparse next to a steep feature. Fitting also to the linear field at points inside the
// cells ties the spline to the mesh's field everywhere the mesh is.
#include <cstdint>

#include "core/mesh/ScatteredData.h"

namespace mfadvr {

// The quadrature rules that place samples in a tetrahedron: 1 (the centroid) or 4 (the
// degree-2 rule of four points, barycentric (a, b, b, b) and permutations).
bool isCellSampleCount(int perCell);

// `data` with, after its points, `perCell` samples of every tetrahedron of nonzero volume, each
// with the linear interpolation of its tetrahedron's vertex values. Throws mfadvr::Error for an
// unsupported count, data without cells, or data that fail ScatteredData::validate (such as a
// tetrahedron index out of range). The points come first and keep their order; the tetrahedra
// stay as they were (they index the points only).
ScatteredData withCellSamples(const ScatteredData& data, int perCell);

// Samples withCellSamples adds: `perCell` per tetrahedron of nonzero volume (of valid data).
std::int64_t cellSampleCount(const ScatteredData& data, int perCell);

}  // namespace mfadvr
