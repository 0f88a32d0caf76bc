#include "core/render/TransferFunctionPresets.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

// Colour maps sampled at x = i/32, i = 0..32, from matplotlib 3.6 (each map's 256-entry table,
// interpolated linearly): "coolwarm" is Moreland's diverging Cool to Warm map (ParaView's
// default; endpoints (0.230, 0.299, 0.754) and (0.706, 0.016, 0.150), interpolated in Msh space),
// "viridis" and "inferno" are van der Walt and Smith's maps (CC0). With 33 points the largest
// deviation from matplotlib's 256-entry tables is 0.2/255 (coolwarm) and 1.6/255 (viridis,
// inferno) in any channel: below what the eye sees in a volume rendering.
constexpr int kSamples = 33;
constexpr float kCoolToWarm[kSamples][3] = {
    {0.2298f, 0.2987f, 0.7537f}, {0.2662f, 0.3531f, 0.8015f}, {0.3039f, 0.4065f, 0.8449f},
    {0.3428f, 0.4587f, 0.8837f}, {0.3830f, 0.5094f, 0.9173f}, {0.4244f, 0.5581f, 0.9455f},
    {0.4667f, 0.6045f, 0.9680f}, {0.5096f, 0.6482f, 0.9847f}, {0.5530f, 0.6888f, 0.9952f},
    {0.5963f, 0.7261f, 0.9997f}, {0.6392f, 0.7595f, 0.9980f}, {0.6813f, 0.7888f, 0.9902f},
    {0.7221f, 0.8138f, 0.9764f}, {0.7614f, 0.8342f, 0.9568f}, {0.7986f, 0.8496f, 0.9315f},
    {0.8334f, 0.8600f, 0.9009f}, {0.8654f, 0.8647f, 0.8651f}, {0.8976f, 0.8488f, 0.8208f},
    {0.9239f, 0.8272f, 0.7745f}, {0.9443f, 0.8008f, 0.7267f}, {0.9587f, 0.7696f, 0.6780f},
    {0.9672f, 0.7340f, 0.6287f}, {0.9698f, 0.6942f, 0.5794f}, {0.9667f, 0.6503f, 0.5303f},
    {0.9579f, 0.6028f, 0.4818f}, {0.9435f, 0.5517f, 0.4343f}, {0.9238f, 0.4972f, 0.3880f},
    {0.8990f, 0.4395f, 0.3433f}, {0.8691f, 0.3783f, 0.3003f}, {0.8346f, 0.3128f, 0.2593f},
    {0.7956f, 0.2412f, 0.2205f}, {0.7525f, 0.1570f, 0.1841f}, {0.7057f, 0.0156f, 0.1502f},
};
constexpr float kViridis[kSamples][3] = {
    {0.2670f, 0.0049f, 0.3294f}, {0.2770f, 0.0502f, 0.3755f}, {0.2823f, 0.0946f, 0.4170f},
    {0.2829f, 0.1354f, 0.4530f}, {0.2789f, 0.1749f, 0.4830f}, {0.2708f, 0.2133f, 0.5066f},
    {0.2593f, 0.2507f, 0.5244f}, {0.2454f, 0.2867f, 0.5370f}, {0.2302f, 0.3213f, 0.5455f},
    {0.2148f, 0.3545f, 0.5510f}, {0.2000f, 0.3864f, 0.5545f}, {0.1861f, 0.4173f, 0.5567f},
    {0.1733f, 0.4474f, 0.5579f}, {0.1613f, 0.4770f, 0.5581f}, {0.1497f, 0.5064f, 0.5573f},
    {0.1384f, 0.5358f, 0.5551f}, {0.1281f, 0.5651f, 0.5509f}, {0.1209f, 0.5945f, 0.5442f},
    {0.1203f, 0.6238f, 0.5343f}, {0.1310f, 0.6529f, 0.5208f}, {0.1554f, 0.6815f, 0.5032f},
    {0.1930f, 0.7096f, 0.4812f}, {0.2415f, 0.7366f, 0.4545f}, {0.2986f, 0.7624f, 0.4230f},
    {0.3629f, 0.7867f, 0.3866f}, {0.4330f, 0.8091f, 0.3453f}, {0.5081f, 0.8292f, 0.2992f},
    {0.5873f, 0.8470f, 0.2489f}, {0.6694f, 0.8622f, 0.1954f}, {0.7529f, 0.8751f, 0.1427f},
    {0.8359f, 0.8861f, 0.1025f}, {0.9166f, 0.8961f, 0.1008f}, {0.9932f, 0.9062f, 0.1439f},
};
constexpr float kInferno[kSamples][3] = {
    {0.0015f, 0.0005f, 0.0139f}, {0.0139f, 0.0112f, 0.0716f}, {0.0420f, 0.0280f, 0.1406f},
    {0.0815f, 0.0432f, 0.2144f}, {0.1285f, 0.0473f, 0.2896f}, {0.1823f, 0.0405f, 0.3539f},
    {0.2370f, 0.0366f, 0.3956f}, {0.2894f, 0.0453f, 0.4182f}, {0.3399f, 0.0618f, 0.4292f},
    {0.3897f, 0.0803f, 0.4331f}, {0.4393f, 0.0986f, 0.4317f}, {0.4889f, 0.1164f, 0.4259f},
    {0.5386f, 0.1339f, 0.4157f}, {0.5882f, 0.1516f, 0.4011f}, {0.6375f, 0.1704f, 0.3822f},
    {0.6858f, 0.1910f, 0.3591f}, {0.7328f, 0.2143f, 0.3321f}, {0.7776f, 0.2414f, 0.3016f},
    {0.8195f, 0.2728f, 0.2685f}, {0.8578f, 0.3090f, 0.2333f}, {0.8918f, 0.3500f, 0.1965f},
    {0.9210f, 0.3954f, 0.1584f}, {0.9451f, 0.4448f, 0.1188f}, {0.9640f, 0.4974f, 0.0776f},
    {0.9774f, 0.5526f, 0.0380f}, {0.9855f, 0.6100f, 0.0245f}, {0.9879f, 0.6692f, 0.0596f},
    {0.9847f, 0.7296f, 0.1222f}, {0.9759f, 0.7909f, 0.1973f}, {0.9623f, 0.8522f, 0.2867f},
    {0.9486f, 0.9109f, 0.3962f}, {0.9518f, 0.9608f, 0.5247f}, {0.9884f, 0.9984f, 0.6449f},
};

std::vector<ColorPoint> sampled(const float (&rgb)[kSamples][3]) {
  std::vector<ColorPoint> out;
  for (int i = 0; i < kSamples; ++i)
    out.push_back({i / double(kSamples - 1), Vec3f(rgb[i][0], rgb[i][1], rgb[i][2])});
  return out;
}

// matplotlib's "jet" is piecewise linear per channel; these are all of its breakpoints, so the
// map is exact.
std::vector<ColorPoint> jet() {
  return {{0.0, {0.0f, 0.0f, 0.5f}},
          {0.11, {0.0f, 0.0f, 1.0f}},
          {0.125, {0.0f, 0.0f, 1.0f}},
          {0.34, {0.0f, 0.86f, 1.0f}},
          {0.35, {0.0f, 0.9f, 0.967742f}},
          {0.375, {0.0806452f, 1.0f, 0.887097f}},
          {0.64, {0.935484f, 1.0f, 0.0322581f}},
          {0.65, {0.967742f, 0.962963f, 0.0f}},
          {0.66, {1.0f, 0.925926f, 0.0f}},
          {0.89, {1.0f, 0.0740741f, 0.0f}},
          {0.91, {0.909091f, 0.0f, 0.0f}},
          {1.0, {0.5f, 0.0f, 0.0f}}};
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool parseDouble(std::string_view t, double& v) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  return !t.empty() && r.ec == std::errc() && r.ptr == t.data() + t.size() && std::isfinite(v);
}

std::vector<std::string_view> splitColons(std::string_view s) {
  std::vector<std::string_view> out;
  size_t start = 0;
  while (true) {
    const size_t end = s.find(':', start);
    out.push_back(s.substr(start, end == std::string_view::npos ? end : end - start));
    if (end == std::string_view::npos) return out;
    start = end + 1;
  }
}

}  // namespace

std::vector<std::string> colorMapPresetNames() {
  return {"cool-to-warm", "viridis", "inferno", "jet", "grayscale", "red", "white"};
}

std::vector<std::string> opacityPresetNames() {
  return {"ramp", "ramp:LO:HI", "step:ISO[:A]", "tent:CENTER:WIDTH[:A]", "constant:A"};
}

std::optional<std::vector<ColorPoint>> findColorMapPreset(std::string_view name) {
  const std::string n = lower(name);
  if (n == "cool-to-warm" || n == "cool to warm" || n == "coolwarm") return sampled(kCoolToWarm);
  if (n == "viridis" || n == "viridis (matplotlib)") return sampled(kViridis);
  if (n == "inferno" || n == "inferno (matplotlib)") return sampled(kInferno);
  if (n == "jet") return jet();
  if (n == "grayscale" || n == "greyscale" || n == "gray" || n == "grey")
    return std::vector<ColorPoint>{{0.0, Vec3f(0, 0, 0)}, {1.0, Vec3f(1, 1, 1)}};
  // One point: the same colour everywhere, for isosurface-like pictures lit by shading alone.
  if (n == "red") return std::vector<ColorPoint>{{0.0, Vec3f(1, 0, 0)}};
  if (n == "white") return std::vector<ColorPoint>{{0.0, Vec3f(1, 1, 1)}};
  return std::nullopt;
}

std::optional<std::vector<OpacityPoint>> findOpacityPreset(std::string_view spec) {
  const auto parts = splitColons(spec);
  const std::string name = lower(parts[0]);
  const char* form = nullptr;
  size_t minParams = 0, maxParams = 0;
  if (name == "ramp") {
    form = "ramp or ramp:LO:HI (opacity 0 at LO rising linearly to 1 at HI, LO < HI)";
    maxParams = 2;
  } else if (name == "step") {
    form = "step:ISO[:A] (opacity 0 below ISO, A (default 1) from ISO on)";
    minParams = 1;
    maxParams = 2;
  } else if (name == "tent") {
    form =
        "tent:CENTER:WIDTH[:A] (opacity rising from 0 at CENTER-WIDTH/2 to A (default 1) at "
        "CENTER and back to 0 at CENTER+WIDTH/2, WIDTH > 0)";
    minParams = 2;
    maxParams = 3;
  } else if (name == "constant") {
    form = "constant:A (opacity A everywhere)";
    minParams = maxParams = 1;
  } else {
    return std::nullopt;
  }
  const size_t count = parts.size() - 1;
  std::vector<double> p(count);
  bool ok = (count >= minParams && count <= maxParams) && !(name == "ramp" && count == 1);
  for (size_t i = 0; ok && i < count; ++i) ok = parseDouble(parts[i + 1], p[i]);
  // The last parameter of step, tent and constant is an opacity.
  const bool hasAlpha =
      (name == "step" && count == 2) || (name == "tent" && count == 3) || name == "constant";
  if (ok && hasAlpha) ok = p.back() >= 0.0 && p.back() <= 1.0;
  if (ok && name == "ramp" && count == 2) ok = p[0] < p[1];
  if (ok && name == "tent") ok = p[1] > 0.0;
  if (!ok)
    throw Error("opacity preset '" + std::string(spec) + "': expected " + form +
                "; values are finite numbers, x normalized to the data range (0 = min, 1 = max), "
                "opacities in [0,1]");

  if (name == "ramp") {
    const double lo = count ? p[0] : 0.0, hi = count ? p[1] : 1.0;
    return std::vector<OpacityPoint>{{lo, 0.0f}, {hi, 1.0f}};
  }
  if (name == "step") {
    const float a = count == 2 ? static_cast<float>(p[1]) : 1.0f;
    return std::vector<OpacityPoint>{{p[0], 0.0f}, {p[0], a}};
  }
  if (name == "tent") {
    const float a = count == 3 ? static_cast<float>(p[2]) : 1.0f;
    return std::vector<OpacityPoint>{
        {p[0] - 0.5 * p[1], 0.0f}, {p[0], a}, {p[0] + 0.5 * p[1], 0.0f}};
  }
  return std::vector<OpacityPoint>{{0.0, static_cast<float>(p[0])}};
}

}  // namespace mfadvr

namespace mfadvr {

// Medical presets. The CT values follow the standard Hounsfield scale (air -1000, fat about
// -100, water 0, soft tissue 20..80, contrast-filled vessels 150..500, bone 300..2000); the
// opacities are per the renderer's unit distance, so thin structures stay visible and large
// ones translucent at the default.
std::optional<TransferFunction> findTransferFunctionPreset(std::string_view name) {
  const std::string n = lower(name);
  TransferFunction tf;
  tf.space = TfSpace::Data;
  if (n == "ct-bone") {
    // Bone only: cortical bone nearly opaque, trabecular bone translucent, all else clear.
    tf.opacity = {{-1024, 0.0f}, {150, 0.0f},   {300, 0.15f},
                  {700, 0.55f},  {1500, 0.85f}, {3071, 0.9f}};
    tf.color = {{150, {0.55f, 0.25f, 0.15f}},
                {300, {0.85f, 0.70f, 0.50f}},
                {700, {0.95f, 0.90f, 0.80f}},
                {1500, {1.0f, 1.0f, 0.97f}}};
  } else if (n == "ct-skin") {
    // The skin surface: an opaque boundary where air turns into tissue (about -500 HU).
    tf.opacity = {{-1024, 0.0f}, {-600, 0.0f}, {-400, 0.6f}, {3071, 0.6f}};
    tf.color = {{-600, {0.75f, 0.50f, 0.40f}},
                {-200, {0.93f, 0.72f, 0.60f}},
                {200, {0.95f, 0.80f, 0.70f}},
                {600, {1.0f, 1.0f, 0.95f}}};
  } else if (n == "ct-soft-tissue") {
    // Fat faint yellow, muscle and organs translucent red, bone opaque ivory.
    tf.opacity = {{-1024, 0.0f}, {-150, 0.0f}, {-60, 0.03f}, {40, 0.12f},
                  {120, 0.05f},  {250, 0.05f}, {400, 0.6f},  {3071, 0.8f}};
    tf.color = {{-150, {0.90f, 0.80f, 0.45f}},
                {-60, {0.90f, 0.80f, 0.45f}},
                {40, {0.80f, 0.30f, 0.25f}},
                {120, {0.90f, 0.50f, 0.40f}},
                {400, {1.0f, 0.95f, 0.85f}}};
  } else if (n == "ct-vessels") {
    // CT angiography: contrast-filled vessels (about 200..500 HU) red, bone dim for context.
    tf.opacity = {{-1024, 0.0f}, {100, 0.0f},  {180, 0.3f}, {350, 0.6f},
                  {500, 0.45f},  {800, 0.15f}, {3071, 0.2f}};
    tf.color = {{100, {0.50f, 0.05f, 0.05f}},
                {200, {0.85f, 0.15f, 0.10f}},
                {350, {1.0f, 0.35f, 0.25f}},
                {600, {1.0f, 0.90f, 0.80f}},
                {3071, {1.0f, 1.0f, 1.0f}}};
  } else if (n == "mr-tissue") {
    // T1/T2 anatomy: the dark background and noise clear, brighter tissue increasingly opaque.
    tf.space = TfSpace::Normalized;
    tf.opacity = {{0.0, 0.0f}, {0.08, 0.0f}, {0.2, 0.05f}, {0.5, 0.3f}, {1.0, 0.6f}};
    tf.color = {
        {0.08, {0.30f, 0.20f, 0.15f}}, {0.4, {0.80f, 0.60f, 0.50f}}, {1.0, {1.0f, 0.95f, 0.90f}}};
  } else if (n == "mr-vessels") {
    // MR angiography (time of flight, contrast): vessels are the brightest third of the range.
    tf.space = TfSpace::Normalized;
    tf.opacity = {{0.0, 0.0f}, {0.35, 0.0f}, {0.6, 0.4f}, {1.0, 0.9f}};
    tf.color = {
        {0.35, {0.60f, 0.10f, 0.10f}}, {0.6, {1.0f, 0.30f, 0.20f}}, {1.0, {1.0f, 0.90f, 0.80f}}};
  } else {
    return std::nullopt;
  }
  return tf;
}

std::vector<std::string> transferFunctionPresetNames() {
  return {"ct-bone", "ct-skin", "ct-soft-tissue", "ct-vessels", "mr-tissue", "mr-vessels"};
}

}  // namespace mfadvr
