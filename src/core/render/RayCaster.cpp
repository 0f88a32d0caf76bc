#include "core/render/RayCaster.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <mutex>

#include "core/render/IsoBasis.h"

namespace mfadvr {

RayParams compileRayParams(const RenderSettings& s, const TransferFunctionTable& table,
                           const Vec3d& boxMin, const Vec3d& boxMax) {
  RayParams p;
  p.camera = s.primaryRays();
  for (int a = 0; a < 3; ++a) {
    p.boxMin[a] = s.clipBox ? std::max(boxMin[a], s.clipBox->min[a]) : boxMin[a];
    p.boxMax[a] = s.clipBox ? std::min(boxMax[a], s.clipBox->max[a]) : boxMax[a];
    if (s.crop) {
      p.boxMin[a] = std::max(p.boxMin[a], s.crop->min[a]);
      p.boxMax[a] = std::min(p.boxMax[a], s.crop->max[a]);
    }
    // A clip box beside the field leaves a box of zero width, which no ray samples.
    if (p.boxMax[a] < p.boxMin[a]) p.boxMax[a] = p.boxMin[a];
    p.background[a] = s.background[a];
  }
  p.alignSteps = s.alignSamplesToCamera;
  p.sampleDistance = s.sampleDistance;
  p.correctionExponent = s.sampleDistance / s.opacityUnitDistance;
  p.stopOpacity = static_cast<float>(s.earlyTerminationOpacity);
  p.rayEnd = s.rayEnd.empty() ? nullptr : s.rayEnd.data();
  p.tf = table.view();
  if (s.shade) p.shading = makeShadingParams(s.lighting, s.camera.directionOfProjection());
  p.shadeSamples = s.shade;
  p.blend = s.blend;
  // v' = (v - lo) / (hi - lo) over the table's span (its entries' index is (v - lo) * scale).
  p.valueLo = p.tf.lo;
  p.valueScale = p.tf.scale / static_cast<float>(p.tf.count - 1);
  if (s.averageRange) {
    p.averageLo = static_cast<float>(s.averageRange->first);
    p.averageHi = static_cast<float>(s.averageRange->second);
  }
  p.additiveScale = 1.0 / s.opacityUnitDistance;
  if (s.blend == BlendMode::Maximum) p.transparentBeyond = table.transparentUpTo();
  if (s.blend == BlendMode::Minimum) p.transparentBeyond = table.transparentFrom();
  p.isoCount = s.blend == BlendMode::Iso ? static_cast<int>(s.isoSurfaces.size()) : 0;
  for (int i = 0; i < p.isoCount; ++i) {
    const IsoSurface& iso = s.isoSurfaces[i];
    p.isoValue[i] = static_cast<float>(iso.value);
    const Vec3f c = iso.color ? *iso.color : s.transferFunction.colorAt(iso.value);
    for (int a = 0; a < 3; ++a) p.isoColor[i][a] = c[a];
    p.isoColor[i][3] = iso.opacity ? *iso.opacity : s.transferFunction.opacityAt(iso.value);
  }
  if (p.isoCount > 0) {
    const IsoBasisTables& tables = isoBasisTables();
    p.isoNodes = tables.nodes.data();
    p.isoBasis = tables.basis.data();
  }
  p.clipPlaneCount = static_cast<int>(s.clipPlanes.size());
  for (int i = 0; i < p.clipPlaneCount; ++i) {
    const ClipPlane& c = s.clipPlanes[i];
    const Vec3d n = c.normal.normalized();
    for (int a = 0; a < 3; ++a) p.clipPlane[i][a] = n[a];
    p.clipPlane[i][3] = -n.dot(c.point);
  }
  return p;
}

RayParams compileRayParams(const RenderSettings& s, const ClassificationTables& tables,
                           const Vec3d& boxMin, const Vec3d& boxMax) {
  RayParams p = compileRayParams(s, tables.table(), boxMin, boxMax);
  p.gradientTf = tables.gradientView();
  p.curvatureTf = tables.curvatureView(p.camera);
  return p;
}

void keepDepth(const RenderSettings& settings, Image& image, RayParams& params) {
  if (!settings.depth) return;
  image.depth.assign(static_cast<size_t>(image.width) * image.height,
                     std::numeric_limits<float>::quiet_NaN());
  params.depth = image.depth.data();
}

void forEachTile(const RenderSettings& s, const TileFunction& tile, RenderStats* stats) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  constexpr int kTile = 16;
  const int tilesX = (s.width + kTile - 1) / kTile, tilesY = (s.height + kTile - 1) / kTile;
  const int tiles = tilesX * tilesY;
  std::atomic<std::int64_t> samples{0}, hits{0}, terminated{0}, skipped{0};
  std::atomic<int> done{0};
  std::mutex progressMutex;
  int lastReported = 0;

  auto work = [&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const auto& range) {
      RayCounters c;
      for (int t = range.begin(); t < range.end(); ++t) {
        const int x0 = (t % tilesX) * kTile, y0 = (t / tilesX) * kTile;
        tile(x0, y0, std::min(x0 + kTile, s.width), std::min(y0 + kTile, s.height), c);
        const int finished = ++done;
        if (s.progress) {
          const int percent = static_cast<int>(100LL * finished / tiles);
          std::unique_lock lock(progressMutex, std::try_to_lock);
          if (lock && percent > lastReported) {
            lastReported = percent;
            s.progress(static_cast<double>(finished) / tiles);
          }
        }
      }
      samples += c.samples;
      hits += c.hits;
      terminated += c.terminated;
      skipped += c.skipped;
#if MFADVR_EMPTY_SPACE_PROFILE
      EmptySpaceProfile::add(c.cycles);
#endif
    });
  };
  if (s.threads > 0) {
    tbb::task_arena arena(s.threads);
    arena.execute(work);
  } else {
    work();
  }
  // The last tile's report can lose the race for the lock; the caller still gets its 1.
  if (s.progress && lastReported < 100) s.progress(1.0);
  if (stats) {
    stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
    stats->rays = std::int64_t(s.width) * s.height;
    stats->raysHit = hits;
    stats->samples = samples;
    stats->terminated = terminated;
    stats->skipped = skipped;
  }
}

}  // namespace mfadvr
