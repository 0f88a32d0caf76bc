#pragma once
// Side-by-side image grids for comparisons.
#include <vector>

#include "core/image/Image.h"

namespace mfadvr {

// Places the images left to right, `gap` pixels apart, on a `background` grey; they need not
// share a size (shorter ones are top-aligned). Output is RGB.
Image8 montageHorizontal(const std::vector<Image8>& images, int gap = 8,
                         std::uint8_t background = 255);

// Rows of montageHorizontal stacked top to bottom, `gap` pixels apart, left-aligned (rows may
// differ in length and height). Output is RGB.
Image8 montageGrid(const std::vector<std::vector<Image8>>& rows, int gap = 8,
                   std::uint8_t background = 255);

}  // namespace mfadvr
