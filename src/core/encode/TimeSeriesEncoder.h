#pragma once
// One 4-D model of a whole time series (docs/time-varying.md): space fitted as a grid is, time as
// a fourth separable axis, streamed over the steps.
//
// Each step is fitted on its own with the same spatial knots (the separable fit of
// StructuredEncoder.h); its control grid C_s then adds its row of the time basis to the right-hand
// side of the time axis's normal equations, B_l += N_l(u_s) C_s (p_t + 1 slabs per step), and is
// dropped. Once every step was seen, one banded solve per spatial control point gives the nt
// slabs: the tensor least-squares solution over (x, y, z, t) (the pseudo-inverse of a Kronecker
// product is the product of the pseudo-inverses), smoothed in time with the same lambda as in
// space. Memory: the 4-D control points, one step's samples and one step's fit, never the series.
// The errors are measured in a second pass over the steps, on the model as stored.
#include <string>
#include <vector>

#include "core/encode/Encoder.h"
#include "core/grid/VolumeSeries.h"
#include "core/model/TimeVaryingModel.h"

namespace mfadvr {

struct TimeSeriesOptions {
  int degree = 3;        // lowered to steps - 1 for fewer than degree + 1 steps (with a note)
  int controlCount = 0;  // 0: as many as steps (interpolating in time)
  // Without a coder in the options: zfp for integer samples (`mfadvr encode`'s default for
  // grids too), float32 otherwise.
  bool zfpForIntegerSamples = false;
};

inline constexpr int kDefaultTimeDegree = 3;

// Spatial options as encodeStructured's, with these differences:
// - `--smooth auto` chooses lambda by GCV on the middle step (SmoothingChoice.h); that lambda
//   fits every step and the time axis.
// - `--dequantize` dequantizes each step on its own (Dequantizer.h) and interpolates them in time
//   (no smoothing in time; --time-ctrl must equal the steps), so that every sample of every step
//   stays within half a quantization step; zfp then gets the room the fits leave.
// - A budget (--bits-per-sample, --psnr, --rms-error) searches the zfp tolerance of the 4-D array
//   for the given or default control grid (the grid encoder also searches control counts); an
//   error budget measures each candidate over every step (one pass over the series each).
// - --max-error is refused (mfadvr::Error).
// Coding: float32, lossless, or zfp over the 4-D array (tolerance given, else 0.25 for integer
// samples: the model then rounds back to the samples when it interpolates them; 1e-5 of the value
// range for float ones). Throws mfadvr::Error for fewer than two steps, times that do not
// increase (naming the step), a step whose grid differs from the first's (naming it) and bad
// options. `notes` receives what was adjusted (a lowered degree).
TimeVaryingModel encodeTimeSeries(const VolumeSeries& series, const EncodeOptions& options,
                                  const TimeSeriesOptions& time, FitReport* report = nullptr,
                                  std::vector<std::string>* notes = nullptr);

// What an encode does beside the plain fit, for its memory estimate.
struct TimeSeriesWork {
  bool budget = false;      // a candidate decoded beside the control points
  bool dequantize = false;  // the dequantizer's vectors beside a step's samples
};

// Bytes the encode holds at most: the 4-D control points (float32), one step's samples and its
// fit (structuredFitPeakBytes), one step's control grid, and what `work` adds.
std::int64_t timeSeriesPeakBytes(const Index3& dims, const Index3& counts, std::int64_t slabs,
                                 const TimeSeriesWork& work = {});

}  // namespace mfadvr
