#pragma once
// The steps of a ray, shared by every blend mode's integration (RayIntegrator.h,
// RayReduction.h), host and device: the ray through a pixel clipped to the box, the clipping
// planes and its ray end; its steps and their samples; front-to-back compositing; the pixel over
// the background.
#include <type_traits>

#include "core/render/kernel/OpacityCorrectionKernel.h"
#include "core/render/kernel/RayParams.h"

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
  std::int64_t pixel = 0;  // y * width + x: the ray's place in per-pixel arrays
};

// Clips [tEnter, tExit] of the ray o + t d to the kept side of every clipping plane (n . x + w
// >= 0); false when nothing of it is kept. A ray parallel to a plane is kept or dropped whole.
MFADVR_HD MFADVR_INLINE bool clipToPlanes(const RayParams& rp, const double o[3], const double d[3],
                                          double& tEnter, double& tExit) {
  for (int i = 0; i < rp.clipPlaneCount; ++i) {
    const double* q = rp.clipPlane[i];
    const double s0 = q[0] * o[0] + q[1] * o[1] + q[2] * o[2] + q[3];
    const double sd = q[0] * d[0] + q[1] * d[1] + q[2] * d[2];
    if (sd > 0.0) {
      const double t = -s0 / sd;
      if (t > tEnter) tEnter = t;
    } else if (sd < 0.0) {
      const double t = -s0 / sd;
      if (t < tExit) tExit = t;
    } else if (s0 < 0.0) {
      return false;
    }
  }
  return tEnter <= tExit;
}

MFADVR_HD MFADVR_INLINE bool raySegment(const RayParams& rp, int x, int y, RaySegment& r) {
  primaryRay(rp.camera, x, y, r.o, r.d);
  double tEnter, tExit;
  r.pixel = static_cast<std::int64_t>(y) * rp.camera.width + x;
  bool crosses = intersectBox(r.o, r.d, rp.boxMin, rp.boxMax, tEnter, tExit);
  if (crosses && rp.clipPlaneCount > 0) crosses = clipToPlanes(rp, r.o, r.d, tEnter, tExit);
  if (crosses && rp.rayEnd) {
    const double end = rp.rayEnd[r.pixel];
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
// mid: the sample's distance along the ray.
MFADVR_HD MFADVR_INLINE bool stepSample(const RaySegment& ray, std::int64_t k, double dt,
                                        double p[3], double& length, double& mid) {
  const double t = rayStep(static_cast<double>(k), ray.t0, ray.tEnter, ray.tExit, dt, length);
  if (!(length > 0.0)) return false;
  mid = t + 0.5 * length;
  for (int a = 0; a < 3; ++a) p[a] = ray.o[a] + mid * ray.d[a];
  return true;
}

MFADVR_HD MFADVR_INLINE bool stepSample(const RaySegment& ray, std::int64_t k, double dt,
                                        double p[3], double& length) {
  double mid;
  return stepSample(ray, k, dt, p, length, mid);
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

}  // namespace mfadvr
