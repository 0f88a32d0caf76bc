#pragma once
// The ray caster's CPU driver (paper section 3.1, Algorithm 1): square tiles of pixels spread
// over TBB threads, progress and timing around the shared per-ray integration
// (kernel/RayIntegrator.h, which describes the sampling, classification, shading and
// compositing). Every reconstruction method goes through it, so that each is rendered with
// exactly the same rays, samples, transfer function, shading and compositing.
//
// The MFA model (ModelField) takes its own path (ModelRenderer.h): the spline kernel with its
// degree fixed at compile time, batched sampling and exact empty-space skipping. Other fields
// go through FieldRaySampler.
//
// A field whose sampler has `bool inside(x)` (a model with a domain mask) is empty where it
// answers false; the ray loop is instantiated with and without that test. Rays may end early,
// per pixel (RenderSettings::rayEnd): opaque geometry in a VTK scene.
//
// Pixels are computed independently, so the image is bit-identical for any thread count. Where
// the sampler takes them, rows of a tile go eight rays at a time (kernel/RayPacketIntegrator.h),
// with the same result per pixel as one ray at a time; with empty-space skipping, groups of
// kMarchGroup rays make their way in through empty space together (kernel/InterleavedMarch.h),
// also with the same result per pixel.
#include <functional>
#include <type_traits>

#include "core/field/Field.h"
#include "core/field/ModelField.h"
#include "core/image/Image.h"
#include "core/render/ClassificationTables.h"
#include "core/render/FieldRaySampler.h"
#include "core/render/RenderSettings.h"
#include "core/render/TransferFunctionTable.h"
#include "core/render/kernel/DepthBoundsView.h"
#include "core/render/kernel/InterleavedMarch.h"
#include "core/render/kernel/RayIntegrator.h"
#include "core/render/kernel/RayPacketIntegrator.h"
#include "core/render/kernel/RayParams.h"

namespace mfadvr {

// The plain parameters of one render; `table` and `settings.rayEnd` must outlive the result.
RayParams compileRayParams(const RenderSettings& settings, const TransferFunctionTable& table,
                           const Vec3d& boxMin, const Vec3d& boxMax);

// The same with the gradient classification of `tables` (which must outlive the result).
RayParams compileRayParams(const RenderSettings& settings, const ClassificationTables& tables,
                           const Vec3d& boxMin, const Vec3d& boxMax);

// With settings.depth: image.depth filled with NaN and params.depth pointed at it.
void keepDepth(const RenderSettings& settings, Image& image, RayParams& params);

// The tile loop: calls tile(x0, y0, x1, y1, counters) for every 16x16 tile (clipped to the
// image) on settings.threads threads, reports progress, and fills stats (optional).
using TileFunction = std::function<void(int, int, int, int, RayCounters&)>;
void forEachTile(const RenderSettings& settings, const TileFunction& tile, RenderStats* stats);

// A sampler for the tile [x0, x1) x [y0, y1): make(x0, y0, x1, y1) where make takes the tile
// (to gather what the tile's rays share, such as their stretches inside a mesh's boundary), else
// make().
template <class MakeSampler>
auto samplerForTile(const MakeSampler& make, int x0, int y0, int x1, int y1) {
  if constexpr (std::is_invocable_v<const MakeSampler&, int, int, int, int>)
    return make(x0, y0, x1, y1);
  else
    return make();
}

// Casts every pixel's ray with samplers from make() or make(x0, y0, x1, y1) (one per tile). depth:
// where the rays of a sampler that skips empty space may begin and end their march (DepthBounds.h;
// not for Masked).
template <bool Masked, bool Shade, class MakeSampler>
void castRays(const RenderSettings& settings, const RayParams& params, const MakeSampler& make,
              Image& image, RenderStats* stats, DepthBoundsView depth = {}) {
  // Packets and the march ahead serve composite renders (the other blend modes sample every
  // step); packets keep no depth and classify by the value alone.
  const bool composite = params.blend == BlendMode::Composite;
  [[maybe_unused]] const bool packets = composite && !params.depth && !params.gradientTf.active() &&
                                        !params.curvatureTf.active() &&
                                        (!Shade || params.shadeSamples);
  forEachTile(
      settings,
      [&](int x0, int y0, int x1, int y1, RayCounters& counters) {
        auto sampler = samplerForTile(make, x0, y0, x1, y1);
        auto oneRay = [&](int x, int y) {
          RaySegment ray;
          const bool hits = raySegment(params, x, y, ray);
          RayStart start;
          if (!Masked && hits && composite && decltype(sampler)::kSkipsEmptySpace)
            start = boundSteps(depth, x, y, ray, params.sampleDistance);
          integrateSegment<Masked, Shade>(params, sampler, hits ? &ray : nullptr, start,
                                          image.pixel(x, y), counters);
        };
        for (int y = y0; y < y1; ++y) {
          int x = x0;
#if defined(MFADVR_SPLINE_LANE_KERNEL)
          // Eight rays at a time where the sampler takes packets; the same pixels either way.
          if constexpr (takesRayPackets<decltype(sampler)>()) {
            for (; packets && x + kRayPacket <= x1; x += kRayPacket) {
              float rgba[kRayPacket][4];
              if (integratePacket<Masked, Shade>(params, sampler, x, y, rgba, counters)) {
                for (int l = 0; l < kRayPacket; ++l)
                  for (int c = 0; c < 4; ++c) image.pixel(x + l, y)[c] = rgba[l][c];
              } else {
                for (int l = 0; l < kRayPacket; ++l) oneRay(x + l, y);
              }
            }
          }
#endif
          if constexpr (marchesRaysApart<decltype(sampler)>()) {
            // The way in through empty space, kMarchGroup rays at a time; not through a mesh's
            // exact boundary, which the sampler holds for one ray at a time.
            constexpr int G = kMarchGroup;
            const bool interleaved = composite && !(Masked && sampler.insideFollowsTheRay());
            for (; interleaved && x + G <= x1; x += G) {
              RaySegment segment[G];
              const RaySegment* rays[G];
              RayStart start[G];
              for (int g = 0; g < G; ++g) {
                rays[g] = raySegment(params, x + g, y, segment[g]) ? &segment[g] : nullptr;
                if (!Masked && rays[g])
                  start[g] = boundSteps(depth, x + g, y, segment[g], params.sampleDistance);
              }
              marchIn<G, Masked>(params, sampler, rays, start, counters);
              for (int g = 0; g < G; ++g)
                integrateSegment<Masked, Shade>(params, sampler, rays[g], start[g],
                                                image.pixel(x + g, y), counters);
            }
          }
          for (; x < x1; ++x) oneRay(x, y);
        }
      },
      stats);
}

// Renders the MFA model: ModelRenderer.cpp.
Image renderModel(const ModelField& field, const RenderSettings& settings,
                  RenderStats* stats = nullptr);

struct ModelView;
// The same from the plain structs of a render (ModelRenderSetup.h), or copies of them: the one
// switch on degree, mask (view.mask.nodes), shading and skipping (view.empty) per render.
Image renderModelView(const RenderSettings& settings, const RayParams& params,
                      const ModelView& view, RenderStats* stats = nullptr);

// Renders `field` with `settings`; stats (optional) receive the timing and counts.
template <Field F>
Image renderVolume(const F& field, const RenderSettings& settings, RenderStats* stats = nullptr) {
  if constexpr (std::same_as<F, ModelField>) {
    return renderModel(field, settings, stats);
  } else {
    settings.validate();
    const ClassificationTables tables(settings);
    RayParams params = compileRayParams(settings, tables, field.boxMin(), field.boxMax());
    Image image(settings.width, settings.height);
    keepDepth(settings, image, params);
    using S = decltype(field.sampler());
    const bool masked = FieldRaySampler<S, false>(field.sampler()).canBeOutside();
    // The Hessian's difference step of curvature renders: 1e-4 of the box diagonal (1/20 of a
    // voxel of a 256^3 grid; small against every cell, large against float rounding).
    const double step = 1e-4 * (field.boxMax() - field.boxMin()).norm();
    auto run = [&]<bool Masked, bool Shade>() {
      castRays<Masked, Shade>(
          settings, params, [&] { return FieldRaySampler<S, Shade>(field.sampler(), step); }, image,
          stats);
    };
    if (masked) {
      if (settings.needsGradients())
        run.template operator()<FieldRaySampler<S, true>::kHasInside, true>();
      else
        run.template operator()<FieldRaySampler<S, false>::kHasInside, false>();
    } else {
      if (settings.needsGradients())
        run.template operator()<false, true>();
      else
        run.template operator()<false, false>();
    }
    return image;
  }
}

}  // namespace mfadvr
