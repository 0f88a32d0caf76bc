#include "core/render/TransferFunction2D.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/image/PngFile.h"
#include "core/util/Error.h"

namespace mfadvr {

namespace {

using nlohmann::json;

// Table sizes beyond this are refused: 4096 x 4096 entries of 32 bytes is 512 MB already.
constexpr int kMaxSide = 4096;

void checkRange(double lo, double hi, const std::string& what) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && hi > lo))
    throw Error("2-D transfer function: the " + what + " axis needs finite ends LO < HI, got " +
                std::to_string(lo) + ", " + std::to_string(hi));
}

std::pair<double, double> numberPair(const json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    throw Error(where + ": expected [LO, HI]");
  const double lo = v[0].get<double>(), hi = v[1].get<double>();
  if (!(std::isfinite(lo) && std::isfinite(hi) && hi >= lo))
    throw Error(where + ": expected finite LO <= HI");
  return {lo, hi};
}

struct Box {
  double v0, v1, g0, g1;
  float rgba[4];
};

}  // namespace

void TransferFunction2D::validate() const {
  if (width < 2 || height < 2 || width > kMaxSide || height > kMaxSide)
    throw Error("2-D transfer function: the table must be 2 to " + std::to_string(kMaxSide) +
                " entries along each axis, got " + std::to_string(width) + " x " +
                std::to_string(height));
  if (rgba.size() != static_cast<size_t>(width) * height * 4)
    throw Error("2-D transfer function: " + std::to_string(rgba.size()) + " floats for " +
                std::to_string(width) + " x " + std::to_string(height) + " RGBA entries");
  for (float x : rgba)
    if (!(x >= 0.0f && x <= 1.0f))
      throw Error("2-D transfer function: colours and opacities must lie in [0, 1]");
  checkRange(valueLo, valueHi, "value");
  checkRange(gradientLo, gradientHi, "gradient");
  if (gradientLo < 0.0)
    throw Error("2-D transfer function: the gradient axis starts below 0 (|grad f| >= 0)");
}

TransferFunction2D transferFunction2DFromImage(const Image8& image,
                                               const TransferFunction2DRange& range) {
  checkImage8(image, "2-D transfer function image");
  TransferFunction2D tf;
  tf.width = image.width;
  tf.height = image.height;
  tf.valueLo = range.valueLo;
  tf.valueHi = range.valueHi;
  tf.gradientLo = range.gradientLo;
  tf.gradientHi = range.gradientHi;
  tf.rgba.resize(static_cast<size_t>(tf.width) * tf.height * 4);
  const int c = image.channels;
  for (int j = 0; j < tf.height; ++j) {
    const int row = tf.height - 1 - j;  // the image's bottom row is the low gradient end
    for (int i = 0; i < tf.width; ++i) {
      const std::uint8_t* p = &image.data[(static_cast<size_t>(row) * tf.width + i) * c];
      float* e = &tf.rgba[(static_cast<size_t>(j) * tf.width + i) * 4];
      for (int k = 0; k < 3; ++k) e[k] = p[k] / 255.0f;
      e[3] = c == 4 ? p[3] / 255.0f : 1.0f;
    }
  }
  tf.validate();
  return tf;
}

TransferFunction2D parseTransferFunction2DJson(const std::string& text, const std::string& where) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(where + ": not valid JSON (" + e.what() + ")");
  }
  if (!doc.is_object() || !doc.contains("boxes") || !doc["boxes"].is_array() ||
      doc["boxes"].empty())
    throw Error(where +
                ": expected {\"boxes\": [{\"value\": [LO, HI], \"gradient\": [LO, HI], "
                "\"color\": [R, G, B], \"opacity\": A}, ...]}");
  int width = 256, height = 128;
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
    for (const char* key : {"value", "gradient", "opacity"})
      if (!j.contains(key)) throw Error(at + ": needs \"" + std::string(key) + "\"");
    Box box;
    std::tie(box.v0, box.v1) = numberPair(j["value"], at + " \"value\"");
    std::tie(box.g0, box.g1) = numberPair(j["gradient"], at + " \"gradient\"");
    if (box.g0 < 0.0) throw Error(at + ": |grad f| is >= 0; \"gradient\" starts below 0");
    if (!j["opacity"].is_number()) throw Error(at + ": \"opacity\" must be a number");
    box.rgba[3] = j["opacity"].get<float>();
    box.rgba[0] = box.rgba[1] = box.rgba[2] = 1.0f;
    if (j.contains("color")) {
      const json& c = j["color"];
      if (!c.is_array() || c.size() != 3)
        throw Error(at + ": \"color\" must be [R, G, B] in [0, 1]");
      for (int k = 0; k < 3; ++k) {
        if (!c[k].is_number()) throw Error(at + ": \"color\" must be [R, G, B] in [0, 1]");
        box.rgba[k] = c[k].get<float>();
      }
    }
    for (float x : box.rgba)
      if (!(x >= 0.0f && x <= 1.0f)) throw Error(at + ": colour and opacity must lie in [0, 1]");
    boxes.push_back(box);
  }
  // The table spans the boxes with one transparent entry beyond them on every side (the
  // gradient axis from 0), so that the edge clamp reads "outside every box" there.
  double v0 = boxes[0].v0, v1 = boxes[0].v1, g1 = boxes[0].g1;
  for (const Box& b : boxes) {
    v0 = std::min(v0, b.v0);
    v1 = std::max(v1, b.v1);
    g1 = std::max(g1, b.g1);
  }
  if (!(v1 > v0)) v1 = v0 + std::max(1.0, std::abs(v0)) * 1e-6;
  if (!(g1 > 0.0)) g1 = 1e-6;
  TransferFunction2D tf;
  tf.width = width;
  tf.height = height;
  const double dv = (v1 - v0) / (width - 3), dg = g1 / (height - 2);
  tf.valueLo = v0 - dv;
  tf.valueHi = v1 + dv;
  tf.gradientLo = 0.0;
  tf.gradientHi = g1 + dg;
  tf.rgba.assign(static_cast<size_t>(width) * height * 4, 0.0f);
  for (int j = 0; j < height; ++j) {
    const double g = tf.gradientLo + (tf.gradientHi - tf.gradientLo) * j / (height - 1);
    for (int i = 0; i < width; ++i) {
      const double v = tf.valueLo + (tf.valueHi - tf.valueLo) * i / (width - 1);
      float* e = &tf.rgba[(static_cast<size_t>(j) * width + i) * 4];
      for (const Box& b : boxes)
        if (v >= b.v0 && v <= b.v1 && g >= b.g0 && g <= b.g1) std::copy_n(b.rgba, 4, e);
    }
  }
  tf.validate();
  return tf;
}

TransferFunction2D readTransferFunction2D(const std::string& path,
                                          const TransferFunction2DRange* range) {
  namespace fs = std::filesystem;
  const std::string where = "2-D transfer function '" + path + "'";
  if (!fs::exists(path)) throw Error(where + ": no such file");
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".png") {
    if (!range) throw Error(where + ": a PNG table needs the ends of its axes (--tf2d-range)");
    return transferFunction2DFromImage(readPng(path), *range);
  }
  if (ext == ".json") {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (!in) throw Error(where + ": cannot read it");
    return parseTransferFunction2DJson(text.str(), where);
  }
  throw Error(where + ": expected a .png image or a .json file of boxes");
}

}  // namespace mfadvr
