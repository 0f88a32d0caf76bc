#include "app/EncodeCliOptions.h"

#include <charconv>
#include <cmath>

#include "app/OptionParsing.h"

namespace mfadvr::app {

namespace {

double parsePositive(const std::string& option, const std::string& text, bool allowZero) {
  const double v = parseNumberList(option, text, 1, 1)[0];
  if (v < 0.0 || (!allowZero && v == 0.0))
    throw CLI::ValidationError(
        option, std::string("must be ") + (allowZero ? ">= 0" : "> 0") + ", got '" + text + "'");
  return v;
}

Index3 parseCounts(const std::string& option, const std::string& text, long minimum) {
  const auto n = parseIntTriple(option, text);
  Index3 out{};
  for (int a = 0; a < 3; ++a) {
    if (n[a] < minimum)
      throw CLI::ValidationError(option, "counts must be at least " + std::to_string(minimum));
    out[a] = n[a];
  }
  return out;
}

}  // namespace

void EncodeCliOptions::addTo(CLI::App* sub, const std::string& group) {
  degreeOption_ = sub->add_option("--degree", degree,
                                  "Polynomial degree P or PX,PY,PZ (1..7); by default 3, lowered "
                                  "on a grid axis of fewer than 4 samples to samples - 1")
                      ->capture_default_str()
                      ->group(group);
  sub->add_option("--ctrl", ctrl,
                  "Control points N or NX,NY,NZ per axis. Grids: default as many as samples "
                  "(interpolation); scattered data: default about the cube root of the point "
                  "count (at most 64); with --max-error: the starting counts (default degree+2)")
      ->group(group);
  sub->add_option("--max-error", maxError,
                  "Adaptive encoding: refine knots until the max error over all input samples "
                  "is at most E times the value range (e.g. 1e-3)")
      ->group(group);
  sub->add_option("--max-ctrl", maxCtrl,
                  "Adaptive encoding: at most N or NX,NY,NZ control points per axis "
                  "(default: the sample count for grids, 256 for scattered data)")
      ->group(group);
  sub->add_option("--max-rounds", maxRounds, "Adaptive encoding: at most R refinement rounds")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000))
      ->group(group);
  dequantizeOption_ =
      sub->add_option("--dequantize", dequantize,
                      "Grids of quantized samples (integer scans): the smoothest model whose value "
                      "at every sample stays within half a quantization step STEP of it (default "
                      "1 for integer samples; float data give theirs), so that it still rounds "
                      "back to every sample: no terraces (docs/encoding.md). --smooth LAMBDA sets "
                      "the roughness it minimizes")
          ->expected(0, 1)
          ->group(group);
  sub->add_option("--smooth", smooth,
                  "Smoothing weight lambda >= 0 of the roughness penalty, or 'auto' (grids: "
                  "chosen by generalized cross-validation; meshes and point clouds: by "
                  "hold-out cross-validation on 1/8 of the points). Damps wavelengths below about "
                  "2 pi lambda^(1/4) knot spans. Grids: default 0 (no smoothing; "
                  "docs/denoise.md); scattered data: default 1e-2 (docs/encoding.md)")
      ->group(group);
  sub->add_option(
         "--knot-density", knotDensity,
         "Scattered data: how far the knots follow the points' density along each axis, "
         "0 (uniform) .. < 1 (spans holding equal shares of the points). Default: 0.75 for "
         "meshes (control points gather where the mesh is refined), 0 for point clouds "
         "(docs/encoding.md)")
      ->group(group);
  sub->add_option(
         "--cell-samples", cellSamples,
         "Meshes: also fit the mesh's own field (linear in each tetrahedron) at N points inside "
         "every tetrahedron: 0 (the points alone), 1 (centroids) or 4. Ties the model to the mesh "
         "between its points instead of ringing there; fits take 3-5x longer. Default: 1 for "
         "meshes, 0 with --max-error or --smooth auto (their bound and choice concern the "
         "measured points) and for point clouds (docs/encoding.md)")
      ->group(group);
  sub->add_option("--mask-res", maskRes,
                  "Scattered data: domain-mask nodes N (longest axis) or NX,NY,NZ (default: 128 "
                  "along the longest axis for meshes, from the point count for point clouds)")
      ->group(group);
  sub->add_flag("--no-mask", noMask,
                "Scattered data: store no domain mask nor boundary (the model then covers its "
                "whole box)")
      ->group(group);
  sub->add_flag("--no-boundary", noBoundary,
                "Meshes: store only the voxel mask, not the mesh's exact boundary triangles "
                "(which rays and queries otherwise use to find where the mesh begins and "
                "ends; docs/encoding.md)")
      ->group(group);
}

std::vector<std::string> EncodeCliOptions::fitDefaultDegreeToGrid(EncodeOptions& options,
                                                                  const Index3& dims) const {
  std::vector<std::string> notes;
  if (degreeGiven()) return notes;
  for (int a = 0; a < 3; ++a) {
    if (dims[a] >= 2 && options.degree[a] > dims[a] - 1) {
      options.degree[a] = static_cast<int>(dims[a] - 1);
      notes.push_back(std::string("axis ") + "xyz"[a] + " has " + std::to_string(dims[a]) +
                      " samples: degree " + std::to_string(options.degree[a]) +
                      " on that axis (the default 3 needs 4; --degree sets it)");
    }
  }
  return notes;
}

EncodeOptions EncodeCliOptions::parse() const {
  const StructuredFitOptions fit = parseFitOptions(degree, ctrl);
  EncodeOptions o;
  o.degree = fit.degree;
  o.controlCounts = fit.controlCounts;
  if (smooth == "auto") {
    o.autoSmoothing = true;
  } else if (!smooth.empty()) {
    const double v = parseNumberList("--smooth", smooth, 1, 1)[0];
    if (!(v >= 0.0) || !std::isfinite(v))
      throw CLI::ValidationError("--smooth",
                                 "must be a finite number >= 0 or 'auto', got '" + smooth + "'");
    o.smoothing = v;
  }
  if (dequantizeOption_ && dequantizeOption_->count() > 0)
    o.dequantizeStep = dequantize.empty() ? 0.0 : parsePositive("--dequantize", dequantize, false);
  if (!maxError.empty()) {
    AdaptiveOptions a;
    a.maxRelativeError = parsePositive("--max-error", maxError, false);
    if (!maxCtrl.empty()) a.maxControlCounts = parseCounts("--max-ctrl", maxCtrl, 2);
    a.maxRounds = maxRounds;
    o.adaptive = a;
  } else if (!maxCtrl.empty()) {
    throw CLI::ValidationError("--max-ctrl", "limits adaptive encoding; give --max-error too");
  }
  if (!knotDensity.empty()) {
    const double w = parseNumberList("--knot-density", knotDensity, 1, 1)[0];
    if (!(w >= 0.0 && w < 1.0))
      throw CLI::ValidationError("--knot-density", "must lie in [0, 1), got '" + knotDensity + "'");
    o.knotDensity = w;
  }
  if (!cellSamples.empty()) {
    const double n = parseNumberList("--cell-samples", cellSamples, 1, 1)[0];
    if (n != 0.0 && n != 1.0 && n != 4.0)
      throw CLI::ValidationError("--cell-samples", "must be 0, 1 or 4, got '" + cellSamples + "'");
    o.cellSamples = static_cast<int>(n);
  }
  if (!maskRes.empty()) {
    const auto n = parseIntTriple("--mask-res", maskRes);
    const bool single = maskRes.find(',') == std::string::npos;
    for (int a = 0; a < 3; ++a)
      if (n[a] < 2 || n[a] > 4096)
        throw CLI::ValidationError("--mask-res", "nodes per axis must be in 2..4096");
    if (single)
      o.mask.longestAxisNodes = static_cast<int>(n[0]);
    else
      o.mask.dims = {n[0], n[1], n[2]};
  }
  if (noMask && !maskRes.empty())
    throw CLI::ValidationError("--no-mask", "contradicts --mask-res; give one of them");
  o.mask.enabled = !noMask;
  o.mask.boundary = !noBoundary;
  return o;
}

}  // namespace mfadvr::app
