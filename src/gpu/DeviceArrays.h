#pragma once
// Which host arrays a device copy of a render needs, and the plain structs with their pointers
// moved to those copies. The CUDA renderer uploads exactly these arrays and launches on the
// relocated structs; the tests relocate onto host copies and render them with the CPU driver,
// so that the sizes and the pointer rewriting are checked on machines without a GPU.
// Plain C++: no CUDA headers.
#include <cstddef>
#include <vector>

#include "core/render/EmptySpaceGrid.h"
#include "core/render/kernel/RayParams.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr::gpu {

struct HostArray {
  const void* data;
  std::size_t bytes;
  const char* what;  // for messages ("the control points")
};

std::size_t totalBytes(const std::vector<HostArray>& arrays);

// The model's own arrays, in a fixed order: control points; per axis knots, basis polynomials,
// inverse span lengths; the mask's nodes when there is a mask; a mesh's exact boundary (its
// hierarchy's nodes, its triangles) when there is one. (Not the empty-space flags, which depend
// on the transfer function.)
std::vector<HostArray> modelArrays(const ModelView& view);
// `view` with those arrays replaced by `copies` (one per modelArrays(view) entry, same order).
ModelView relocateModel(const ModelView& view, const std::vector<const void*>& copies);

// The empty-space flags the device's rays read: the cells' (each holds its level of the pyramid,
// ModelView::empty). The pyramid serves the host's depth bounds only and stays on the host: the
// relocated view has none (emptyPyramid null, emptyLevels 0).
std::vector<HostArray> flagArrays(const EmptySpaceFlags& flags);
ModelView relocateFlags(const ModelView& view, const std::vector<const void*>& copies);

// A frame's own arrays: the transfer-function table, then the ray ends when present.
std::vector<HostArray> frameArrays(const RayParams& params);
RayParams relocateFrame(const RayParams& params, const std::vector<const void*>& copies);

}  // namespace mfadvr::gpu
