#pragma once
// Float images for analysis (ParaView, Python): an NRRD file with an attached header,
//
//   NRRD0004 / comment / type: float / dimension: 3 / sizes: 4 W H / encoding: raw /
//   endian: little / blank line, then 16 * W * H bytes of float32 RGBA, x fastest, row 0 at top.
//
// The values are the renderer's own: linear RGBA, RGB composited over the background, alpha the
// accumulated opacity; nothing is clamped or quantized.
#include <string>

#include "core/image/Image.h"

namespace mfadvr {

// Atomic write (temporary file renamed over the target); mfadvr::Error naming the path on failure.
void writeFloatImage(const std::string& path, const Image& image);

// image.depth as a float32 NRRD of sizes W H (x fastest, row 0 at the top), NaN where a ray has
// no depth; `rule` (one line) says what the distances are, in the header's comment. Atomic.
void writeDepthImage(const std::string& path, const Image& image, const std::string& rule);

}  // namespace mfadvr
