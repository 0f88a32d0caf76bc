#include "core/render/CurvatureTransferFunction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {

namespace {

using nlohmann::json;

constexpr int kMaxSide = 4096;
// Presets: 256 x 256 entries over [-2K, 2K] on both axes (their colours are full at K).
constexpr int kPresetSide = 256;

using Rgb = std::array<float, 3>;
// The ends of the presets' diverging maps (cool-to-warm's ends, ParaView's default map).
constexpr Rgb kBlue = {0.230f, 0.299f, 0.754f}, kRed = {0.706f, 0.016f, 0.150f};
constexpr Rgb kWhite = {0.865f, 0.865f, 0.865f};
constexpr Rgb kGreen = {0.10f, 0.60f, 0.20f}, kOrange = {0.95f, 0.50f, 0.10f};

double smoothRamp(double x, double lo, double hi) {
  const double t = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

Rgb mix(const Rgb& a, const Rgb& b, double t) {
  Rgb c;
  for (int i = 0; i < 3; ++i) c[i] = static_cast<float>(a[i] + (b[i] - a[i]) * t);
  return c;
}

// A diverging map over t in [-1, 1]: low, white, high.
Rgb diverging(double t, const Rgb& low, const Rgb& high) {
  t = std::clamp(t, -1.0, 1.0);
  return t < 0.0 ? mix(kWhite, low, -t) : mix(kWhite, high, t);
}

std::pair<double, double> numberPair(const json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    throw Error(where + ": expected [LO, HI]");
  const double lo = v[0].get<double>(), hi = v[1].get<double>();
  if (!(std::isfinite(lo) && std::isfinite(hi) && hi >= lo))
    throw Error(where + ": expected finite LO <= HI");
  return {lo, hi};
}

float unitNumber(const json& j, const char* key, float fallback, const std::string& at) {
  if (!j.contains(key)) return fallback;
  if (!j[key].is_number()) throw Error(at + ": \"" + key + "\" must be a number in [0, 1]");
  const float x = j[key].get<float>();
  if (!(x >= 0.0f && x <= 1.0f)) throw Error(at + ": \"" + key + "\" must lie in [0, 1]");
  return x;
}

struct Box {
  double k1Lo, k1Hi, k2Lo, k2Hi;
  float entry[5];
};

}  // namespace

void CurvatureTransferFunction::validate() const {
  if (width < 2 || height < 2 || width > kMaxSide || height > kMaxSide)
    throw Error("curvature transfer function: the table must be 2 to " + std::to_string(kMaxSide) +
                " entries along each axis, got " + std::to_string(width) + " x " +
                std::to_string(height));
  if (entries.size() != static_cast<size_t>(width) * height * 5)
    throw Error("curvature transfer function: " + std::to_string(entries.size()) + " floats for " +
                std::to_string(width) + " x " + std::to_string(height) + " entries of 5");
  for (float x : entries)
    if (!(x >= 0.0f && x <= 1.0f))
      throw Error(
          "curvature transfer function: colours, weights and opacities must lie in "
          "[0, 1]");
  for (auto [lo, hi, axis] : {std::tuple{k1Lo, k1Hi, "k1"}, std::tuple{k2Lo, k2Hi, "k2"}})
    if (!(std::isfinite(lo) && std::isfinite(hi) && hi > lo))
      throw Error(std::string("curvature transfer function: the ") + axis +
                  " axis needs finite ends LO < HI");
}

std::string curvaturePresetNames() {
  return "ridges-valleys, mean, gaussian";
}

CurvatureTransferFunction curvaturePreset(const std::string& name, double k) {
  if (!(k > 0.0) || !std::isfinite(k))
    throw Error("curvature preset '" + name + "': the curvature scale K must be positive");
  if (name != "ridges-valleys" && name != "mean" && name != "gaussian")
    throw Error("unknown curvature transfer function '" + name +
                "' (presets: " + curvaturePresetNames() + ", or a .json file of boxes)");
  CurvatureTransferFunction tf;
  tf.width = tf.height = kPresetSide;
  tf.k1Lo = tf.k2Lo = -2.0 * k;
  tf.k1Hi = tf.k2Hi = 2.0 * k;
  tf.entries.resize(static_cast<size_t>(kPresetSide) * kPresetSide * 5);
  for (int j = 0; j < kPresetSide; ++j) {
    const double k2 = tf.k2Lo + (tf.k2Hi - tf.k2Lo) * j / (kPresetSide - 1);
    for (int i = 0; i < kPresetSide; ++i) {
      const double k1 = tf.k1Lo + (tf.k1Hi - tf.k1Lo) * i / (kPresetSide - 1);
      Rgb c = kWhite;
      double weight = 1.0;
      if (name == "mean") {
        c = diverging(0.5 * (k1 + k2) / k, kBlue, kRed);
      } else if (name == "gaussian") {
        c = diverging(k1 * k2 / (k * k), kGreen, kOrange);
      } else {
        const double ridge = smoothRamp(k1, 0.25 * k, k), valley = smoothRamp(-k2, 0.25 * k, k);
        weight = std::max(ridge, valley);
        if (ridge + valley > 0.0) c = mix(kOrange, kBlue, valley / (ridge + valley));
      }
      float* e = &tf.entries[(static_cast<size_t>(j) * kPresetSide + i) * 5];
      std::copy(c.begin(), c.end(), e);
      e[3] = static_cast<float>(weight);
      e[4] = 1.0f;
    }
  }
  tf.validate();
  return tf;
}

CurvatureTransferFunction parseCurvatureTransferFunctionJson(const std::string& text,
                                                             const std::string& where) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(where + ": not valid JSON (" + e.what() + ")");
  }
  if (!doc.is_object() || !doc.contains("boxes") || !doc["boxes"].is_array() ||
      doc["boxes"].empty())
    throw Error(where +
                ": expected {\"boxes\": [{\"k1\": [LO, HI], \"k2\": [LO, HI], \"color\": [R, G, "
                "B], \"weight\": W, \"opacity\": A}, ...]}");
  int width = 256, height = 256;
  if (doc.contains("size")) {
    const json& s = doc["size"];
    if (!s.is_array() || s.size() != 2 || !s[0].is_number_integer() || !s[1].is_number_integer())
      throw Error(where + ": \"size\" must be [W, H], whole numbers");
    width = s[0].get<int>();
    height = s[1].get<int>();
    if (width < 4 || height < 4 || width > kMaxSide || height > kMaxSide)
      throw Error(where + ": \"size\" must lie in 4 .. " + std::to_string(kMaxSide));
  }
  std::vector<Box> boxes;
  for (size_t b = 0; b < doc["boxes"].size(); ++b) {
    const json& j = doc["boxes"][b];
    const std::string at = where + ": box " + std::to_string(b + 1);
    if (!j.is_object()) throw Error(at + ": expected an object");
    for (const char* key : {"k1", "k2"})
      if (!j.contains(key)) throw Error(at + ": needs \"" + std::string(key) + "\"");
    Box box;
    std::tie(box.k1Lo, box.k1Hi) = numberPair(j["k1"], at + " \"k1\"");
    std::tie(box.k2Lo, box.k2Hi) = numberPair(j["k2"], at + " \"k2\"");
    std::fill_n(box.entry, 3, 1.0f);
    if (j.contains("color")) {
      const json& c = j["color"];
      if (!c.is_array() || c.size() != 3)
        throw Error(at + ": \"color\" must be [R, G, B] in [0, 1]");
      for (int k = 0; k < 3; ++k) {
        if (!c[k].is_number()) throw Error(at + ": \"color\" must be [R, G, B] in [0, 1]");
        box.entry[k] = c[k].get<float>();
        if (!(box.entry[k] >= 0.0f && box.entry[k] <= 1.0f))
          throw Error(at + ": \"color\" must be [R, G, B] in [0, 1]");
      }
    }
    box.entry[3] = unitNumber(j, "weight", 1.0f, at);
    box.entry[4] = unitNumber(j, "opacity", 1.0f, at);
    boxes.push_back(box);
  }
  // The table spans the boxes with one entry beyond them on every side, so that the edge clamp
  // reads "outside every box" there (weight 0, opacity 1: the sample unchanged).
  double a0 = boxes[0].k1Lo, a1 = boxes[0].k1Hi, b0 = boxes[0].k2Lo, b1 = boxes[0].k2Hi;
  for (const Box& b : boxes) {
    a0 = std::min(a0, b.k1Lo);
    a1 = std::max(a1, b.k1Hi);
    b0 = std::min(b0, b.k2Lo);
    b1 = std::max(b1, b.k2Hi);
  }
  auto widen = [](double lo, double& hi) {
    if (!(hi > lo)) hi = lo + std::max(1.0, std::abs(lo)) * 1e-6;
  };
  widen(a0, a1);
  widen(b0, b1);
  CurvatureTransferFunction tf;
  tf.width = width;
  tf.height = height;
  const double da = (a1 - a0) / (width - 3), db = (b1 - b0) / (height - 3);
  tf.k1Lo = a0 - da;
  tf.k1Hi = a1 + da;
  tf.k2Lo = b0 - db;
  tf.k2Hi = b1 + db;
  if (!(std::isfinite(tf.k1Lo) && std::isfinite(tf.k1Hi) && std::isfinite(tf.k2Lo) &&
        std::isfinite(tf.k2Hi)))
    throw Error(where + ": the boxes' curvatures are too large");
  tf.entries.resize(static_cast<size_t>(width) * height * 5);
  for (int j = 0; j < height; ++j) {
    const double k2 = tf.k2Lo + (tf.k2Hi - tf.k2Lo) * j / (height - 1);
    for (int i = 0; i < width; ++i) {
      const double k1 = tf.k1Lo + (tf.k1Hi - tf.k1Lo) * i / (width - 1);
      float* e = &tf.entries[(static_cast<size_t>(j) * width + i) * 5];
      const float unchanged[5] = {1.0f, 1.0f, 1.0f, 0.0f, 1.0f};
      std::copy_n(unchanged, 5, e);
      for (const Box& b : boxes)
        if (k1 >= b.k1Lo && k1 <= b.k1Hi && k2 >= b.k2Lo && k2 <= b.k2Hi)
          std::copy_n(b.entry, 5, e);
    }
  }
  tf.validate();
  return tf;
}

CurvatureTransferFunction readCurvatureTransferFunction(const std::string& spec, double defaultK) {
  namespace fs = std::filesystem;
  std::string ext = fs::path(spec).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".json") {
    const std::string where = "curvature transfer function '" + spec + "'";
    if (!fs::exists(spec)) throw Error(where + ": no such file");
    std::ifstream in(spec, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (!in) throw Error(where + ": cannot read it");
    return parseCurvatureTransferFunctionJson(text.str(), where);
  }
  const auto colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  double k = defaultK;
  if (colon != std::string::npos) {
    const std::string number = spec.substr(colon + 1);
    char* end = nullptr;
    k = std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size() || !(k > 0.0) || !std::isfinite(k))
      throw Error("curvature transfer function '" + spec +
                  "': K after the colon must be a positive number (1 / world units)");
  }
  return curvaturePreset(name, k);
}

}  // namespace mfadvr
