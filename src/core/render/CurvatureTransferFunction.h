#pragma once
// A curvature transfer function (Kindlmann et al., "Curvature-based transfer functions for
// direct volume rendering", IEEE Visualization 2003): a table over the principal curvatures
// (k1, k2), k1 >= k2, of the level set through each sample (field/Curvature.h; 1 / world units,
// positive where the surface bends around higher values). Each entry holds a colour, the weight
// with which it replaces the sample's colour from the value transfer function (0: the sample
// keeps its colour), and a factor on the sample's opacity. Read back with bilinear
// interpolation, clamped to the table's edges. Only an analytic model gives the exact Hessian
// this needs at every sample; the grid filters' is the difference of their own gradients.
//
// Forms (docs/transfer-functions.md, "Curvature"): a preset, scaled by a curvature K (1 / world
// units: the curvature of a sphere of radius 1 / K, at which the preset's colours are full):
//   ridges-valleys  ridges (k1 from K/4 to K) orange, valleys (-k2 from K/4 to K) blue
//   mean            (k1 + k2) / 2 over [-K, K]: blue (bends around lower values), white, red
//   gaussian        k1 k2 over [-K^2, K^2]: green (saddles), white, orange (caps and cups)
// or a JSON file of boxes in (k1, k2), later boxes over earlier ones:
//   {"boxes": [{"k1": [LO, HI], "k2": [LO, HI], "color": [R, G, B], "weight": W,
//               "opacity": A}, ...], "size": [W, H]}
// (weight and opacity default to 1; outside every box the sample is unchanged).
#include <string>
#include <vector>

namespace mfadvr {

struct CurvatureTransferFunction {
  int width = 0, height = 0;  // >= 2 each
  // width * height * 5 floats: entry (i, j) at (j * width + i) * 5, i along k1, j along k2:
  // R, G, B, weight (in [0, 1]), opacity factor (in [0, 1]).
  std::vector<float> entries;
  // Entry i = 0 sits at k1Lo, i = width - 1 at k1Hi; likewise j along k2.
  double k1Lo = -1.0, k1Hi = 1.0, k2Lo = -1.0, k2Hi = 1.0;

  // Throws mfadvr::Error naming the first problem.
  void validate() const;
  const float* entry(int i, int j) const {
    return &entries[(static_cast<size_t>(j) * width + i) * 5];
  }
};

// The preset names, for help texts and errors.
std::string curvaturePresetNames();

// A preset scaled by K > 0 (1 / world units). mfadvr::Error for an unknown name.
CurvatureTransferFunction curvaturePreset(const std::string& name, double k);

// The JSON box form; `where` names the source in errors.
CurvatureTransferFunction parseCurvatureTransferFunctionJson(const std::string& text,
                                                             const std::string& where);

// SPEC: a preset name with an optional ":K" (default: defaultK), or a .json file of boxes.
CurvatureTransferFunction readCurvatureTransferFunction(const std::string& spec, double defaultK);

}  // namespace mfadvr
