#pragma once
// Transfer functions for the volume renderer, with VTK's semantics: a piecewise-linear
// scalar->RGB map (vtkColorTransferFunction in RGB space) and a piecewise-linear scalar->opacity
// map (vtkPiecewiseFunction). Parsing of the user-facing forms (presets, inline points, JSON files,
// ParaView preset exports) is declared here too, so that one include serves the renderer and the
// command line. docs/transfer-functions.md describes the forms.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/util/Vec.h"

namespace mfadvr {

// Where the x of a transfer-function point lives: fractions of the data's value range
// (0 = min, 1 = max), or data values.
enum class TfSpace { Normalized, Data };

struct ColorPoint {
  double x;
  Vec3f rgb;  // in [0,1]
};

struct OpacityPoint {
  double x;
  float alpha;  // in [0,1]
};

// Piecewise-linear scalar->RGB and scalar->opacity maps (vtkColorTransferFunction in RGB space,
// vtkPiecewiseFunction): linear between points, clamped to the end values outside them.
// Points are sorted by x; two points may share an x to make a jump (the later one holds from that
// x on), so "step at an isovalue" is exact. NaN samples are transparent (opacity 0).
struct TransferFunction {
  TfSpace space = TfSpace::Normalized;
  std::vector<ColorPoint> color;
  std::vector<OpacityPoint> opacity;
  // VTK's ScalarOpacityUnitDistance: opacities are per this distance in world units; 0 means
  // "not set" (the renderer then picks a default from the data spacing).
  double unitDistance = 0.0;
  // Where the colour points' x live when that differs from `space`: a normalized colour preset
  // combined with data-value opacities is common, and neither can be converted without the data
  // range. Unset means `space`. resolved() clears it; colorAt() takes x in colorPointSpace().
  std::optional<TfSpace> colorSpace;

  TfSpace colorPointSpace() const { return colorSpace.value_or(space); }

  // Throws mfadvr::Error unless both lists are non-empty, sorted non-decreasing, finite, in [0,1]
  // for rgb/alpha, unitDistance >= 0 and finite.
  void validate() const;
  // Maps Normalized points onto [vmin, vmax] (Data points are copied); result space Data.
  // vmin == vmax is allowed (constant data): then normalize as if the range were [vmin, vmin+1].
  TransferFunction resolved(double vmin, double vmax) const;
  Vec3f colorAt(double x) const;  // x in colorPointSpace()
  float opacityAt(double x) const;
  // The least and greatest opacity over the values [lo, hi] (x as the opacity points'): the
  // ends' and those of the points between (a jump's both sides).
  std::pair<float, float> opacityOver(double lo, double hi) const;
};

// Colour-map and opacity presets; the names and forms the parse functions accept.
std::vector<std::string> colorMapPresetNames();
// Forms with their parameters, e.g. "step:ISO[:A]"; parameters are normalized values.
std::vector<std::string> opacityPresetNames();

// Parses the command-line forms; throws mfadvr::Error with a message listing the accepted forms.
// `opacitySpec`: a preset ("ramp", "step:0.5", ...), inline points "x:a,x:a,..." (normalized),
//   or a JSON file; empty means "ramp".
// `colorSpec`: a preset name, inline points "x:r:g:b,..." (normalized), or a JSON file; empty means
//   the colours of the opacity JSON file if it has any, else "cool-to-warm".
// A JSON file is our format or a ParaView preset export ("file.json#Name" picks a preset by name).
// The result is validated; colour and opacity may live in different spaces (see colorSpace).
TransferFunction parseTransferFunction(const std::string& opacitySpec,
                                       const std::string& colorSpec);

// Loads our JSON format or a ParaView preset export ("path#Name" picks a preset by name).
// A list absent from the file is left empty (a file may hold only a colour map or only an opacity
// map); a file with neither is an error. Not validated beyond the file's own syntax.
TransferFunction loadTransferFunctionJson(const std::string& path);
// Our JSON format; loadTransferFunctionJson reads it back exactly.
nlohmann::json transferFunctionToJson(const TransferFunction& tf);
void saveTransferFunctionJson(const TransferFunction& tf, const std::string& path);

// ---- inline evaluation: called at every ray sample, so no allocation and no call overhead ----

namespace detail {
// Index of the first point whose x is greater than `x` (the size when none is): the segment
// [i-1, i] holds x, and with repeated x the later point wins. Short lists scan linearly.
template <typename Point>
inline std::size_t upperPoint(const std::vector<Point>& p, double x) {
  if (p.size() <= 8) {
    std::size_t i = 0;
    while (i < p.size() && !(x < p[i].x)) ++i;
    return i;
  }
  return static_cast<std::size_t>(
      std::upper_bound(p.begin(), p.end(), x, [](double v, const Point& q) { return v < q.x; }) -
      p.begin());
}
}  // namespace detail

inline Vec3f TransferFunction::colorAt(double x) const {
  const std::size_t i = detail::upperPoint(color, x);
  if (i == 0) return color.front().rgb;
  if (i == color.size()) return color.back().rgb;
  const ColorPoint& a = color[i - 1];
  const ColorPoint& b = color[i];
  const float t = static_cast<float>((x - a.x) / (b.x - a.x));
  return a.rgb + t * (b.rgb - a.rgb);
}

inline float TransferFunction::opacityAt(double x) const {
  if (std::isnan(x)) return 0.0f;
  const std::size_t i = detail::upperPoint(opacity, x);
  if (i == 0) return opacity.front().alpha;
  if (i == opacity.size()) return opacity.back().alpha;
  const OpacityPoint& a = opacity[i - 1];
  const OpacityPoint& b = opacity[i];
  const double t = (x - a.x) / (b.x - a.x);
  return static_cast<float>(a.alpha + t * (b.alpha - a.alpha));
}

}  // namespace mfadvr
