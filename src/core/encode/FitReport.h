#pragma once
// How well an encoding went: errors over every input sample, size, time.
#include <cstdint>
#include <string>

#include "core/util/Vec.h"

namespace mfadvr {

class Model;

struct FitReport {
  std::string source;
  Index3 samples{0, 0, 0};
  Degree3 degree{0, 0, 0};
  Index3 controlCounts{0, 0, 0};
  double seconds = 0.0;  // wall time of the fit, error evaluation included
  double valueMin = 0.0, valueMax = 0.0;
  double maxError = 0.0;  // absolute, model (float32 control points) vs every input sample
  double rmsError = 0.0;
  std::int64_t inputBytes = 0;
  std::int64_t modelBytes = 0;  // size of the .mfa file
  // The encoding process's peak resident memory when the report was made (the command sets it
  // after the model is written; 0: not measured).
  std::int64_t peakMemoryBytes = 0;
  std::string encoder;           // as recorded in the model's provenance
  std::string field;             // scalar name, when the input has one
  std::string fieldAssociation;  // scattered inputs: "point data", "cell data averaged to points"

  // Scattered inputs (points == 0 for grids).
  std::int64_t points = 0;
  // Meshes with --cell-samples: samples of the mesh's linear field inside its tetrahedra, fitted
  // beside the points; the errors above are then over the points and these samples.
  std::int64_t cellSamples = 0;
  std::string inputKind;        // "tetrahedral mesh", "point cloud", ...
  double smoothing = 0.0;       // regularization weight lambda (grids too, with --smooth)
  int solverIterations = 0;     // conjugate-gradient iterations, all levels and rounds
  double solverResidual = 0.0;  // relative residual |b - Ax| / |b| of the last solve

  // Grids with --smooth auto: the noise level estimated with the chosen lambda (absolute, RMS;
  // 0 when lambda was given) and what the choice saw.
  double noiseEstimate = 0.0;
  std::string smoothingNote;

  // Grids with --dequantize (dequantizeStep == 0 without): the step, the ADMM iterations, whether
  // they met the tolerance, the share of samples on an interval's edge and the time taken.
  double dequantizeStep = 0.0;
  double dequantizeLambda = 0.0;  // of the smoother whose roughness was minimized
  int dequantizeIterations = 0;
  bool dequantizeConverged = true;
  double dequantizeEdgeShare = 0.0;
  double dequantizeSeconds = 0.0;

  // Time series (timeSteps == 0 for one volume): steps, the time axis's degree and control
  // count; the errors above are over every sample of every step.
  std::int64_t timeSteps = 0;
  int timeDegree = 0;
  int timeControlCount = 0;
  // Adaptive encoding (rounds == 0 when the control counts were fixed).
  int rounds = 0;
  double targetRelativeError = 0.0;
  bool reachedTarget = true;
  std::string stopReason;  // why refinement stopped

  // Domain mask (maskKind empty when the model has none).
  std::string maskKind;
  Index3 maskDims{0, 0, 0};
  double maskInsideFraction = 1.0;
  // Exact boundary of a mesh (0 triangles: none) and the time to extract it.
  std::int64_t boundaryTriangles = 0, boundaryVertices = 0;
  double boundarySeconds = 0.0;

  // Control-point coding (core/model/ControlCoding.h; errors above are of the decoded model).
  std::string coding = "float32";
  double codingTolerance = 0.0;  // zfp: the largest change of a control point
  std::string codingNote;        // what the encoder chose and why (defaults, bounds, budgets)

  double valueRange() const { return valueMax - valueMin; }
  // Errors relative to the value range (0 when the data are constant and fitted exactly).
  double maxRelativeError() const { return relative(maxError); }
  double rmsRelativeError() const { return relative(rmsError); }
  // PSNR over the value range, dB, from the RMS error (+inf for an exact model).
  double psnr() const;
  // File bits per input sample (or point).
  double bitsPerSample() const;
  double compressionRatio() const {
    return modelBytes > 0 ? static_cast<double>(inputBytes) / static_cast<double>(modelBytes) : 0;
  }

 private:
  double relative(double e) const { return valueRange() > 0.0 ? e / valueRange() : e; }
};

// PSNR in dB of an RMS error over a value range: 20 log10(range / rms); +inf for rms 0.
double psnrOf(double range, double rms);

// The report fields a model records itself: source, input size, degree, control counts, value
// range, errors, fit time (from its provenance), encoder and file size. Encoders add the rest.
FitReport fitReportOf(const Model& model);

}  // namespace mfadvr
