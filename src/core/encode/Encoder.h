#pragma once
// One entry point per kind of input for everything `mfadvr encode` can do: a fixed-size or
// adaptive fit, and for scattered data the domain mask that goes with the model.
//
// The names follow one scheme: encode<Kind> is the whole job (options -> finished model);
// fit<Kind>, fit<Kind>WithKnots and fit<Kind>Adaptive are the fitting algorithms it chooses
// between. Kind is Structured (a StructuredGrid) or Scattered (ScatteredData: meshes and points).
#include <functional>
#include <optional>
#include <string>

#include "core/encode/AdaptiveEncoder.h"
#include "core/encode/CodingChoice.h"
#include "core/encode/FitReport.h"
#include "core/encode/ScatteredEncoder.h"
#include "core/encode/SmoothingChoice.h"
#include "core/encode/StructuredEncoder.h"
#include "core/grid/StructuredGrid.h"
#include "core/mesh/ScatteredData.h"

namespace mfadvr {

struct MaskOptions {
  bool enabled = true;       // scattered inputs only; grids never get one
  Index3 dims{0, 0, 0};      // nodes per axis; 0: from longestAxisNodes
  int longestAxisNodes = 0;  // nodes along the longest box axis, the others in proportion;
                             // 0: the default for the kind of input
  // Meshes: also store the mesh's exact boundary (DomainBoundary.h), which the renderer and
  // queries then use in place of the mask. Only with the mask (enabled).
  bool boundary = true;
};

struct EncodeOptions {
  Degree3 degree{3, 3, 3};
  Index3 controlCounts{0, 0, 0};  // 0: the default (fixed fits) or the start (adaptive)
  // lambda of the roughness penalty (core/spline/DerivativePenalty.h); none: kDefaultSmoothing
  // for scattered inputs, 0 (no smoothing) for grids.
  std::optional<double> smoothing;
  // Grids: lambda chosen by generalized cross-validation (SmoothingChoice.h) instead.
  bool autoSmoothing = false;
  // With autoSmoothing: the samples are multiples of this step, taken as a floor on their noise
  // (SmoothingChoice.h). Off unless given: measured on quantized phantoms it over-smooths more
  // often than it helps (docs/denoise.md), so integer scans get plain GCV too.
  std::optional<double> quantizationStep;
  // Grids: the smoothest model within half a quantization step of every sample
  // (core/encode/Dequantizer.h), with this step; 0: 1, for integer samples.
  std::optional<double> dequantizeStep;
  std::optional<AdaptiveOptions> adaptive;
  // Scattered inputs: how far the knots follow the points' density (ScatteredFitOptions);
  // unset: kDefaultMeshKnotDensity for meshes, 0 (uniform) for point clouds.
  std::optional<double> knotDensity;
  // Meshes: samples of the mesh's own (linear) field fitted per tetrahedron beside its points,
  // 0 (points only), 1 (centroids) or 4 (core/mesh/CellSamples.h); unset:
  // defaultCellSamples().
  std::optional<int> cellSamples;
  MaskOptions mask;
  CodingOptions coding;  // grids; scattered inputs take a given float32 or lossless coder
  std::function<void(double fraction, const std::string& stage)> progress;
};

// The cell samples a scattered input gets unless told: kDefaultMeshCellSamples for a mesh fitted
// with fixed control counts and a fixed smoothing; 0 for point clouds (no cells), --max-error fits
// and --smooth auto, whose bound and choice are about the measured points (the samples inside the
// tetrahedra are the mesh's interpolation, not measurements).
constexpr int kDefaultMeshCellSamples = 1;
int defaultCellSamples(const ScatteredData& data, const EncodeOptions& options);

// A fit (fixed, adaptive, or the candidates of a budget), smoothed when asked (with
// options.autoSmoothing, lambda is chosen first, on the whole grid), and the coding of its control
// points (CodingChoice.h). With --max-error and zfp coding, the fit gets half the bound and the
// coding the room the fit leaves, so that the decoded model keeps the bound; the interpolating
// model coded to the same bound replaces it when its file is smaller.
Model encodeStructured(const StructuredGrid& grid, const EncodeOptions& options,
                       FitReport* report = nullptr);

// The same for samples held elsewhere (GridSamples; `layout` gives dims, box and provenance). A
// plain or smoothed fit without coding reads them plane by plane (no float32 copy of the grid);
// automatic smoothing, error bounds, budgets and coders work on a float32 copy.
Model encodeStructured(const StructuredGrid& layout, const GridSamples& samples,
                       const EncodeOptions& options, FitReport* report = nullptr);

// Throws mfadvr::Error when options.dequantizeStep comes with an option it does not combine with
// (--max-error, a budget, --smooth auto).
void refuseWithDequantize(const EncodeOptions& options);

// options with autoSmoothing replaced by the lambda chosen for `grid` (for fitting pieces of one
// grid with one lambda); `choice` receives the choice when made.
EncodeOptions withChosenSmoothing(const StructuredGrid& grid, const EncodeOptions& options,
                                  SmoothingChoice* choice = nullptr);

// Fits the points, then voxelizes the mask: mesh occupancy when the data have cells (default
// 128 nodes along the longest box axis), point coverage otherwise (default resolution from the
// point count, see defaultCoverageResolution).
Model encodeScattered(const ScatteredData& data, const EncodeOptions& options,
                      FitReport* report = nullptr);

// The mask dims encodeScattered uses for `data` with `options`.
Index3 maskDimsFor(const ScatteredData& data, const MaskOptions& options);

}  // namespace mfadvr
