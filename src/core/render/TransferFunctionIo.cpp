// The user-facing forms of a transfer function: presets, inline points, our JSON format and
// ParaView preset exports, and the rules that combine an opacity spec with a colour spec.
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/render/ParaViewPreset.h"
#include "core/render/TransferFunction.h"
#include "core/render/TransferFunctionPresets.h"
#include "core/util/AtomicFile.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* spaceName(TfSpace s) {
  return s == TfSpace::Normalized ? "normalized" : "data";
}

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + v[i];
  return out;
}

std::string opacityForms() {
  return "expected an opacity preset (" + join(opacityPresetNames()) +
         "), a whole transfer-function preset (" + join(transferFunctionPresetNames()) +
         "), inline points 'x:a,x:a,...' (x normalized: 0 = data min, 1 = data max), or a JSON "
         "file (ours or a ParaView preset export)";
}

std::string colorForms() {
  return "expected a colour-map preset (" + join(colorMapPresetNames()) +
         "), the colours of a transfer-function preset (" + join(transferFunctionPresetNames()) +
         "), inline points 'x:r:g:b,...' (x normalized, r, g, b in [0,1]), or a JSON file (ours "
         "or a ParaView preset export, 'file.json#Name' to pick one preset)";
}

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

bool parseDouble(const std::string& t, double& v) {
  const char* b = t.data() + (!t.empty() && t.front() == '+' ? 1 : 0);
  const auto r = std::from_chars(b, t.data() + t.size(), v);
  return b != t.data() + t.size() && r.ec == std::errc() && r.ptr == t.data() + t.size() &&
         std::isfinite(v);
}

std::vector<std::string> split(std::string_view s, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t end = s.find(sep, start);
    out.push_back(trim(s.substr(start, end == std::string_view::npos ? end : end - start)));
    if (end == std::string_view::npos) return out;
    start = end + 1;
  }
}

// Inline points "x:v:v,x:v:v,..." with `values` numbers after each x.
std::vector<std::vector<double>> parseInline(const std::string& spec, size_t values,
                                             const std::string& what, const char* itemForm) {
  std::vector<std::vector<double>> out;
  const auto items = split(spec, ',');
  for (size_t i = 0; i < items.size(); ++i) {
    const auto fields = split(items[i], ':');
    std::vector<double> v(fields.size());
    bool ok = fields.size() == values + 1;
    for (size_t k = 0; ok && k < fields.size(); ++k) ok = parseDouble(fields[k], v[k]);
    if (!ok)
      throw Error(what + " '" + spec + "': point " + std::to_string(i + 1) + " '" + items[i] +
                  "' is not " + itemForm + " (finite numbers separated by ':', points by ',')");
    out.push_back(std::move(v));
  }
  return out;
}

// "file.json#Name" selects a preset inside a ParaView export; a path that exists as given wins.
std::pair<std::string, std::string> splitPresetName(const std::string& spec) {
  const size_t hash = spec.rfind('#');
  if (hash == std::string::npos || fs::exists(spec)) return {spec, ""};
  return {spec.substr(0, hash), spec.substr(hash + 1)};
}

bool looksLikeJsonFile(const std::string& spec) {
  std::string l = spec;
  for (char& c : l) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto p = l.rfind(".json");
  return p != std::string::npos && (p + 5 == l.size() || l[p + 5] == '#');
}

bool looksLikeNumber(const std::string& spec) {
  return !spec.empty() && (std::isdigit(static_cast<unsigned char>(spec[0])) || spec[0] == '-' ||
                           spec[0] == '+' || spec[0] == '.');
}

double numberAt(const json& v, const std::string& where) {
  if (!v.is_number()) throw Error(where + " must be a number, not " + v.dump());
  return v.get<double>();
}

TfSpace parseSpace(const json& v, const std::string& where) {
  if (v == "normalized") return TfSpace::Normalized;
  if (v == "data") return TfSpace::Data;
  throw Error(where +
              " must be \"normalized\" (fractions of the data range) or \"data\" (data "
              "values), not " +
              v.dump());
}

TransferFunction fromOurJson(const json& doc, const std::string& where) {
  if (!doc.is_object())
    throw Error(where +
                ": expected a JSON object with \"color\" and/or \"opacity\" lists, or a "
                "ParaView preset export (an array of presets with \"RGBPoints\")");
  static const char* const kKeys[] = {"space",         "color", "opacity",     "unit_distance",
                                      "color_x_space", "name",  "description", "comment"};
  for (const auto& [key, value] : doc.items())
    if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys))
      throw Error(where + ": unknown key \"" + key +
                  "\"; known keys: space, color, opacity, unit_distance, color_x_space, name, "
                  "description, comment");
  TransferFunction tf;
  if (doc.contains("space")) tf.space = parseSpace(doc["space"], where + ": \"space\"");
  if (doc.contains("color_x_space")) {
    const TfSpace s = parseSpace(doc["color_x_space"], where + ": \"color_x_space\"");
    if (s != tf.space) tf.colorSpace = s;
  }
  if (doc.contains("unit_distance"))
    tf.unitDistance = numberAt(doc["unit_distance"], where + ": \"unit_distance\"");
  auto list = [&](const char* key, size_t width, const char* form) {
    std::vector<std::vector<double>> out;
    if (!doc.contains(key)) return out;
    const auto& a = doc[key];
    if (!a.is_array())
      throw Error(where + ": \"" + key + "\" must be an array of " + form + " points");
    for (size_t i = 0; i < a.size(); ++i) {
      const std::string at = where + ": " + key + "[" + std::to_string(i) + "]";
      if (!a[i].is_array() || a[i].size() != width)
        throw Error(at + " must be " + form + ", not " + a[i].dump());
      std::vector<double> v;
      for (const auto& n : a[i]) v.push_back(numberAt(n, at));
      out.push_back(std::move(v));
    }
    return out;
  };
  for (const auto& v : list("color", 4, "[x, r, g, b]"))
    tf.color.push_back({v[0], Vec3f(float(v[1]), float(v[2]), float(v[3]))});
  for (const auto& v : list("opacity", 2, "[x, a]"))
    tf.opacity.push_back({v[0], static_cast<float>(v[1])});
  if (tf.color.empty() && tf.opacity.empty())
    throw Error(where +
                ": has neither a \"color\" nor an \"opacity\" list (at least one, "
                "non-empty, is needed)");
  return tf;
}

// One of the two lists, with the space its x live in.
template <typename Point>
struct Part {
  std::vector<Point> points;
  TfSpace space = TfSpace::Normalized;
  double unitDistance = 0.0;
  std::optional<TransferFunction> file;  // the whole file when the part came from one
};

// Checks one list alone, so that the message names the spec it came from.
template <typename Point>
void validatePart(const Part<Point>& part, const std::string& what, const std::string& spec) {
  TransferFunction tf;
  if constexpr (std::is_same_v<Point, ColorPoint>) {
    tf.color = part.points;
    tf.opacity = {{0.0, 0.0f}};
  } else {
    tf.opacity = part.points;
    tf.color = {{0.0, Vec3f(0, 0, 0)}};
  }
  tf.unitDistance = part.unitDistance;
  try {
    tf.validate();
  } catch (const Error& e) {
    throw Error(what + " '" + spec + "': " + e.what());
  }
}

Part<OpacityPoint> parseOpacity(const std::string& spec) {
  Part<OpacityPoint> part;
  const std::string s = spec.empty() ? "ramp" : trim(spec);
  if (!looksLikeJsonFile(s)) {
    // A whole preset acts as a file with both lists: its colours apply unless a colour map
    // is given.
    if (auto whole = findTransferFunctionPreset(s)) {
      part.file = *whole;
      part.points = whole->opacity;
      part.space = whole->space;
      return part;
    }
    if (auto preset = findOpacityPreset(s)) {
      part.points = *preset;
      return part;
    }
    if (looksLikeNumber(s)) {
      for (const auto& v : parseInline(s, 1, "opacity", "x:a"))
        part.points.push_back({v[0], static_cast<float>(v[1])});
      validatePart(part, "opacity", s);
      return part;
    }
    if (!fs::exists(splitPresetName(s).first))
      throw Error("opacity '" + s + "' is neither a preset, inline points nor an existing file; " +
                  opacityForms());
  }
  part.file = loadTransferFunctionJson(s);
  if (part.file->opacity.empty())
    throw Error("opacity file '" + s +
                "' has no opacity points (our \"opacity\" list or ParaView's \"Points\"); it is "
                "only a colour map: pass it as the colour map instead");
  part.points = part.file->opacity;
  part.space = part.file->space;
  part.unitDistance = part.file->unitDistance;
  validatePart(part, "opacity", s);
  return part;
}

Part<ColorPoint> parseColor(const std::string& spec) {
  Part<ColorPoint> part;
  const std::string s = trim(spec);
  if (!looksLikeJsonFile(s)) {
    if (auto whole = findTransferFunctionPreset(s)) {
      part.points = whole->color;
      part.space = whole->colorPointSpace();
      return part;
    }
    if (auto preset = findColorMapPreset(s)) {
      part.points = *preset;
      return part;
    }
    if (looksLikeNumber(s)) {
      for (const auto& v : parseInline(s, 3, "colour map", "x:r:g:b"))
        part.points.push_back({v[0], Vec3f(float(v[1]), float(v[2]), float(v[3]))});
      validatePart(part, "colour map", s);
      return part;
    }
    if (!fs::exists(splitPresetName(s).first))
      throw Error("colour map '" + s + "' is neither a preset, inline points nor an existing " +
                  "file; " + colorForms());
  }
  part.file = loadTransferFunctionJson(s);
  if (part.file->color.empty())
    throw Error("colour-map file '" + s +
                "' has no colours (our \"color\" list or ParaView's \"RGBPoints\")");
  part.points = part.file->color;
  part.space = part.file->colorPointSpace();
  part.unitDistance = part.file->unitDistance;
  validatePart(part, "colour map", s);
  return part;
}

}  // namespace

TransferFunction loadTransferFunctionJson(const std::string& spec) {
  const auto [path, name] = splitPresetName(spec);
  const std::string where = "transfer function file '" + path + "'";
  if (!fs::exists(path)) throw Error(where + ": no such file");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw Error(where + ": cannot read it");
  json doc;
  try {
    doc = json::parse(text.str());
  } catch (const json::exception& e) {
    throw Error(where + ": not valid JSON (" + e.what() + ")");
  }
  if (isParaViewPreset(doc)) return paraViewPresetToTransferFunction(doc, name, where);
  if (!name.empty())
    throw Error(where + ": '#" + name +
                "' picks a preset in a ParaView preset export, but this file is not one");
  return fromOurJson(doc, where);
}

json transferFunctionToJson(const TransferFunction& tf) {
  json out = {{"space", spaceName(tf.space)}};
  if (tf.colorPointSpace() != tf.space) out["color_x_space"] = spaceName(tf.colorPointSpace());
  if (!tf.color.empty()) {
    json c = json::array();
    for (const auto& p : tf.color) c.push_back({p.x, p.rgb.x(), p.rgb.y(), p.rgb.z()});
    out["color"] = std::move(c);
  }
  if (!tf.opacity.empty()) {
    json o = json::array();
    for (const auto& p : tf.opacity) o.push_back({p.x, p.alpha});
    out["opacity"] = std::move(o);
  }
  if (tf.unitDistance != 0.0) out["unit_distance"] = tf.unitDistance;
  return out;
}

void saveTransferFunctionJson(const TransferFunction& tf, const std::string& path) {
  writeFileAtomically(path, transferFunctionToJson(tf).dump(2) + "\n");
}

TransferFunction parseTransferFunction(const std::string& opacitySpec,
                                       const std::string& colorSpec) {
  const auto opacity = parseOpacity(opacitySpec);
  Part<ColorPoint> color;
  if (!trim(colorSpec).empty()) {
    color = parseColor(colorSpec);
  } else if (opacity.file && !opacity.file->color.empty()) {
    color.points = opacity.file->color;
    color.space = opacity.file->colorPointSpace();
  } else {
    color.points = *findColorMapPreset("cool-to-warm");  // ParaView's default
  }
  TransferFunction tf;
  tf.space = opacity.space;
  tf.opacity = opacity.points;
  tf.color = std::move(color.points);
  if (color.space != tf.space) tf.colorSpace = color.space;
  // The opacity's unit distance first: it is a property of the opacities.
  tf.unitDistance = opacity.unitDistance != 0.0 ? opacity.unitDistance : color.unitDistance;
  tf.validate();
  return tf;
}

}  // namespace mfadvr
