#pragma once
// The blend modes other than composite (BlendMode.h), host and device: the ray's samples reduced
// to one value (max, min) or one level (average, additive), then made a pixel. The ray and its
// samples are the composite integration's (RaySteps.h), the sampler is the same ray sampler
// (RayIntegrator.h describes its interface), so that every method and mode sees the same
// samples. Nothing is shaded, no ray terminates early, no space is skipped: every sample can
// set the extreme or add to the sum.
#include "core/render/kernel/RaySteps.h"

namespace mfadvr {

// What a ray has gathered so far.
struct RayReduction {
  float extreme = 0.0f;  // max / min: the value so far
  double extremeAt = 0.0;
  bool any = false;      // max / min: a value was seen
  double sum = 0.0;      // average: of a v' dt; additive: of a v' dt / u
  double weight = 0.0;   // average: of dt over the values in range
  double firstAt = NAN;  // average / additive: the first sample that added something

  MFADVR_HD MFADVR_INLINE void take(const RayParams& rp, float v, double length, double mid) {
    if (!(v == v)) return;  // NaN: no value
    switch (rp.blend) {
      case BlendMode::Maximum:
      case BlendMode::Minimum: {
        const bool better = rp.blend == BlendMode::Maximum ? v > extreme : v < extreme;
        if (!any || better) {
          extreme = v;
          extremeAt = mid;
          any = true;
        }
        return;
      }
      case BlendMode::Average:
      case BlendMode::Additive: {
        if (rp.blend == BlendMode::Average) {
          if (!(v >= rp.averageLo && v <= rp.averageHi)) return;
          weight += length;
        }
        const float a = rp.tf.classify(v).alpha;
        const double add = static_cast<double>(a) * ((v - rp.valueLo) * rp.valueScale) * length;
        sum += rp.blend == BlendMode::Additive ? add * rp.additiveScale : add;
        if (a > 0.0f && !(firstAt == firstAt)) firstAt = mid;
        return;
      }
      default:
        return;
    }
  }

  // The pixel's RGBA over the background, and its depth (NaN: none).
  MFADVR_HD MFADVR_INLINE void finish(const RayParams& rp, float out[4], float& depth) const {
    depth = NAN;
    if (rp.blend == BlendMode::Maximum || rp.blend == BlendMode::Minimum) {
      if (!any) return overBackground(rp, 0.0f, 0.0f, 0.0f, 0.0f, out);
      const TfEntry e = rp.tf.classify(extreme);
      if (e.alpha > 0.0f) depth = static_cast<float>(extremeAt);
      return overBackground(rp, e.alpha * e.r, e.alpha * e.g, e.alpha * e.b, e.alpha, out);
    }
    double level = sum;
    if (rp.blend == BlendMode::Average) {
      if (!(weight > 0.0)) return overBackground(rp, 0.0f, 0.0f, 0.0f, 0.0f, out);
      level = sum / weight;
    }
    const float g = static_cast<float>(level < 0.0 ? 0.0 : level > 1.0 ? 1.0 : level);
    depth = static_cast<float>(firstAt);
    overBackground(rp, g, g, g, 1.0f, out);
  }
};

// Reduces the samples of `ray` into out (RGBA) and, when the render keeps depth, rp.depth.
// Masked: samples outside the sampler's mask do not count. Samplers that skip empty space are
// asked emptyAt() only to locate each point (their stage() relies on it); nothing is skipped.
template <bool Masked, class Sampler>
MFADVR_HD MFADVR_OUTLINE void reduceSegment(const RayParams& rp, Sampler& sampler,
                                            const RaySegment& ray, float out[4],
                                            RayCounters& counters) {
  constexpr int K = Sampler::kBatch;
  const double dt = rp.sampleDistance;
  RayReduction r;
  sampler.beginRay(ray.o, ray.d);
  std::int64_t k = 0;
  bool done = false;
  while (!done && k < ray.steps) {
    double lengths[K], mids[K];
    int n = 0;
    while (n < K && k < ray.steps) {
      double p[3], length, mid;
      if (!stepSample(ray, k, dt, p, length, mid)) {
        done = true;
        break;
      }
      ++k;
      if constexpr (Masked) {
        if (!sampler.inside(p)) continue;
      }
      if constexpr (Sampler::kSkipsEmptySpace) {
        double tLeave;
        (void)sampler.emptyAt(p, tLeave);
      }
      sampler.stage(n, p);
      lengths[n] = length;
      mids[n] = mid;
      ++n;
    }
    if (n == 0) continue;
    float values[K];
    sampler.evaluate(n, values);
    counters.samples += n;
    for (int i = 0; i < n; ++i) r.take(rp, values[i], lengths[i], mids[i]);
  }
  float depth;
  r.finish(rp, out, depth);
  if (rp.depth) rp.depth[ray.pixel] = depth;
}

}  // namespace mfadvr
