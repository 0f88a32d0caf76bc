// The MFA model's render path: the shared per-ray integration over SplineRaySampler, with the
// spline's degree, the domain mask, shading and empty-space skipping chosen once per render
// (ModelKernelSwitch.h).
#include <chrono>
#include <optional>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>

#include "core/render/BoundaryRaster.h"
#include "core/render/DepthBounds.h"
#include "core/render/ModelKernelSwitch.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {

Image renderModelView(const RenderSettings& settings, const RayParams& params,
                      const ModelView& view, RenderStats* stats) {
  Image image(settings.width, settings.height);
  RayParams frame = params;
  keepDepth(settings, image, frame);
  // Where the rays may begin and end their march through empty space: a pass over the coarse
  // blocks, timed as part of the frame. A masked model's march counts the steps outside its mask
  // apart.
  const auto start = std::chrono::steady_clock::now();
  std::optional<DepthBounds> depth;
  if (view.empty && !view.mask.nodes && !view.boundary.nodes &&
      params.blend == BlendMode::Composite) {
    auto build = [&] { depth.emplace(params.camera, view); };
    if (settings.threads > 0)
      tbb::task_arena(settings.threads).execute(build);
    else
      build();
  }
  // A mesh's boundary: its triangles projected into the image once, so that each tile gathers
  // its rays' stretches inside the mesh at once (BoundaryRaster.h).
  std::optional<BoundaryRaster> raster;
  if (view.boundary.nodes) {
    auto build = [&] { raster.emplace(view.boundary, params.camera); };
    if (settings.threads > 0)
      tbb::task_arena(settings.threads).execute(build);
    else
      build();
  }
  tbb::enumerable_thread_specific<BoundaryTileStretches> tileStretches;
  const double boundsSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  modelKernelSwitch(view, settings.needsGradients(),
                    [&]<int P, bool Masked, bool Shade, bool Skip>() {
                      auto make = [&](int x0, int y0, int x1, int y1) {
                        SplineRaySampler<P, Skip, Shade> sampler(view);
                        if (Masked && raster) {
                          BoundaryTileStretches& tile = tileStretches.local();
                          raster->gather(x0, y0, x1, y1, tile);
                          sampler.useBoundaryTile(tile.view);
                        }
                        return sampler;
                      };
                      castRays<Masked, Shade>(settings, frame, make, image, stats,
                                              depth ? depth->view() : DepthBoundsView{});
                    });
  if (stats) stats->seconds += boundsSeconds;
  return image;
}

Image renderModel(const ModelField& field, const RenderSettings& settings, RenderStats* stats) {
  const ModelRenderSetup setup(field, settings);
  Image image = renderModelView(settings, setup.params(), setup.view(), stats);
  if (stats) stats->seconds += setup.setupSeconds();
  return image;
}

}  // namespace mfadvr
