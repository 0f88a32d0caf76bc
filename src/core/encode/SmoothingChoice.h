#pragma once
// `--smooth auto` for grids: the smoothing weight lambda chosen from the data by generalized
// cross-validation (GCV), and the noise level it implies.
//
// GCV(lambda) = (RSS / P) / (1 - T / P)^2, with RSS the squared error of the penalized fit over
// the P samples and T the trace of its hat matrix (its effective number of parameters, a
// product of 1-D traces for the separable fit). Its minimum estimates the lambda that predicts
// unseen samples best, without knowing the noise level; the noise variance then follows as
// RSS / (P - T). Lambda is searched over powers of ten from 1e-6 to 1e3 (one fit each), then
// refined by halving the step around the best one down to a factor of 10^(1/8).
//
// Large grids are judged on eight bricks of 64^3 samples centred in the octants of the volume
// (their RSS and traces summed), with control points as dense as the whole fit's: lambda is
// measured in knot spans, so the choice carries over, and the search costs the same for any
// volume.
//
// Quantized samples (integer scans: a step of 1) carry an error of at least step / sqrt(12)
// RMS, but the error of a smooth field quantized is structured (terraces), and GCV takes it for
// signal. When the noise GCV implies is below that floor, lambda is raised until it reaches it
// (the discrepancy principle with the quantization noise: bisection over log lambda). Measured
// on quantized phantoms this over-smooths more often than it helps (flat regions quantize
// without error, so step / sqrt(12) overstates the noise): `encode` leaves it off.
#include <functional>
#include <string>
#include <vector>

#include "core/encode/StructuredEncoder.h"

namespace mfadvr {

struct SmoothingChoice {
  double lambda = 0.0;
  double noiseRms = 0.0;             // sqrt(RSS / (P - T)) at lambda, absolute
  double effectiveParameters = 0.0;  // T at lambda, over the samples judged
  std::int64_t samplesJudged = 0;    // P: the whole grid, or the bricks
  int bricks = 0;                    // 0: the whole grid
  struct Point {
    double lambda, gcv, rss, trace;
  };
  std::vector<Point> curve;           // every lambda tried, in the order tried
  bool raisedToQuantization = false;  // lambda raised to the quantization floor
  std::string note;                   // one line for the report
};

struct SmoothingSearch {
  std::int64_t wholeGridSamples = 128 * 128 * 128;  // larger grids are judged on bricks
  std::int64_t brickSamples = 64;                   // per axis
  double quantizationStep = 0.0;                    // samples are multiples of it; 0: not known
};

// The choice for a fit with options.degree and options.controlCounts (options.smoothing is
// ignored). Throws mfadvr::Error as fitStructured does.
SmoothingChoice chooseSmoothing(const StructuredGrid& grid, const StructuredFitOptions& options,
                                const SmoothingSearch& search = {});

}  // namespace mfadvr
