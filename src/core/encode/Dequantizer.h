#pragma once
// `encode --dequantize [STEP]`: the smoothest model that still rounds back to every sample.
//
// A quantized sample s only says that the value lies in [s - STEP/2, s + STEP/2]; an
// interpolating model takes every step literally (terraces, wood-grain rings on the isosurfaces
// of 8-bit scans), a smoothing fit ignores the bound. Among the values v of the grid within
// those intervals (narrowed by a slack left to the control-point coding), the one of least
// roughness v^T K v, where K is the roughness of the separable smoother of `--smooth lambda`
// (S = (I + K)^-1: the tensor product of the axes' penalized fits, StructuredEncoder.h), is found
// by ADMM with over-relaxation (Boyd et al. 2011, "Distributed Optimization and Statistical
// Learning via the Alternating Direction Method of Multipliers", sections 3.1 and 3.4.3):
//
//   v = S (z - u);   z = clamp(a v + (1 - a) z + u, lo, hi);   u += a v + (1 - a) z_old - z,
//
// started from the samples (z = s, u = 0), until the largest |v - z| and the largest change of z
// are both below tolerance x STEP. The model is then fitted to z (which is inside the intervals):
// an interpolating model gives z back at the samples, so that it rounds back to every sample.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/grid/StructuredGrid.h"
#include "core/spline/KnotVector.h"

namespace mfadvr {

struct DequantizeOptions {
  double step = 1.0;  // the quantization step: sample s stands for [s - step/2, s + step/2]
  // lambda of the smoother whose roughness is minimized; it also sets ADMM's step (a larger one
  // moves the values further per iteration).
  double smoothing = 0.1;
  // Share of step/2 kept free for the coding of the control points (zfp): the values are held
  // within (1 - slack) step/2 of the samples. Measured on a smooth field quantized to 8 bits
  // (docs/encoding.md): 0.05 gives the most accurate coded model and the smallest file; a wider
  // slack lets zfp add more noise than the narrower intervals remove.
  double slack = 0.05;
  double tolerance = 2e-3;  // of the step: the stopping test on both residuals
  int maxIterations = 300;
  double relaxation = 1.6;  // a in the updates above (1: plain ADMM)
  std::function<void(double fraction, const std::string& stage)> progress;
};

struct DequantizeResult {
  std::vector<float> targets;  // z: the values the model is fitted to, x fastest
  int iterations = 0;
  bool converged = false;
  double primalResidual = 0.0;  // max |v - z| at the end, absolute
  double edgeShare = 0.0;       // share of the samples whose z sits on its interval's edge
  double seconds = 0.0;
};

// Throws mfadvr::Error for a step that is not positive and finite, and for samples that are not
// multiples of it (checked to 1e-3 of the step; integer samples with the default step of 1).
DequantizeResult dequantizeTargets(const StructuredGrid& grid,
                                   const std::array<KnotVector, 3>& knots,
                                   const DequantizeOptions& options);

}  // namespace mfadvr
