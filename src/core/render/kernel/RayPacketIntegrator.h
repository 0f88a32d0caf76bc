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
//   LaneVector8 evaluatePacket(const LaneDouble8 x[3])   values at the eight points
//   void gradientPacket(LaneVector8 g[3])   their physical gradients (shaded renders)
// and for masked renders (Masked)
//   bool beginPacket(const RaySegment rays[8], LaneInt8 live)   false: go one ray at a time
//   LaneInt8 insidePacket(const LaneDouble8 x[3], LaneInt8& live)   inside() of each lane
//   LaneDouble8 firstInsidePacket()   where each live lane may first be inside
// A masked packet evaluates its lanes where any is inside; the others' values go unused, as
// integrateRay never evaluates them. Renders with empty-space skipping take one ray at a time.
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

// classify() of eight values: entries {r, g, b, alpha, alphaStep} as vectors over the lanes.
MFADVR_INLINE void classifyPacket(const TransferFunctionView& tf, LaneVector8 value,
                                  LaneVector8 channel[5]) {
  LaneInt8 i;
  LaneVector8 t;
  tf.position(value, i, t);
  LaneVector8 e[8];  // each lane's interpolated entry
  for (int l = 0; l < 8; ++l) {
    LaneVector8 a, b;
    __builtin_memcpy(&a, &tf.entries[i[l]], sizeof a);
    __builtin_memcpy(&b, &tf.entries[i[l] + 1], sizeof b);
    e[l] = interpolate(a, b, t[l]);
  }
  // Transpose lanes of entries into channels of lanes: pairs of lanes, then quadruples. w[c]
  // ends with channel c of lanes 0..3 in its low half and channel c + 4 in its high half,
  // w[4 + c] the same for lanes 4..7.
  LaneVector8 u[8], w[8];
  for (int l = 0; l < 8; l += 2) {
    u[l] = __builtin_shufflevector(e[l], e[l + 1], 0, 8, 1, 9, 4, 12, 5, 13);
    u[l + 1] = __builtin_shufflevector(e[l], e[l + 1], 2, 10, 3, 11, 6, 14, 7, 15);
  }
  for (int l = 0; l < 8; l += 4)
    for (int h = 0; h < 2; ++h) {
      w[l + 2 * h] = __builtin_shufflevector(u[l + h], u[l + h + 2], 0, 1, 8, 9, 4, 5, 12, 13);
      w[l + 2 * h + 1] =
          __builtin_shufflevector(u[l + h], u[l + h + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    }
  for (int c = 0; c < 4; ++c)
    channel[c] = __builtin_shufflevector(w[c], w[4 + c], 0, 1, 2, 3, 8, 9, 10, 11);
  channel[4] = __builtin_shufflevector(w[0], w[4], 4, 5, 6, 7, 12, 13, 14, 15);
  for (int c = 0; c < 5; ++c) channel[c] = value == value ? channel[c] : 0.0f;  // NaN: clear
}

// The rays of pixels (x0 + lane, y), lane = 0..7; out[lane] receives the pixel's RGBA. False
// (nothing rendered or counted) where a masked sampler cannot take the packet.
template <bool Masked, bool Shade, class Sampler>
MFADVR_INLINE bool integratePacket(const RayParams& rp, Sampler& sampler, int x0, int y,
                                   float out[kRayPacket][4], RayCounters& counters) {
  constexpr int K = kRayPacket;
  const double dt = rp.sampleDistance;
  // Zeroed although every lane is set below: GCC 12 otherwise warns that they may be read
  // uninitialized (it does not follow the lanes' stores through the loop).
  LaneDouble8 o[3] = {}, d[3] = {}, tEnter = {}, tExit = {}, t0 = {}, steps = {};
  std::int64_t longest = 0;
  RayShadingOf<LaneVector8> shading = {};  // lane l: ray l's RayShading
  LaneInt8 live = {};                      // -1 in the lanes whose ray has steps left
  RaySegment rays[K];
  bool hits[K];
  for (int l = 0; l < K; ++l) {
    hits[l] = raySegment(rp, x0 + l, y, rays[l]);
    if (hits[l] && rays[l].steps > 0) live[l] = -1;
  }
  if constexpr (Masked) {
    if (!sampler.beginPacket(rays, live)) return false;
  }
  for (int l = 0; l < K; ++l) {
    const RaySegment& ray = rays[l];
    const bool hit = hits[l];
    for (int a = 0; a < 3; ++a) {
      o[a][l] = ray.o[a];
      d[a][l] = ray.d[a];
    }
    tEnter[l] = ray.tEnter;
    tExit[l] = ray.tExit;
    t0[l] = ray.t0;
    steps[l] = static_cast<double>(ray.steps);  // exact: far below 2^53 steps
    if (!hit) continue;
    ++counters.hits;
    if (ray.steps > longest) longest = ray.steps;
    if constexpr (Shade) {
      const float df[3] = {float(ray.d[0]), float(ray.d[1]), float(ray.d[2])};
      RayShading one;
      prepareRayShading(rp.shading, df, one);
      for (int c = 0; c < 3; ++c) {
        shading.toEye[c][l] = one.toEye[c];
        for (int i = 0; i < rp.shading.lightCount; ++i) shading.half[i][c][l] = one.half[i][c];
      }
    }
  }

  LaneVector8 red = {}, green = {}, blue = {}, alpha = {};
  std::int64_t samples = 0;
  std::int64_t first = 0;
  if constexpr (Masked) {
    // The steps before every lane's first stretch inside take no sample: the packet starts at
    // the first step that may (two steps early, far beyond any rounding of a point's distance).
    const LaneDouble8 enter = sampler.firstInsidePacket();
    double k = INFINITY;
    for (int l = 0; l < K; ++l) {
      const double kl = __builtin_floor((enter[l] - t0[l]) / dt) - 2.0;
      k = kl < k ? kl : k;
    }
    first = !(k > 0.0)                         ? 0
            : k < static_cast<double>(longest) ? static_cast<std::int64_t>(k)
                                               : longest;
  }
  for (std::int64_t k = first; k < longest; ++k) {
    LaneDouble8 length;
    const LaneDouble8 kv = LaneDouble8{} + static_cast<double>(k);
    const LaneDouble8 t = rayStep(kv, t0, tEnter, tExit, dt, length);
    // A ray ends after its steps, or where a step would have no length (it left the box).
    live &= __builtin_convertvector((kv < steps) & (length > 0.0), LaneInt8);
    if (!anyLane(live)) break;
    const LaneDouble8 m = t + 0.5 * length;
    LaneDouble8 x[3];
    for (int a = 0; a < 3; ++a) x[a] = o[a] + m * d[a];
    // The lanes that take a sample: the live ones, those inside where Masked.
    LaneInt8 in = live;
    if constexpr (Masked) {
      in = sampler.insidePacket(x, live);
      if (!anyLane(in)) continue;
    }
    const LaneVector8 values = sampler.evaluatePacket(x);
    samples += countLanes(in);

    // Classification (and shading); lanes without a visible sample composite a zero opacity,
    // which leaves them unchanged.
    LaneVector8 tf[5];
    classifyPacket(rp.tf, values, tf);
    LaneVector8 a = tf[4];
    const LaneInt8 shortStep = in & __builtin_convertvector(length != dt, LaneInt8);
    if (anyLane(shortStep)) [[unlikely]]
      for (int l = 0; l < K; ++l)
        if (shortStep[l]) a[l] = correctOpacity(tf[3][l], rp.correctionExponent * length[l] / dt);
    const LaneInt8 visible = in & (tf[3] > 0.0f);
    a = visible ? a : 0.0f;
    LaneVector8 c[3] = {tf[0], tf[1], tf[2]};
    if constexpr (Shade) {
      LaneVector8 g[3], shaded[3];
      sampler.gradientPacket(g);
      shadeSample(rp.shading, shading, c, g, shaded);
      for (int i = 0; i < 3; ++i) c[i] = visible ? shaded[i] : c[i];
    }
    compositeSample(red, green, blue, alpha, a, c);
    const LaneInt8 stop = visible & (alpha >= rp.stopOpacity);
    counters.terminated += countLanes(stop);
    live &= ~stop;
  }
  counters.samples += samples;
  for (int l = 0; l < K; ++l) overBackground(rp, red[l], green[l], blue[l], alpha[l], out[l]);
  return true;
}

#endif  // MFADVR_SPLINE_LANE_KERNEL

}  // namespace mfadvr
