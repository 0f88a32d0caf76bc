#pragma once
// The per-ray integration of the ray caster (paper section 3.1, Algorithm 1), one plain function
// over RayParams and a sampler, for host and device. The CPU driver (RayCaster.h) calls it per
// pixel from its tiles (integrateSegment from where a march ahead stopped, with skipping); a
// GPU driver calls it per thread.
//
// A ray from the camera through the pixel centre is clipped to the box, to the clipping planes
// and to its ray end (RaySteps.h);
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
//   void beginRay(const RaySegment& ray)  the ray about to be walked (its pixel, origin, direction)
//   bool inside(const double p[3])     false outside a domain mask (only called when Masked)
//   bool emptyAt(const double p[3], double& tLeave)     only when kSkipsEmptySpace: true when
//        no value the field can take around p is visible; tLeave: a ray distance up to which
//        every point of the ray is in that same empty region
// and evaluates samples in batches of up to kBatch points (SampleBatch.h):
//   void stage(int lane, const double p[3])   the lane's point (after inside / emptyAt for p)
//   void evaluate(int n, float v[])           the values at lanes 0..n-1
//   void gradient(int lane, float g[3])       the physical gradient at a lane's point
//   void hessian(int lane, const double p[3], float h[6])   the physical Hessian (xx, xy, xz,
//        yy, yz, zz) at the lane's point p (curvature classification only)
// A batch's values are independent, so the processor overlaps their evaluations; classifying,
// shading and compositing then take the lanes in ray order. A ray that terminates inside a
// batch has evaluated at most kBatch - 1 samples it does not use; the counters and the image
// are those of one sample at a time. Skipped samples are exactly those that would have been
// transparent, so the image is the same with and without skipping.
//
// With rp.gradientTf active (a loop with gradients, Shade = true), a visible sample is
// classified again from its gradient (GradientTransferView.h): gradient opacity, 2-D transfer
// functions; by the curvature of its level set (CurvatureTransferView.h): curvature transfer
// functions and contours; rp.shadeSamples then says whether its colour is also shaded.
//
// This is the composite blend; the other blend modes reduce the same samples (RayReduction.h)
// or walk the ray for isosurfaces (IsoSurfaceWalk.h), chosen per ray from rp.blend. With rp.depth,
// each ray records where its opacity first reaches 0.5 (the midpoint of that sample's step).
// A driver may compile the composite blend and the others as separate kernels (RayBlends): on a
// GPU one kernel for all of them carries the isosurface walk's registers and stack into every
// composite ray (measured 1.3-1.5x slower, docs/benchmarks.md).
#include "core/render/kernel/IsoSurfaceWalk.h"
#include "core/render/kernel/RayReduction.h"
#include "core/render/kernel/RaySteps.h"
#include "core/render/kernel/SampleBatch.h"

namespace mfadvr {

// Whether the blends other than composite and iso skip (RayReduction.h): on the host; the
// device's kernels sample every step of them.
#if defined(__CUDA_ARCH__)
inline constexpr bool kReducesWithSkipping = false;
#else
inline constexpr bool kReducesWithSkipping = true;
#endif

// The composite blend of the segment (null: the ray misses the box) from `start` into out.
template <bool Masked, bool Shade, class Sampler>
MFADVR_HD MFADVR_INLINE void compositeSegment(const RayParams& rp, Sampler& sampler,
                                              const RaySegment* segment, RayStart start,
                                              float out[4], RayCounters& counters) {
  float red = 0.0f, green = 0.0f, blue = 0.0f, alpha = 0.0f;
  float depth = NAN;  // where alpha first reaches 0.5 (rp.depth)
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
      if (samples && rp.shadeSamples) prepareRayShading(rp.shading, df, rayShading);
    }
#if MFADVR_EMPTY_SPACE_PROFILE
    const std::int64_t rayStart = cycleCount();
#endif
    if (samples) sampler.beginRay(ray);
    constexpr int K = Sampler::kBatch;
    std::int64_t k = start.k;
    std::int64_t carried = start.skipped;  // passed over before step k
    bool done = false, terminated = false;
    while (!done && k < steps) {
      // Zeroed although only lanes < n are read: GCC 12 otherwise warns that they may be read
      // uninitialized (it cannot follow n through the loops); the stores cost nothing measurable.
      double lengths[K] = {}, mids[K] = {};
      // Samples skipped before each lane, counted as the lanes are used (and those after the
      // last lane unless the ray stops first), so that the counters do not depend on the batch
      // size.
      std::int64_t skippedBefore[K] = {};
      std::int64_t skipped = carried;
      carried = 0;
      int n = 0;
#if MFADVR_EMPTY_SPACE_PROFILE
      const std::int64_t marchStart = cycleCount();
#endif
      while (n < K && k < steps) {
        double length, mid, p[3];
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
        mids[n] = mid;
        skippedBefore[n] = skipped;
        skipped = 0;
        ++n;
      }
      float values[K] = {};
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
        TfEntry tf = rp.tf.classify(values[i]);
        if (!(tf.alpha > 0.0f)) {
#if MFADVR_EMPTY_SPACE_PROFILE
          ++transparent;
#endif
          continue;
        }
        float factor = 1.0f;  // the gradient opacity
        float c[3] = {tf.r, tf.g, tf.b};
        if constexpr (Shade) {
          if (rp.gradientTf.active() || rp.curvatureTf.active() || rp.shadeSamples) {
            float g[3];
            sampler.gradient(i, g);
            // Classification by |grad f| too: the 1-D table (for a 2-D function its envelope)
            // only said the sample may be visible.
            if (rp.gradientTf.active()) {
              rp.gradientTf.apply(values[i], g, tf, factor);
              if (!(tf.alpha * factor > 0.0f)) continue;
              c[0] = tf.r;
              c[1] = tf.g;
              c[2] = tf.b;
            }
            // And by the curvature of the level set, from the Hessian at the sample's point.
            float contour = 0.0f;
            if (rp.curvatureTf.active()) {
              double p[3];
              for (int a = 0; a < 3; ++a) p[a] = o[a] + mids[i] * d[a];
              float h[6];
              sampler.hessian(i, p, h);
              rp.curvatureTf.apply(g, h, d, mids[i], c, factor, contour);
              if (!(tf.alpha * factor > 0.0f)) continue;
            }
            if (rp.shadeSamples) {
              const float unshaded[3] = {c[0], c[1], c[2]};
              shadeSample(rp.shading, rayShading, unshaded, g, c);
            }
            if (contour > 0.0f)
              for (int a = 0; a < 3; ++a) c[a] += contour * (rp.curvatureTf.contourColor[a] - c[a]);
          }
        }
        const double length = lengths[i];
        const float a =
            (length == dt ? tf.alphaStep
                          : correctOpacity(tf.alpha, rp.correctionExponent * length / dt)) *
            factor;
        const bool below = alpha < 0.5f;
        compositeSample(red, green, blue, alpha, a, c);
        if (below && alpha >= 0.5f) depth = static_cast<float>(mids[i]);
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
    if (rp.depth) rp.depth[ray.pixel] = depth;
  }
  overBackground(rp, red, green, blue, alpha, out);
}

// Which blends an instantiation of the integration renders: every one (chosen per ray from
// rp.blend), only the composite blend, or only the others (rp.blend is not Composite).
enum class RayBlends { Any, Composite, Others };

// Integrates the segment (raySegment; null: the ray misses the box) from `start` into out.
template <bool Masked, bool Shade, RayBlends Blends = RayBlends::Any, class Sampler>
MFADVR_HD MFADVR_INLINE void integrateSegment(const RayParams& rp, Sampler& sampler,
                                              const RaySegment* segment, RayStart start,
                                              float out[4], RayCounters& counters) {
  if constexpr (Blends == RayBlends::Others) {
    if (!segment) {
      overBackground(rp, 0.0f, 0.0f, 0.0f, 0.0f, out);
      return;
    }
  }
  if constexpr (Blends != RayBlends::Composite) {
    if (segment && (Blends == RayBlends::Others || rp.blend != BlendMode::Composite)) {
      ++counters.hits;
      if (rp.blend == BlendMode::Iso) {
        isoSegment<Masked, Shade>(rp, sampler, *segment, out, counters);
      } else if constexpr (!Sampler::kSkipsEmptySpace || (!Shade && kReducesWithSkipping)) {
        reduceSegment<Masked>(rp, sampler, *segment, out, counters);
      } else {
        // Not reached: the other blends skip in unshaded renders on the host only
        // (ModelRenderSetup, CudaRenderer), and leaving the reduction out of the other skipping
        // loops keeps their compilation shorter.
        overBackground(rp, 0.0f, 0.0f, 0.0f, 0.0f, out);
      }
      return;
    }
  }
  if constexpr (Blends != RayBlends::Others)
    compositeSegment<Masked, Shade>(rp, sampler, segment, start, out, counters);
}

template <bool Masked, bool Shade, RayBlends Blends = RayBlends::Any, class Sampler>
MFADVR_HD MFADVR_INLINE void integrateRay(const RayParams& rp, Sampler& sampler, int x, int y,
                                          float out[4], RayCounters& counters) {
  RaySegment ray;
  const bool hits = raySegment(rp, x, y, ray);
  integrateSegment<Masked, Shade, Blends>(rp, sampler, hits ? &ray : nullptr, RayStart{}, out,
                                          counters);
}

}  // namespace mfadvr
