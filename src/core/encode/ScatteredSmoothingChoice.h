#pragma once
// `--smooth auto` for meshes and point clouds: the smoothing weight lambda chosen by hold-out
// cross-validation.
//
// Grids choose lambda by generalized cross-validation (SmoothingChoice.h), whose hat-matrix
// trace is a product of 1-D traces there; a scattered fit has no such product. So one point in
// eight (every eighth in a fixed pseudo-random order, never a point that spans the box, so the
// box and the knots stay those of the whole fit) is held out, the rest are fitted with lambda
// from 1 down by factors of ten, each fit started from the previous one, and the held-out
// points' RMS error is measured. The search stops two factors of ten past the best, is refined
// by half a decade on both sides, and the lambda of the smallest error is chosen. Each candidate
// costs one fit of 7/8 of the points at the final knots; a mesh sampled finely relative to its
// features gets a small lambda (the held-out points are predicted by interpolation), noisy data
// a larger one.
#include <cstdint>
#include <string>
#include <vector>

#include "core/encode/ScatteredEncoder.h"

namespace mfadvr {

struct ScatteredSmoothingChoice {
  double lambda = 0.0;
  double heldOutRms = 0.0;         // RMS error at the held-out points with lambda
  std::int64_t heldOutPoints = 0;  // the points judged
  struct Point {
    double lambda, heldOutRms;
  };
  std::vector<Point> curve;  // every lambda tried, in the order tried
  std::string note;          // one line for the report
};

// The choice for a fit with options.degree, options.controlCounts and options.knotDensity
// (options.smoothing is ignored). Needs at least 64 points; throws mfadvr::Error as
// fitScattered does.
ScatteredSmoothingChoice chooseScatteredSmoothing(const ScatteredData& data,
                                                  const ScatteredFitOptions& options);

}  // namespace mfadvr
