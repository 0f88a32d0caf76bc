#pragma once
// The per-ray integration for eight rays at once, one SIMD lane per ray (host only): a packet
// is eight neighbouring pixels of a row. Each ray is sampled, classified, shaded and composited
// exactly as integrateRay (RayIntegrator.h) does it alone, with the same formulas (rayStep,
// compositeSample, the transfer-function view, shadeSample), so every pixel is bit for bit the
// same whichever path computed it (RayPacketTest).
//
// Why: along one ray, the batch of samples can be evaluated together, but each sample's step,
// classification and compositing wait on the previous one, and a sample's point, span lookup
// and step are scalar work. Across rays nothing depends on anything: the eight rays' points,
// spans and local coordinates are computed as vectors, the spline kernel takes one point per
// lane (SplineLaneKernel.h), and the eight compositing chains run side by side. A lane whose ray
// has ended (left the box, or reached the early-termination opacity) idles until the packet's
// last ray ends; neighbouring rays have similar lengths (docs/benchmarks.md: lane use).
//
// The sampler provides, besides the batch interface of RayIntegrator.h:
//   static constexpr bool kRayPackets          true
//   void evaluatePacket(const LaneDouble8 x[3], float v[8])   values at the eight points
//   void gradient(int lane, float g[3])        physical gradient of a lane (shaded renders)
// Packets cover renders without a domain mask or empty-space skipping; those take one ray at a
// time.
#include <cstdint>

#include "core/render/kernel/RayIntegrator.h"
#include "core/spline/SplineLaneKernel.h"

namespace mfadvr {

inline constexpr int kRayPacket = 8;

// Whether Sampler takes packets of rays on this build.
template <class Sampler>
constexpr bool takesRayPackets() {
  if constexpr (requires { Sampler::kRayPackets; })
    return Sampler::kRayPackets;
  else
    return false;
}

#if defined(MFADVR_SPLINE_LANE_KERNEL)

// The rays of pixels (x0 + lane, y), lane = 0..7; out[lane] receives the pixel's RGBA.
template <bool Shade, class Sampler>
MFADVR_INLINE void integratePacket(const RayParams& rp, Sampler& sampler, int x0, int y,
                                   float out[kRayPacket][4], RayCounters& counters) {
  constexpr int K = kRayPacket;
  const double dt = rp.sampleDistance;
  LaneDouble8 o[3], d[3], tEnter, tExit, t0;
  std::int64_t steps[K];
  std::int64_t longest = 0;
  RayShading rayShading[Shade ? K : 1];
  unsigned live = 0;  // bit per lane: the ray has steps left
  for (int l = 0; l < K; ++l) {
    RaySegment ray;
    const bool hit = raySegment(rp, x0 + l, y, ray);
    for (int a = 0; a < 3; ++a) {
      o[a][l] = ray.o[a];
      d[a][l] = ray.d[a];
    }
    tEnter[l] = ray.tEnter;
    tExit[l] = ray.tExit;
    t0[l] = ray.t0;
    steps[l] = ray.steps;
    if (!hit) continue;
    ++counters.hits;
    if (ray.steps > 0) live |= 1u << l;
    if (ray.steps > longest) longest = ray.steps;
    if constexpr (Shade) {
      const float df[3] = {float(ray.d[0]), float(ray.d[1]), float(ray.d[2])};
      prepareRayShading(rp.shading, df, rayShading[l]);
    }
  }

  LaneVector8 red = {}, green = {}, blue = {}, alpha = {};
  std::int64_t samples = 0;
  for (std::int64_t k = 0; k < longest && live; ++k) {
    for (int l = 0; l < K; ++l)
      if (k >= steps[l]) live &= ~(1u << l);
    LaneDouble8 length;
    const LaneDouble8 kv = LaneDouble8{} + static_cast<double>(k);
    const LaneDouble8 t = rayStep(kv, t0, tEnter, tExit, dt, length);
    for (int l = 0; l < K; ++l)
      if (!(length[l] > 0.0)) live &= ~(1u << l);
    if (!live) break;
    const LaneDouble8 m = t + 0.5 * length;
    LaneDouble8 x[3];
    for (int a = 0; a < 3; ++a) x[a] = o[a] + m * d[a];
    float values[K];
    sampler.evaluatePacket(x, values);

    // Classification (and shading) per lane; lanes without a visible sample composite a zero
    // opacity, which leaves them unchanged.
    float opacity[K] = {}, colour[3][K] = {};
    for (int l = 0; l < K; ++l) {
      if (!(live >> l & 1u)) continue;
      ++samples;
      const TfEntry tf = rp.tf.classify(values[l]);
      float a = tf.alphaStep;
      if (length[l] != dt) [[unlikely]]
        a = correctOpacity(tf.alpha, rp.correctionExponent * length[l] / dt);
      float c[3] = {tf.r, tf.g, tf.b};
      if constexpr (Shade) {
        if (tf.alpha > 0.0f) {
          const float unshaded[3] = {tf.r, tf.g, tf.b};
          float g[3];
          sampler.gradient(l, g);
          shadeSample(rp.shading, rayShading[l], unshaded, g, c);
        }
      }
      opacity[l] = tf.alpha > 0.0f ? a : 0.0f;
      for (int i = 0; i < 3; ++i) colour[i][l] = c[i];
    }
    LaneVector8 a, c[3];
    __builtin_memcpy(&a, opacity, sizeof a);
    for (int i = 0; i < 3; ++i) __builtin_memcpy(&c[i], colour[i], sizeof c[i]);
    compositeSample(red, green, blue, alpha, a, c);
    const auto stop = (alpha >= rp.stopOpacity) & (a > 0.0f);
    for (int l = 0; l < K; ++l)
      if ((live >> l & 1u) && stop[l]) {
        ++counters.terminated;
        live &= ~(1u << l);
      }
  }
  counters.samples += samples;
  for (int l = 0; l < K; ++l) overBackground(rp, red[l], green[l], blue[l], alpha[l], out[l]);
}

#endif  // MFADVR_SPLINE_LANE_KERNEL

}  // namespace mfadvr
