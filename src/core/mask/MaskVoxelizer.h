#pragma once
// Building a DomainMask from scattered input (docs/architecture.md, Domains and masks).
//
// Both builders set node values on the mask grid over `box` (node (i,j,k) at
// box.min + (i/(mx-1), j/(my-1), k/(mz-1)) * extent). The mask then counts a point as inside
// where the trilinear interpolation of the nodes is at least 1/2 (DomainMask.h).
//
// Both run over all cores and give the same mask for any thread count: a node is only ever
// raised from 0 to 1, so the order of the writes does not matter.
#include <cstdint>
#include <span>

#include "core/mask/DomainMask.h"
#include "core/mesh/ScatteredData.h"
#include "core/model/Model.h"

namespace mfadvr {

// Default node count of the longest box axis for a mesh occupancy mask.
inline constexpr int kDefaultMeshMaskNodes = 128;

// Occupancy of a tetrahedral mesh: node = 1 where the node position lies inside or on some
// tetrahedron (barycentric coordinates >= -1e-9, a tolerance relative to the tetrahedron, so
// nodes on shared faces and on the mesh boundary count as inside). Each tetrahedron visits only
// the nodes in its bounding box. Degenerate (zero-volume) tetrahedra are skipped.
// A part of the mesh thinner than a node spacing may contain no node and so be lost: choose
// dims so that the spacing is finer than the thinnest feature worth keeping
// (defaultMaskDims(box, kDefaultMeshMaskNodes) suits meshes of solid bodies).
// Throws mfadvr::Error for bad dims (DomainMask's limits) or a tetrahedron index out of range.
DomainMask meshOccupancyMask(std::span<const Vec3d> points, std::span<const Tetrahedron> tets,
                             const DomainBox& box, Index3 dims);

// Coverage of a point cloud: every point sets the 8 corner nodes of the node cell that contains
// it (points outside the box are clamped onto it), then a morphological closing by one node
// (dilation, then erosion, each over the 26-neighbourhood, the 3x3x3 block of nodes) fills gaps
// of up to two unset nodes between set ones. Erosion considers only neighbours inside the
// grid, so nodes on the box faces are not eroded merely for lying on the border and the closing
// never removes a node the points set.
// With defaultCoverageResolution the boundary lies within about one node spacing of the cloud.
// Throws mfadvr::Error for bad dims.
DomainMask pointCoverageMask(std::span<const Vec3d> points, const DomainBox& box, Index3 dims);

// Node counts proportional to the box extent with (about) equal spacing on every axis: the
// longest axis gets longestAxisNodes (clamped to DomainMask's 2..kMaxMaskNodesPerAxis), the
// others round(extent / spacing) + 1, at least 2. The longest axis gets fewer where the total
// would exceed kMaxMaskNodes.
Index3 defaultMaskDims(const DomainBox& box, int longestAxisNodes);

// Longest-axis node count for a point-coverage mask of `pointCount` points: about the cube root
// of the count, clamped to 8..256. A cloud that fills its box then puts about one point in each
// node cell; since a point sets all 8 corners of its cell, a node inside the cloud stays unset
// only when all 8 cells around it are empty (about e^-8 of them for a uniform cloud), and the
// closing fills those. A finer grid would leave holes between the points; a coarser one would
// blur the boundary further than needed. Non-cubic boxes get fewer nodes in total, so more
// points per cell.
int defaultCoverageResolution(std::int64_t pointCount);

}  // namespace mfadvr
