#include "core/render/ParaViewPreset.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/render/ColorSpace.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// Enough points that a Diverging or Lab map, interpolated in RGB between them, stays within a
// fraction of a colour level of the curved original.
constexpr int kMinColorSamples = 64;
// Subdivisions of an opacity segment whose midpoint/sharpness make it a curve.
constexpr int kCurveSamples = 32;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<double> numbers(const nlohmann::json& preset, const char* key, size_t tuple,
                            const std::string& where) {
  const auto& a = preset.at(key);
  bool ok = a.is_array() && !a.empty() && a.size() % tuple == 0;
  std::vector<double> out;
  for (size_t i = 0; ok && i < a.size(); ++i) {
    ok = a[i].is_number() && std::isfinite(a[i].get<double>());
    if (ok) out.push_back(a[i].get<double>());
  }
  if (!ok)
    throw Error(where + ": \"" + key + "\" must be a non-empty array of finite numbers, " +
                std::to_string(tuple) + " per point");
  return out;
}

// Maps x from [first, last] onto [0,1] (ParaView rescales a preset to the range it is applied to).
double rescale(double x, double first, double last) {
  return last > first ? (x - first) / (last - first) : 0.0;
}

ColorInterpolation colorInterpolation(const nlohmann::json& preset, const std::string& where,
                                      bool& step) {
  step = false;
  if (!preset.contains("ColorSpace")) return ColorInterpolation::Rgb;
  const auto& v = preset["ColorSpace"];
  const std::string s = v.is_string() ? lower(v.get<std::string>()) : std::string();
  if (s == "rgb") return ColorInterpolation::Rgb;
  if (s == "hsv") return ColorInterpolation::Hsv;
  // CIELAB is ParaView's CIEDE2000 path; plain Lab interpolation is close to it.
  if (s == "lab" || s == "cielab") return ColorInterpolation::Lab;
  if (s == "diverging") return ColorInterpolation::Diverging;
  if (s == "step") {
    step = true;
    return ColorInterpolation::Rgb;
  }
  throw Error(where + ": unsupported \"ColorSpace\" " + v.dump() +
              "; expected RGB, HSV, Lab, CIELAB, Diverging or Step");
}

std::vector<ColorPoint> colorPoints(const nlohmann::json& preset, const std::string& where) {
  const auto v = numbers(preset, "RGBPoints", 4, where);
  const size_t n = v.size() / 4;
  const double first = v[0], last = v[4 * (n - 1)];
  bool step = false;
  const auto space = colorInterpolation(preset, where, step);
  auto x = [&](size_t i) { return rescale(v[4 * i], first, last); };
  auto rgb = [&](size_t i) { return Vec3d(v[4 * i + 1], v[4 * i + 2], v[4 * i + 3]); };
  std::vector<ColorPoint> out;
  const int sub =
      space == ColorInterpolation::Rgb
          ? 1
          : std::max(1, static_cast<int>(std::ceil(kMinColorSamples / std::max<double>(1, n - 1))));
  for (size_t i = 0; i < n; ++i) {
    // VTK's Step space gives a segment the colour of its right node: jump right at its left end.
    if (i > 0 && step) out.push_back({x(i - 1), rgb(i).cast<float>()});
    if (i > 0 && !step && x(i) > x(i - 1))
      for (int k = 1; k < sub; ++k) {
        const double t = double(k) / sub;
        const Vec3d c = interpolateColor(rgb(i - 1), rgb(i), t, space);
        out.push_back({x(i - 1) + t * (x(i) - x(i - 1)), c.cast<float>()});
      }
    out.push_back({x(i), rgb(i).cast<float>()});
  }
  return out;
}

// vtkPiecewiseFunction's value between two nodes: s in [0,1] is the position along the segment,
// `mid` where the value is halfway, `sharp` from 0 (linear) to 1 (a step at the midpoint).
double vtkSegmentValue(double y1, double y2, double s, double mid, double sharp) {
  s = s < mid ? 0.5 * s / mid : 0.5 + 0.5 * (s - mid) / (1.0 - mid);
  if (sharp > 0.99) return s < 0.5 ? y1 : y2;
  if (sharp < 0.01) return (1 - s) * y1 + s * y2;
  if (s < 0.5)
    s = 0.5 * std::pow(s * 2.0, 1.0 + 10.0 * sharp);
  else if (s > 0.5)
    s = 1.0 - 0.5 * std::pow((1.0 - s) * 2.0, 1.0 + 10.0 * sharp);
  const double ss = s * s, sss = ss * s;
  const double h1 = 2 * sss - 3 * ss + 1, h2 = -2 * sss + 3 * ss, h3 = sss - 2 * ss + s,
               h4 = sss - ss;
  const double t = (1.0 - sharp) * (y2 - y1);
  return std::clamp(h1 * y1 + h2 * y2 + h3 * t + h4 * t, std::min(y1, y2), std::max(y1, y2));
}

std::vector<OpacityPoint> opacityPoints(const nlohmann::json& preset, const std::string& where) {
  const auto v = numbers(preset, "Points", 4, where);
  const size_t n = v.size() / 4;
  const double first = v[0], last = v[4 * (n - 1)];
  auto x = [&](size_t i) { return rescale(v[4 * i], first, last); };
  auto a = [&](size_t i) { return v[4 * i + 1]; };
  std::vector<OpacityPoint> out;
  for (size_t i = 0; i < n; ++i) {
    if (i > 0 && x(i) > x(i - 1)) {
      // The midpoint and sharpness of node i-1 shape the segment to node i (VTK clamps them so).
      const double mid = std::clamp(v[4 * (i - 1) + 2], 0.00001, 0.99999);
      const double sharp = std::clamp(v[4 * (i - 1) + 3], 0.0, 1.0);
      const double x0 = x(i - 1), dx = x(i) - x0;
      if (sharp > 0.99) {  // a jump at the midpoint: two points, exact
        out.push_back({x0 + mid * dx, static_cast<float>(a(i - 1))});
        out.push_back({x0 + mid * dx, static_cast<float>(a(i))});
      } else if (sharp < 0.01) {  // two lines meeting halfway at the midpoint: exact
        if (mid != 0.5) out.push_back({x0 + mid * dx, static_cast<float>(0.5 * (a(i - 1) + a(i)))});
      } else {
        for (int k = 1; k < kCurveSamples; ++k) {
          const double s = double(k) / kCurveSamples;
          out.push_back(
              {x0 + s * dx, static_cast<float>(vtkSegmentValue(a(i - 1), a(i), s, mid, sharp))});
        }
      }
    }
    out.push_back({x(i), static_cast<float>(a(i))});
  }
  return out;
}

}  // namespace

bool isParaViewPreset(const nlohmann::json& doc) {
  const auto& first = doc.is_array() && !doc.empty() ? doc.front() : doc;
  return first.is_object() && (first.contains("RGBPoints") || first.contains("Points") ||
                               first.contains("ColorSpace") || first.contains("IndexedColors"));
}

TransferFunction paraViewPresetToTransferFunction(const nlohmann::json& doc,
                                                  const std::string& name,
                                                  const std::string& where) {
  const nlohmann::json* preset = nullptr;
  std::vector<std::string> names;
  const auto candidates = doc.is_array() ? doc : nlohmann::json::array({doc});
  for (const auto& p : candidates) {
    if (!p.is_object()) continue;
    const std::string n =
        p.contains("Name") && p["Name"].is_string() ? p["Name"].get<std::string>() : std::string();
    names.push_back(n);
    if (!preset && (name.empty() || n == name)) preset = &p;
  }
  if (!preset && !name.empty())  // a second chance, ignoring case
    for (const auto& p : candidates)
      if (p.is_object() && p.contains("Name") && p["Name"].is_string() &&
          lower(p["Name"].get<std::string>()) == lower(name)) {
        preset = &p;
        break;
      }
  if (!preset) {
    std::string list;
    for (size_t i = 0; i < names.size() && i < 20; ++i) list += (i ? ", '" : "'") + names[i] + "'";
    if (names.size() > 20) list += ", ...";
    throw Error(
        where + ": no preset named '" + name + "'" +
        (names.empty() ? std::string(" (the file holds no presets)") : "; the file has " + list));
  }
  const std::string at =
      where + (preset->contains("Name") ? " preset " + (*preset)["Name"].dump() : "");
  TransferFunction tf;
  tf.space = TfSpace::Normalized;
  if (preset->contains("RGBPoints")) tf.color = colorPoints(*preset, at);
  if (preset->contains("Points")) tf.opacity = opacityPoints(*preset, at);
  if (tf.color.empty() && tf.opacity.empty())
    throw Error(at + ": has neither \"RGBPoints\" (colours) nor \"Points\" (opacities)" +
                (preset->contains("IndexedColors")
                     ? std::string("; categorical (IndexedColors) presets are not supported")
                     : std::string()));
  return tf;
}

}  // namespace mfadvr
