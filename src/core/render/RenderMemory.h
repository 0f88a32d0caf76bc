#pragma once
// What rendering a model will hold in memory, from its file's header alone, so that a model too
// large for the machine is refused before its blocks are read (MemoryBudget.h).
#include <cstdint>
#include <span>
#include <string>

#include "core/model/ModelFile.h"

namespace mfadvr {

// Bytes a renderer holds for one model: the loaded model (loadedModelBytes: 4 B per control
// point, and the coded bytes of a lossy coding) and for empty-space skipping one flag per
// knot-span cell with the pyramid above them (EmptySpaceFlags: under 1/7 more; the cells'
// bounds are computed for the flags and not kept). extremeBounds: a maximum or minimum
// intensity render, which also holds two bytes of bounds per cell and their pyramids
// (ExtremeBounds.h, CellPyramid.h: under 2/7 more).
std::int64_t modelRenderBytes(const ModelFileSummary& model, bool extremeBounds = false);

// A whole scene of models (one, or the blocks of a multi-block file): the sum of
// modelRenderBytes plus, while a model is read, its file bytes once more (the largest of those
// not read in place: ModelFileSummary::readInPlace).
std::int64_t sceneRenderBytes(std::span<const ModelFileSummary> models, bool extremeBounds = false);

// Throws mfadvr::Error (MemoryBudget.h's requireMemory) when the scene cannot be held: the
// message is "<what> (N control points<detail>) needs about ...".
void requireSceneRenderMemory(std::span<const ModelFileSummary> models, const std::string& what,
                              const std::string& detail = "", bool extremeBounds = false);

}  // namespace mfadvr
