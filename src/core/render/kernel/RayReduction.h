#pragma once
// The blend modes other than composite (BlendMode.h), host and device: the ray's samples reduced
// to one value (max, min) or one level (average, additive), then made a pixel. The ray and its
// samples are the composite integration's (RaySteps.h), the sampler is the same ray sampler
// (RayIntegrator.h describes its interface), so that every method and mode sees the same
// samples. Nothing is shaded and no ray terminates early. A sampler that skips (the MFA model's)
// passes over exactly the samples that could not change the pixel: in a maximum (minimum)
// intensity render those of cells whose values cannot exceed (go below) the ray's running extreme
// nor leave the transfer function's transparent end (SplineRaySampler::boundedAt,
// ExtremeBounds.h), in an additive render those the transfer function makes transparent (the
// composite render's empty cells: they add nothing). Average renders count every value within
// their range, transparent or not, and skip nothing.
#include "core/render/kernel/ExtremeLevels.h"
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
// Masked: samples outside the sampler's mask do not count. A sampler that skips is given the
// skipping of the ray's blend (maximum, minimum: its extreme bounds; additive: its empty-space
// flags; never average).
template <bool Masked, class Sampler>
MFADVR_HD MFADVR_OUTLINE void reduceSegment(const RayParams& rp, Sampler& sampler,
                                            const RaySegment& ray, float out[4],
                                            RayCounters& counters) {
  constexpr int K = Sampler::kBatch;
  const double dt = rp.sampleDistance;
  RayReduction r;
  sampler.beginRay(ray);
  [[maybe_unused]] const bool maximum = rp.blend == BlendMode::Maximum;
  [[maybe_unused]] const bool extreme = maximum || rp.blend == BlendMode::Minimum;
  // The byte a cell's bound must pass to be skipped, from the ray's extreme or the transfer
  // function's transparent end, whichever lies further out; it only moves outwards as the ray
  // goes (a batch's values update it after the batch: later, never wrong).
  [[maybe_unused]] int bound = 0;
  [[maybe_unused]] const auto updateBound = [&] {
    if constexpr (Sampler::kSkipsEmptySpace) {
      if (!extreme) return;
      float v = rp.transparentBeyond;
      if (r.any && (maximum ? !(r.extreme <= v) : !(r.extreme >= v))) v = r.extreme;
      bound = maximum ? upperByteAtMost(sampler.upperLevels(), v)
                      : lowerByteAtLeast(sampler.lowerLevels(), v);
    }
  };
  updateBound();
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
        if (extreme ? sampler.boundedAt(p, maximum, bound, tLeave) : sampler.emptyAt(p, tLeave)) {
          const std::int64_t next = stepAfterEmpty(k, tLeave, ray.t0, dt, ray.steps);
          counters.skipped += 1 + (next - k);
          k = next;
          continue;
        }
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
    updateBound();
  }
  float depth;
  r.finish(rp, out, depth);
  if (rp.depth) rp.depth[ray.pixel] = depth;
}

}  // namespace mfadvr
