#pragma once
// Everything the per-ray integration needs besides the field, as one plain struct (host and
// device): camera rays, the box, sampling, the transfer-function table, shading, compositing,
// ray ends. compileRayParams() (render/RayParamsBuilder.h) fills it from RenderSettings; the
// arrays it points to (table entries, ray ends) are owned by the caller.
#include <cstdint>

#include "core/render/BlendMode.h"
#include "core/render/kernel/CameraRays.h"
#include "core/render/kernel/CurvatureTransferView.h"
#include "core/render/kernel/EmptySpaceProfile.h"
#include "core/render/kernel/GradientTransferView.h"
#include "core/render/kernel/ShadingKernel.h"
#include "core/render/kernel/TransferFunctionView.h"

namespace mfadvr {

// At most this many clipping planes per render (VTK's GPU mapper takes six).
inline constexpr int kMaxClipPlanes = 8;
// At most this many isovalues per render.
inline constexpr int kMaxIsoValues = 8;

struct RayParams {
  CameraRays camera;
  double boxMin[3], boxMax[3];
  double sampleDistance = 1.0;
  bool alignSteps = false;  // steps at multiples of sampleDistance from the ray origin
  // Opacity correction exponent of a full step (sample distance / opacity unit distance); the
  // table's alphaStep already holds it, shorter last steps scale it.
  double correctionExponent = 1.0;
  float stopOpacity = 0.99f;  // early ray termination
  float background[3] = {0.0f, 0.0f, 0.0f};
  const float* rayEnd = nullptr;  // width * height distances along the rays, or null
  TransferFunctionView tf;
  ShadingParams shading;  // filled for shaded renders (integrateRay<..., Shade = true>)
  // Loops with gradients (Shade = true) shade the samples' colours unless this is false: a
  // render that classifies by the gradient or curvature without shading.
  bool shadeSamples = true;
  // Gradient opacity and 2-D transfer functions (composite blend); inactive: none.
  GradientTransferView gradientTf;
  // Curvature transfer functions and contours (composite blend); inactive: none.
  CurvatureTransferView curvatureTf;
  BlendMode blend = BlendMode::Composite;
  // Average and additive blends: v' = (v - valueLo) * valueScale, the value normalized over the
  // transfer function's range; average: values in [averageLo, averageHi] count.
  float valueLo = 0.0f, valueScale = 1.0f;
  float averageLo = -INFINITY, averageHi = INFINITY;
  // Additive blend: a step of length dt adds a v' dt * additiveScale (1 / opacity unit distance).
  double additiveScale = 1.0;
  // Maximum blend: every value at or below this is transparent (TransferFunctionTable::
  // transparentUpTo); minimum blend: every value at or above it (transparentFrom). A ray skips
  // cells that cannot go beyond it as it skips those that cannot beat its running extreme.
  float transparentBeyond = NAN;
  // Clipping planes: a point x is kept where n . x + w >= 0, plane i = {n0, n1, n2, w}.
  int clipPlaneCount = 0;
  double clipPlane[kMaxClipPlanes][4];
  // Isosurface blend: the values, their colours (rgb, opacity), and the Chebyshev-Lobatto nodes
  // and Bernstein bases of every degree 0..kMaxIsoDegree (IsoBasis.h; host or device memory).
  int isoCount = 0;
  float isoValue[kMaxIsoValues];
  float isoColor[kMaxIsoValues][4];
  const double* isoNodes = nullptr;
  const double* isoBasis = nullptr;
  // width * height ray distances (RenderSettings::depth), written by every ray that hits the
  // box; the driver fills it with NaN first. Null: no depth.
  float* depth = nullptr;
};

// Per-thread counts, summed by the driver.
struct RayCounters {
  std::int64_t samples = 0;     // field samples taken (not those outside a mask, nor skipped)
  std::int64_t hits = 0;        // rays that crossed the box
  std::int64_t terminated = 0;  // rays stopped early
  std::int64_t skipped = 0;     // samples passed over by empty-space skipping
#if MFADVR_EMPTY_SPACE_PROFILE
  EmptySpaceCycles cycles;  // the profiling build's measurements (EmptySpaceProfile.h)
#endif
};

}  // namespace mfadvr
