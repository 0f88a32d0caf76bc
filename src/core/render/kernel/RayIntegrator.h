#pragma once
// The per-ray integration of the ray caster (paper section 3.1, Algorithm 1), one plain function
// over RayParams and a sampler, for host and device. The CPU driver (RayCaster.h) calls it per
// pixel from its tiles (integrateSegment from where a march ahead stopped, with skipping); a
// GPU driver calls it per thread.
//
// A ray from the camera through the pixel centre is clipped to the box (and to its ray end);
// the clipped segment is cut into steps of the sample distance (the last one shorter when the
// length is not a multiple) and the field is sampled at the middle of each step. With
// rp.alignSteps the steps are instead the multiples of the sample distance along the ray that
// overlap the segment, the first and last cut to it: pieces of a partitioned volume then sample
// the same points as the whole. A sample's
// opacity a from the transfer function is corrected for its step length dt as in VTK,
// a' = 1 - (1 - a)^(dt / unit distance), so the image converges as the step shrinks and a
// constant medium composites to exactly its Beer-Lambert transmittance. The value comes first;
// the gradient is asked for only for a visible sample of a shaded render (a sampler may have
// computed it with the value, when that is cheaper). Colours are
// composited front to back; a ray stops once its opacity reaches the early-termination
// threshold. The result is composited over the background.
//
// The sampler (a "ray sampler") answers, at a physical point p (double[3]):
//   void beginRay(const double o[3], const double d[3])  the ray about to be walked
//   bool inside(const double p[3])     false outside a domain mask (only called when Masked)
//   bool emptyAt(const double p[3], double& tLeave)     only when kSkipsEmptySpace: true when
//        no value the field can take around p is visible; tLeave: a ray distance up to which
//        every point of the ray is in that same empty region
// and evaluates samples in batches of up to kBatch points (SampleBatch.h):
//   void stage(int lane, const double p[3])   the lane's point (after inside / emptyAt for p)
//   void evaluate(int n, float v[])           the values at lanes 0..n-1
//   void gradient(int lane, float g[3])       the physical gradient at a lane's point
// A batch's values are independent, so the processor overlaps their evaluations; classifying,
// shading and compositing then take the lanes in ray order. A ray that terminates inside a
// batch has evaluated at most kBatch - 1 samples it does not use; the counters and the image
// are those of one sample at a time. Skipped samples are exactly those that would have been
// transparent, so the image is the same with and without skipping.
#include <type_traits>

#include "core/render/kernel/OpacityCorrectionKernel.h"
#include "core/render/kernel/RayParams.h"
#include "core/render/kernel/SampleBatch.h"

namespace mfadvr {

// The formulas of one ray step and one compositing step, written once for a ray (D = double,
// F = float) and for a packet of rays as SIMD lanes (vector types, RayPacketIntegrator.h), so
// both compute every sample operation for operation alike.

// Step k of a ray whose steps start at t0 (before tEnter for an aligned ray: its first step is
// cut to begin at tEnter) and end at tExit: returns the step's start; length: its length (the
// last one cut to tExit; not above zero: the ray has no step k).
template <class D>
MFADVR_HD MFADVR_INLINE D rayStep(D k, D t0, D tEnter, D tExit, double dt, D& length) {
  const D t = t0 + k * dt;
  const D rest = tExit - t;
  const D full = dt < rest ? dt : rest;
  if constexpr (std::is_arithmetic_v<D>) {
    if (!(t < tEnter)) {  // one ray: all steps but an aligned ray's first take this branch
      length = full;
      return t;
    }
  }
  const D room = tExit - tEnter;
  D cut = t + dt - tEnter;
  cut = cut > room ? room : cut;
  const auto first = t < tEnter;
  length = first ? cut : full;
  return first ? tEnter : t;
}

// Front-to-back compositing of a sample of colour c and step opacity a (zero: no change), with
// explicit multiply-adds: a ray and a lane round alike whatever the compiler would fuse.
template <class F>
MFADVR_HD MFADVR_INLINE void compositeSample(F& red, F& green, F& blue, F& alpha, F a,
                                             const F c[3]) {
  const F w = (1.0f - alpha) * a;
  red = fusedMultiplyAdd(w, c[0], red);
  green = fusedMultiplyAdd(w, c[1], green);
  blue = fusedMultiplyAdd(w, c[2], blue);
  alpha += w;
}

// The part of the ray through pixel (x, y) that is sampled: origin o, unit direction d, the
// segment [tEnter, tExit] inside the box (and before the pixel's ray end), where step 0 starts
// (t0) and the number of steps. False when the ray does not cross the box.
struct RaySegment {
  double o[3], d[3];
  double tEnter = 0.0, tExit = 0.0, t0 = 0.0;
  std::int64_t steps = 0;
};

MFADVR_HD MFADVR_INLINE bool raySegment(const RayParams& rp, int x, int y, RaySegment& r) {
  primaryRay(rp.camera, x, y, r.o, r.d);
  double tEnter, tExit;
  const bool crosses = intersectBox(r.o, r.d, rp.boxMin, rp.boxMax, tEnter, tExit);
  if (crosses && rp.rayEnd) {
    const double end = rp.rayEnd[static_cast<std::int64_t>(y) * rp.camera.width + x];
    if (end < tExit) tExit = end;
  }
  if (!(crosses && tExit > (tEnter > 0.0 ? tEnter : 0.0))) return false;
  if (tEnter < 0.0) tEnter = 0.0;
  const double dt = rp.sampleDistance;
  r.tEnter = tEnter;
  r.tExit = tExit;
  // Where step 0 starts (before tEnter when aligned: that step is cut to begin at tEnter).
  r.t0 = rp.alignSteps ? floor(tEnter / dt) * dt : tEnter;
  // The tolerance keeps a rounding error from adding a step of zero length.
  r.steps = static_cast<std::int64_t>(ceil((tExit - r.t0) / dt - 1e-6));
  return true;
}

// The composited colour over the background: the pixel's RGBA.
MFADVR_HD MFADVR_INLINE void overBackground(const RayParams& rp, float red, float green, float blue,
                                            float alpha, float out[4]) {
  const float behind = 1.0f - alpha;
  out[0] = red + behind * rp.background[0];
  out[1] = green + behind * rp.background[1];
  out[2] = blue + behind * rp.background[2];
  out[3] = alpha;
}

// The sample of step k of `ray`: the step's midpoint p and its length. False when the ray has
// no step k (its length would not be above zero). Samplers clamp their own lookups, so a sample
// a rounding error outside the box is fine.
MFADVR_HD MFADVR_INLINE bool stepSample(const RaySegment& ray, std::int64_t k, double dt,
                                        double p[3], double& length) {
  const double t = rayStep(static_cast<double>(k), ray.t0, ray.tEnter, ray.tExit, dt, length);
  if (!(length > 0.0)) return false;
  const double m = t + 0.5 * length;
  for (int a = 0; a < 3; ++a) p[a] = ray.o[a] + m * ray.d[a];
  return true;
}

// The ray's sample k - 1 lay in an empty region that the ray leaves at tLeave (the sampler's
// emptyAt): samples j >= k with midpoints t0 + (j + 1/2) dt <= tLeave lie in it too. Returns
// the first step after the last of them (steps: none left).
MFADVR_HD MFADVR_INLINE std::int64_t stepAfterEmpty(std::int64_t k, double tLeave, double t0,
                                                    double dt, std::int64_t steps) {
  const double last = floor((tLeave - t0) / dt - 0.5);
  if (!(last >= static_cast<double>(k))) return k;
  return last < static_cast<double>(steps - 1) ? static_cast<std::int64_t>(last) + 1 : steps;
}

// Where the walk of a ray's steps begins: at step k, `skipped` samples already passed over as
// empty (by a march that went ahead of the integration, InterleavedMarch.h); RayStart{}: the
// whole ray. tail: samples after the ray's last step (its steps cut short, DepthBoundsView.h),
// all empty: counted as skipped unless the ray terminates first.
struct RayStart {
  std::int64_t k = 0;
  std::int64_t skipped = 0;
  std::int64_t tail = 0;
};

// Integrates the segment (raySegment; null: the ray misses the box) from `start` into out.
template <bool Masked, bool Shade, class Sampler>
MFADVR_HD MFADVR_INLINE void integrateSegment(const RayParams& rp, Sampler& sampler,
                                              const RaySegment* segment, RayStart start,
                                              float out[4], RayCounters& counters) {
  float red = 0.0f, green = 0.0f, blue = 0.0f, alpha = 0.0f;
  if (segment) {
    const RaySegment& ray = *segment;
    ++counters.hits;
    const double* o = ray.o;
    const double* d = ray.d;
    const double t0 = ray.t0;
    const std::int64_t steps = ray.steps;
    const double dt = rp.sampleDistance;
    // A ray with nothing left to sample (the depth bounds or the march ahead took it to its end)
    // only adds its counts below: its shading and sampler set-up are skipped (their divisions
    // made a sparse frame about 3 % slower, docs/benchmarks.md).
    const bool samples = start.k < steps;
    RayShading rayShading;
    if constexpr (Shade) {
      const float df[3] = {float(d[0]), float(d[1]), float(d[2])};
      if (samples) prepareRayShading(rp.shading, df, rayShading);
    }
#if MFADVR_EMPTY_SPACE_PROFILE
    const std::int64_t rayStart = cycleCount();
#endif
    if (samples) sampler.beginRay(o, d);
    constexpr int K = Sampler::kBatch;
    std::int64_t k = start.k;
    std::int64_t carried = start.skipped;  // passed over before step k
    bool done = false, terminated = false;
    while (!done && k < steps) {
      double lengths[K];
      // Samples skipped before each lane, counted as the lanes are used (and those after the
      // last lane unless the ray stops first), so that the counters do not depend on the batch
      // size.
      std::int64_t skippedBefore[K];
      std::int64_t skipped = carried;
      carried = 0;
      int n = 0;
#if MFADVR_EMPTY_SPACE_PROFILE
      const std::int64_t marchStart = cycleCount();
#endif
      while (n < K && k < steps) {
        double length, p[3];
        if (!stepSample(ray, k, dt, p, length)) {
          done = true;
          break;
        }
        ++k;
        if constexpr (Masked) {
          if (!sampler.inside(p)) continue;
        }
        if constexpr (Sampler::kSkipsEmptySpace) {
          double tLeave;
#if MFADVR_EMPTY_SPACE_PROFILE
          ++counters.cycles.checks;
#endif
          if (sampler.emptyAt(p, tLeave)) {
            const std::int64_t next = stepAfterEmpty(k, tLeave, t0, dt, steps);
            skipped += 1 + (next - k);
            k = next;
#if MFADVR_EMPTY_SPACE_PROFILE
            ++counters.cycles.jumps;
#endif
            continue;
          }
        }
        sampler.stage(n, p);
        lengths[n] = length;
        skippedBefore[n] = skipped;
        skipped = 0;
        ++n;
      }
      float values[K];
#if MFADVR_EMPTY_SPACE_PROFILE
      const std::int64_t evaluateStart = cycleCount();
      counters.cycles.marching += evaluateStart - marchStart;
      if (n > 0) sampler.evaluate(n, values);
      const std::int64_t evaluateCycles = cycleCount() - evaluateStart;
      int transparent = 0;  // counted as the samples are classified below
#else
      if (n > 0) sampler.evaluate(n, values);
#endif
      bool stopped = false;
      for (int i = 0; i < n && !stopped; ++i) {
        counters.skipped += skippedBefore[i];
        ++counters.samples;
        const TfEntry tf = rp.tf.classify(values[i]);
        if (!(tf.alpha > 0.0f)) {
#if MFADVR_EMPTY_SPACE_PROFILE
          ++transparent;
#endif
          continue;
        }
        const double length = lengths[i];
        const float a = length == dt
                            ? tf.alphaStep
                            : correctOpacity(tf.alpha, rp.correctionExponent * length / dt);
        float c[3] = {tf.r, tf.g, tf.b};
        if constexpr (Shade) {
          const float unshaded[3] = {tf.r, tf.g, tf.b};
          float g[3];
          sampler.gradient(i, g);
          shadeSample(rp.shading, rayShading, unshaded, g, c);
        }
        compositeSample(red, green, blue, alpha, a, c);
        if (alpha >= rp.stopOpacity) {
          ++counters.terminated;
          stopped = done = terminated = true;
        }
      }
      if (!stopped) counters.skipped += skipped;
#if MFADVR_EMPTY_SPACE_PROFILE
      if (n > 0) counters.cycles.transparent += evaluateCycles * transparent / n;
#endif
    }
    counters.skipped += carried;  // a ray that the march ahead took to its end
    if (!terminated) counters.skipped += start.tail;
#if MFADVR_EMPTY_SPACE_PROFILE
    counters.cycles.ray += cycleCount() - rayStart;
#endif
  }
  overBackground(rp, red, green, blue, alpha, out);
}

template <bool Masked, bool Shade, class Sampler>
MFADVR_HD MFADVR_INLINE void integrateRay(const RayParams& rp, Sampler& sampler, int x, int y,
                                          float out[4], RayCounters& counters) {
  RaySegment ray;
  const bool hits = raySegment(rp, x, y, ray);
  integrateSegment<Masked, Shade>(rp, sampler, hits ? &ray : nullptr, RayStart{}, out, counters);
}

}  // namespace mfadvr
