#pragma once
// A small built-in bitmap font (5x7 pixel glyphs in 6x8 cells) for labelling images: montage
// captions with method names and metrics, with no font files or libraries. Covers digits,
// both letter cases and common punctuation; any other character draws as a hollow box.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/image/Image.h"

namespace mfadvr {

inline constexpr int kGlyphWidth = 5, kGlyphHeight = 7;
inline constexpr int kCellWidth = 6, kCellHeight = 8;  // glyph plus one pixel of spacing

using Rgb8 = std::array<std::uint8_t, 3>;

// Whether `c` has a glyph of its own (others draw as a box).
bool hasGlyph(char c);

// Width in pixels of `text` drawn at `scale` (each font pixel a scale x scale square); the
// trailing spacing column is not counted.
int textWidth(std::string_view text, int scale);

// Draws `text` with its top-left corner at (x, y); pixels outside the image are clipped.
void drawText(Image8& image, int x, int y, std::string_view text, int scale, Rgb8 color);

// The image with a band below it holding one line of text per entry, left-aligned, in `color`
// on `background`. The scale is the largest of 1..maxScale at which the widest line fits the
// image's width; when even scale 1 does not fit, the output is widened to the text (the image
// stays at the left) rather than clipping it. Output is RGB.
Image8 withCaption(const Image8& image, const std::vector<std::string>& lines, int maxScale,
                   Rgb8 color = {0, 0, 0}, Rgb8 background = {255, 255, 255});

}  // namespace mfadvr
