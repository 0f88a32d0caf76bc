#pragma once
// A pyramid over one byte per knot-span cell: level l = 1..levels has one byte per aligned block
// of 2^l x 2^l x 2^l cells (clipped at the grid's far faces), the least or the greatest of the
// bytes of its up to eight blocks one level down. Empty-space flags take the least of 0/1 flags
// (a block is empty when all its cells are, EmptySpaceGrid.h), the bounds of maximum and minimum
// intensity skipping the greatest upper and the least lower bound (ExtremeBounds.h).
#include <cstdint>
#include <vector>

#include "core/render/kernel/SplineRaySampler.h"  // EmptyLevelView, kMaxEmptyLevels

namespace mfadvr {

struct CellPyramid {
  int levels = 0;
  EmptyLevelView level[kMaxEmptyLevels];  // level l + 1's block counts and where they start
  std::vector<std::uint8_t> bytes;
};

// Levels go up until one block covers the grid (at most kMaxEmptyLevels); greatest: the
// reduction (else the least).
CellPyramid buildCellPyramid(const int cells[3], const std::uint8_t* cellBytes, bool greatest);

}  // namespace mfadvr
