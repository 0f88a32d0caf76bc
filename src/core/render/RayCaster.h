#pragma once
// The ray caster (paper section 3.1, Algorithm 1), generic over the Field so that every
// reconstruction method is rendered with exactly the same rays, samples, transfer function,
// shading and compositing.
//
// Per pixel: a ray from the camera through the pixel centre is clipped to the field's box; the
// clipped segment is cut into steps of the sample distance (the last step is shorter when the
// length is not a multiple) and the field is sampled at the middle of each step. A sample's
// opacity a from the transfer function is corrected for its step length dt as in VTK,
// a' = 1 - (1 - a)^(dt / unit distance), so the image converges as the step shrinks and a
// constant medium composites to exactly its Beer-Lambert transmittance. Colours (shaded with the
// field's gradient when shading is on) are composited front to back; a ray stops once its
// opacity reaches the early-termination threshold. The result is composited over the background.
//
// A field whose sampler has `bool inside(x)` (a model with a domain mask) is empty where it
// answers false: such samples are neither evaluated nor composited, as if their opacity were 0.
// Rays may end early, per pixel (RenderSettings::rayEnd): opaque geometry in a VTK scene.
//
// The ray loop is instantiated twice, with and without that test, and a sampler with
// `bool masked()` answering false (a model without a mask) gets the loop without it.
//
// Pixels are computed independently in square tiles spread over the threads, so the image is
// bit-identical for any thread count.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>

#include "core/field/Field.h"
#include "core/image/Image.h"
#include "core/render/OpacityCorrection.h"
#include "core/render/RenderSettings.h"
#include "core/render/TransferFunctionTable.h"

namespace mfadvr {

// Entry and exit distances of the ray o + t d (d unit) through the box [lo, hi]; false if it
// misses. Entry may be negative when the origin is inside the box.
inline bool intersectBox(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi,
                         double& tEnter, double& tExit) {
  tEnter = -INFINITY;
  tExit = INFINITY;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    const double inv = 1.0 / d[a];
    double t0 = (lo[a] - o[a]) * inv, t1 = (hi[a] - o[a]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    tEnter = std::max(tEnter, t0);
    tExit = std::min(tExit, t1);
  }
  return tEnter <= tExit;
}

template <Field F>
class RayCaster {
 public:
  RayCaster(const F& field, const RenderSettings& settings)
      : field_(field),
        s_(settings),
        rays_((settings.validate(), settings.camera), settings.width, settings.height),
        correction_(settings.sampleDistance / settings.opacityUnitDistance),
        table_(settings.transferFunction, correction_) {}

  Image render(RenderStats* stats = nullptr) const {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    Image image(s_.width, s_.height);
    constexpr int kTile = 16;
    const int tilesX = (s_.width + kTile - 1) / kTile, tilesY = (s_.height + kTile - 1) / kTile;
    const int tiles = tilesX * tilesY;
    std::atomic<std::int64_t> samples{0}, hits{0}, terminated{0};
    std::atomic<int> done{0};
    std::mutex progressMutex;
    int lastReported = 0;

    auto work = [&] {
      tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const auto& range) {
        auto sampler = field_.sampler();
        std::optional<Shader> shader;
        if (s_.shade) shader.emplace(s_.lighting, s_.camera.directionOfProjection());
        RayCounters c;
        // Fields without a mask get the ray loop without the inside() test.
        const bool masked = canBeOutside(sampler);
        for (int tile = range.begin(); tile < range.end(); ++tile) {
          const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
          const int x1 = std::min(x0 + kTile, s_.width), y1 = std::min(y0 + kTile, s_.height);
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
              Shader* sh = shader ? &*shader : nullptr;
              if (masked)
                castRay<kHasInside<decltype(sampler)>>(x, y, sampler, sh, image.pixel(x, y), c);
              else
                castRay<false>(x, y, sampler, sh, image.pixel(x, y), c);
            }
          const int finished = ++done;
          if (s_.progress) {
            const int percent = static_cast<int>(100LL * finished / tiles);
            std::unique_lock lock(progressMutex, std::try_to_lock);
            if (lock && percent > lastReported) {
              lastReported = percent;
              s_.progress(static_cast<double>(finished) / tiles);
            }
          }
        }
        samples += c.samples;
        hits += c.hits;
        terminated += c.terminated;
      });
    };
    if (s_.threads > 0) {
      tbb::task_arena arena(s_.threads);
      arena.execute(work);
    } else {
      work();
    }
    // The last tile's report can lose the race for the lock; the caller still gets its 1.
    if (s_.progress && lastReported < 100) s_.progress(1.0);
    if (stats) {
      stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
      stats->rays = std::int64_t(s_.width) * s_.height;
      stats->raysHit = hits;
      stats->samples = samples;
      stats->terminated = terminated;
    }
    return image;
  }

 private:
  struct RayCounters {
    std::int64_t samples = 0, hits = 0, terminated = 0;
  };

  template <class Sampler>
  static constexpr bool kHasInside = requires(Sampler& s, const Vec3d& x) {
    { s.inside(x) } -> std::convertible_to<bool>;
  };

  // Whether the sampler can answer inside(x) == false: samplers without inside() cannot; those
  // with masked() say whether they can (a model without a mask cannot); others may.
  template <class Sampler>
  static bool canBeOutside(const Sampler& sampler) {
    if constexpr (!kHasInside<Sampler>)
      return false;
    else if constexpr (requires { sampler.masked(); })
      return sampler.masked();
    else
      return true;
  }

  // shader is null when shading is off. Masked: skip samples where sampler.inside(p) is false.
  template <bool Masked, class Sampler>
  void castRay(int x, int y, Sampler& sampler, Shader* shader, float* out,
               RayCounters& counters) const {
    Vec3d o, d;
    rays_.ray(x, y, o, d);
    // Plain floats: Eigen's small-vector expressions were not inlined into this loop.
    float red = 0.0f, green = 0.0f, blue = 0.0f, alpha = 0.0f;
    double tEnter, tExit;
    const Vec3d lo = field_.boxMin(), hi = field_.boxMax();
    const bool crosses = intersectBox(o, d, lo, hi, tEnter, tExit);
    if (crosses && !s_.rayEnd.empty())
      tExit = std::min(tExit, static_cast<double>(s_.rayEnd[std::size_t(y) * s_.width + x]));
    if (crosses && tExit > std::max(tEnter, 0.0)) {
      ++counters.hits;
      tEnter = std::max(tEnter, 0.0);
      const double dt = s_.sampleDistance;
      // The tolerance keeps a rounding error from adding a step of zero length.
      const std::int64_t steps = static_cast<std::int64_t>(std::ceil((tExit - tEnter) / dt - 1e-6));
      if (shader) shader->setView(d.cast<float>());
      const float stop = static_cast<float>(s_.earlyTerminationOpacity);
      for (std::int64_t k = 0; k < steps; ++k) {
        const double t = tEnter + static_cast<double>(k) * dt;
        const double length = std::min(dt, tExit - t);
        if (!(length > 0.0)) break;
        // Fields clamp their own lookups, so a sample a rounding error outside the box is fine.
        const Vec3d p = o + (t + 0.5 * length) * d;
        if constexpr (Masked) {
          if (!sampler.inside(p)) continue;
        }
        ++counters.samples;
        ValueGradient vg;
        if (s_.shade)
          vg = sampler.valueGradient(p);
        else
          vg.value = sampler.value(p);
        const Classification tf = table_.classify(vg.value);
        if (!(tf.alpha > 0.0f)) continue;
        const float corrected =
            length == dt ? tf.alphaStep : correction_.partial(tf.alpha, length / dt);
        Vec3f c = tf.rgb;
        if (shader) c = shader->shade(c, vg.gradient);
        const float w = (1.0f - alpha) * corrected;
        red += w * c[0];
        green += w * c[1];
        blue += w * c[2];
        alpha += w;
        if (alpha >= stop) {
          ++counters.terminated;
          break;
        }
      }
    }
    const float behind = 1.0f - alpha;
    out[0] = red + behind * s_.background[0];
    out[1] = green + behind * s_.background[1];
    out[2] = blue + behind * s_.background[2];
    out[3] = alpha;
  }

  const F& field_;
  const RenderSettings& s_;
  RayGenerator rays_;
  OpacityCorrection correction_;
  TransferFunctionTable table_;
};

// Renders `field` with `settings`; stats (optional) receive the timing and counts.
template <Field F>
Image renderVolume(const F& field, const RenderSettings& settings, RenderStats* stats = nullptr) {
  return RayCaster<F>(field, settings).render(stats);
}

}  // namespace mfadvr
