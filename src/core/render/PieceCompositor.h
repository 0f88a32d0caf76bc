#pragma once
// Compositing the images of the pieces of a partitioned volume, as a parallel compositor (IceT
// in ParaView) does across ranks: per pixel, the premultiplied images of the pieces are blended
// front to back in the order in which the pixel's ray enters the pieces' regions. Regions must
// not overlap (the pieces of PieceEncoder.h, the blocks of a multi-block model file).
#include <vector>

#include "core/image/Image.h"
#include "core/model/Model.h"
#include "core/render/RenderSettings.h"

namespace mfadvr {

// images[i]: piece i rendered with `settings` clipped to regions[i], over a transparent
// background (0). The result is premultiplied, over a transparent background.
Image compositeInVisibilityOrder(const RenderSettings& settings,
                                 const std::vector<DomainBox>& regions,
                                 const std::vector<Image>& images);

// The same image over settings.background.
void compositeOverBackground(Image& image, const Vec3f& background);

}  // namespace mfadvr
