#pragma once
// Bilinear resizing of rendered images: an interactive frame is ray cast at a fraction of the
// viewport's pixels and magnified smoothly, not in blocks. Pixel centres map onto pixel centres
// (x_src = (x + 1/2) w_src / w - 1/2), clamped at the borders. Applied to premultiplied RGBA
// (as the ray caster produces over a zero background) the interpolation is the right one.
#include "core/image/Image.h"

namespace mfadvr {

// Throws mfadvr::Error on an empty source or a size outside Image's limits.
Image resizeBilinear(const Image& source, int width, int height);

}  // namespace mfadvr
