#pragma once
// PNG files for rendered images and references, through libpng. Pixel values are taken as
// stored: no gamma or colour-profile conversion, so that metrics see exactly the file's bytes.
#include <cstdint>
#include <span>
#include <string>

#include "core/image/Image.h"

namespace mfadvr {

// Encodes an 8-bit RGB or RGBA image (checked with checkImage8) as PNG bytes.
std::string encodePng(const Image8& image);

// Decodes any PNG that libpng reads: palette, gray (1..16 bit), gray+alpha, RGB(A) 8 or 16 bit,
// interlaced or not. The result is 8-bit RGB, or RGBA when the file has an alpha channel or a
// tRNS chunk; 16-bit samples are scaled (rounded) to 8 bits. Any damaged or truncated input
// gives mfadvr::Error naming `name`, never a crash.
Image8 decodePng(std::span<const std::uint8_t> bytes, const std::string& name = "PNG");

// Writes atomically (a temporary file beside the target, renamed over it); mfadvr::Error naming
// the path on failure, with no file left behind.
void writePng(const std::string& path, const Image8& image);
Image8 readPng(const std::string& path);

}  // namespace mfadvr
