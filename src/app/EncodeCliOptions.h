#pragma once
// The encoding options shared by `encode` and `render` (which encodes a non-model input on the
// fly): degree, control points, adaptive bound, smoothing and domain mask.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "core/encode/Encoder.h"

namespace mfadvr::app {

class EncodeCliOptions {
 public:
  std::string degree = "3", ctrl, smooth, maxError, maxCtrl, maskRes, dequantize, knotDensity,
              cellSamples;
  int maxRounds = 30;
  bool noMask = false;
  bool noBoundary = false;

  // Registers the options on `sub` under `group`.
  void addTo(CLI::App* sub, const std::string& group);
  // Throws CLI::ValidationError naming the option for malformed values.
  EncodeOptions parse() const;
  // Whether --degree was given (else the default 3, which a grid axis of fewer than 4 samples
  // cannot carry: fitDefaultDegreeToGrid lowers it there).
  bool degreeGiven() const { return degreeOption_ && degreeOption_->count() > 0; }
  // Whether one of the options of scattered inputs only was given (--mask-res, --no-mask,
  // --no-boundary, --knot-density, --cell-samples).
  bool scatteredOnlyGiven() const {
    return !maskRes.empty() || noMask || noBoundary || !knotDensity.empty() || !cellSamples.empty();
  }
  // Without --degree: the degree of each axis of a `dims` grid at most its samples - 1 (a
  // degree-p axis needs p + 1 samples), so that small grids (AMR patches, thin slabs) encode
  // with the defaults. Returns a note per lowered axis; with --degree, nothing changes (the
  // encoder then reports the conflict).
  std::vector<std::string> fitDefaultDegreeToGrid(EncodeOptions& options, const Index3& dims) const;

 private:
  CLI::Option* degreeOption_ = nullptr;
  CLI::Option* dequantizeOption_ = nullptr;
};

}  // namespace mfadvr::app
