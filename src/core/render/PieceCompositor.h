#pragma once
// Compositing the images of the pieces of a partitioned volume, as a parallel compositor (IceT
// in ParaView) does across ranks: per pixel, the premultiplied images of the pieces are blended
// front to back in the order in which the pixel's ray enters the pieces' regions. Regions must
// not overlap (the pieces of PieceEncoder.h, the blocks of a multi-block model file).
#include <cstdint>
#include <functional>
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

// When the regions are cells of one grid (each spans one interval between consecutive faces of
// the regions on every axis, no two the same; the blocks of `encode --blocks`): an order of the
// pieces that is front to back for every ray of `settings`' camera. Along a ray, a cell's
// distance in cells from the camera's cell (summed over the axes) only grows, so sorting the
// cells by it orders the cells of every ray. Empty when the regions are not such cells.
std::vector<size_t> gridVisibilityOrder(const RenderSettings& settings,
                                        const std::vector<DomainBox>& regions);

// The pixels (inclusive bounds, two pixels of margin) onto which `region` projects under `rays`;
// the whole image when some of it lies behind a perspective camera. Empty: x1 < x0 or y1 < y0.
struct PixelRect {
  int x0, x1, y0, y1;
  std::int64_t count() const {
    return x1 < x0 || y1 < y0 ? 0 : std::int64_t(x1 - x0 + 1) * (y1 - y0 + 1);
  }
};
PixelRect projectedPixels(const CameraRays& rays, const DomainBox& region);

// The rays over `region`'s projection that have not ended at once (ends: none, or > 0 per
// pixel, RenderSettings::rayEnd): at least every ray that can sample the region.
std::int64_t raysStillGoing(const CameraRays& rays, const std::vector<float>& ends,
                            const DomainBox& region);

// Renders the pieces of a partitioned volume here, as the ranks of a parallel renderer would:
// renderPiece(i, pieceSettings, pieceStats) renders piece i with `settings` clipped to
// regions[i], with camera-aligned steps (RenderSettings::alignSamplesToCamera) over a
// transparent background; the images are composited in visibility order. The result is
// premultiplied over a transparent background; stats (optional) receive the pieces' sums.
// Pieces that are cells of a grid (gridVisibilityOrder) are rendered in that order and each
// composited as soon as it is rendered, so that one piece's image is held at a time (and a
// caller may read one piece's model at a time); a pixel whose composite reaches the early-
// termination opacity ends its ray before the pieces behind (as one ray through the whole
// would stop), and a piece that no remaining ray crosses is not rendered (renderPiece is not
// called for it). Other pieces are composited per pixel, all images held.
using PieceRenderer = std::function<Image(size_t, const RenderSettings&, RenderStats*)>;
Image renderPieces(const RenderSettings& settings, const std::vector<DomainBox>& regions,
                   const PieceRenderer& renderPiece, RenderStats* stats = nullptr);

// The same image over settings.background.
void compositeOverBackground(Image& image, const Vec3f& background);

}  // namespace mfadvr
