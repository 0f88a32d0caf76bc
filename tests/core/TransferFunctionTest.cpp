#include "core/render/TransferFunction.h"

#include <cmath>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "core/render/ColorSpace.h"
#include "core/render/TransferFunctionPresets.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

using test::expectError;
using test::scratchDir;

std::string writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

TransferFunction simple() {
  TransferFunction tf;
  tf.color = {{0.0, Vec3f(0, 0, 1)}, {1.0, Vec3f(1, 0, 0)}};
  tf.opacity = {{0.2, 0.0f}, {0.6, 0.8f}};
  return tf;
}

TEST(TransferFunction, InterpolatesLinearlyAndClampsOutside) {
  const auto tf = simple();
  tf.validate();
  EXPECT_FLOAT_EQ(tf.opacityAt(0.4), 0.4f);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.5), 0.6f);
  EXPECT_FLOAT_EQ(tf.opacityAt(-5.0), 0.0f);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.2), 0.0f);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.6), 0.8f);
  EXPECT_FLOAT_EQ(tf.opacityAt(9.0), 0.8f);
  EXPECT_TRUE(tf.colorAt(0.25).isApprox(Vec3f(0.25f, 0, 0.75f)));
  EXPECT_EQ(tf.colorAt(-1.0), Vec3f(0, 0, 1));
  EXPECT_EQ(tf.colorAt(2.0), Vec3f(1, 0, 0));
  EXPECT_FLOAT_EQ(tf.opacityAt(std::numeric_limits<double>::quiet_NaN()), 0.0f);
}

TEST(TransferFunction, OpacityOverARangeTakesItsEndsAndInnerPoints) {
  const auto tf = simple();  // 0 up to 0.2, rising to 0.8 at 0.6, then 0.8
  EXPECT_EQ(tf.opacityOver(-1.0, 0.1), std::make_pair(0.0f, 0.0f));
  EXPECT_EQ(tf.opacityOver(0.7, 3.0), std::make_pair(0.8f, 0.8f));
  EXPECT_EQ(tf.opacityOver(0.0, 1.0), std::make_pair(0.0f, 0.8f));
  const auto inside = tf.opacityOver(0.3, 0.5);  // the ends only: no point between
  EXPECT_FLOAT_EQ(inside.first, 0.2f);
  EXPECT_FLOAT_EQ(inside.second, 0.6f);
  // A peak between the ends counts, though both ends are transparent.
  TransferFunction tent = simple();
  tent.opacity = {{0.4, 0.0f}, {0.5, 0.7f}, {0.6, 0.0f}};
  EXPECT_EQ(tent.opacityOver(0.0, 1.0), std::make_pair(0.0f, 0.7f));
  // A jump inside the range: both of its sides; a jump at the range's end: only the side
  // that the end's value takes.
  TransferFunction step = simple();
  step.opacity = {{0.5, 0.0f}, {0.5, 1.0f}};
  EXPECT_EQ(step.opacityOver(0.0, 1.0), std::make_pair(0.0f, 1.0f));
  EXPECT_EQ(step.opacityOver(0.5, 1.0), std::make_pair(1.0f, 1.0f));
  EXPECT_EQ(step.opacityOver(0.0, 0.4), std::make_pair(0.0f, 0.0f));
}

TEST(TransferFunction, LongListsUseTheSameRules) {
  // More than 8 points takes the binary-search path.
  TransferFunction tf = simple();
  tf.opacity.clear();
  for (int i = 0; i <= 20; ++i) tf.opacity.push_back({i * 0.05, (i % 2) ? 1.0f : 0.0f});
  tf.opacity.insert(tf.opacity.begin() + 11, {0.5, 0.25f});  // a jump at 0.5: 0 -> 0.25
  tf.validate();
  EXPECT_FLOAT_EQ(tf.opacityAt(0.025), 0.5f);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.5), 0.25f);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.525), 0.625f);
  EXPECT_FLOAT_EQ(tf.opacityAt(-1.0), 0.0f);
  EXPECT_FLOAT_EQ(tf.opacityAt(1.0), 0.0f);
  EXPECT_FLOAT_EQ(tf.opacityAt(7.0), 0.0f);
}

TEST(TransferFunction, StepAtIsovalueIsExact) {
  const auto tf = parseTransferFunction("step:0.5", "white").resolved(-2.0, 6.0);
  const double iso = 2.0;  // half way through [-2, 6]
  EXPECT_EQ(tf.opacityAt(std::nextafter(iso, -1e9)), 0.0f);
  EXPECT_EQ(tf.opacityAt(iso), 1.0f);
  EXPECT_EQ(tf.opacityAt(std::nextafter(iso, 1e9)), 1.0f);
  EXPECT_EQ(tf.opacityAt(-100.0), 0.0f);
  EXPECT_EQ(tf.opacityAt(100.0), 1.0f);
  // Also with the partial-opacity form and on the binary-search path.
  const auto partial = parseTransferFunction("step:0.25:0.3", "").resolved(0, 1);
  EXPECT_EQ(partial.opacityAt(std::nextafter(0.25, 0.0)), 0.0f);
  EXPECT_EQ(partial.opacityAt(0.25), 0.3f);
}

TEST(TransferFunction, ResolvedMapsNormalizedOntoTheDataRange) {
  TransferFunction tf = simple();
  tf.unitDistance = 0.5;
  const auto r = tf.resolved(10.0, 20.0);
  EXPECT_EQ(r.space, TfSpace::Data);
  EXPECT_DOUBLE_EQ(r.opacity[0].x, 12.0);
  EXPECT_DOUBLE_EQ(r.opacity[1].x, 16.0);
  EXPECT_EQ(r.color.front().x, 10.0);
  EXPECT_EQ(r.color.back().x, 20.0);  // exact at the ends
  EXPECT_FLOAT_EQ(r.opacityAt(14.0), 0.4f);
  EXPECT_EQ(r.unitDistance, 0.5);
  // Data-space points stay; constant data normalizes over [v, v+1].
  EXPECT_EQ(r.resolved(0.0, 1.0).opacity[0].x, 12.0);
  const auto flat = tf.resolved(3.0, 3.0);
  EXPECT_DOUBLE_EQ(flat.opacity[0].x, 3.2);
  EXPECT_DOUBLE_EQ(flat.color.back().x, 4.0);
  expectError([&] { tf.resolved(2.0, 1.0); }, {"data range"});
  expectError([&] { tf.resolved(0.0, std::nan("")); }, {"data range"});
}

TEST(TransferFunction, ColourAndOpacityMayLiveInDifferentSpaces) {
  TransferFunction tf = simple();
  tf.space = TfSpace::Data;  // opacity in data values
  tf.colorSpace = TfSpace::Normalized;
  const auto r = tf.resolved(0.0, 100.0);
  EXPECT_EQ(r.opacity[1].x, 0.6);
  EXPECT_EQ(r.color[1].x, 100.0);
  EXPECT_FALSE(r.colorSpace.has_value());
  EXPECT_EQ(r.colorPointSpace(), TfSpace::Data);
}

TEST(TransferFunction, ValidateRejectsBadPoints) {
  auto bad = [](auto edit, std::vector<std::string> parts) {
    TransferFunction tf = simple();
    edit(tf);
    expectError([&] { tf.validate(); }, parts);
  };
  bad(
      [](TransferFunction& t) {
        t.opacity = {{0.5, 0.0f}, {0.4, 1.0f}};
      },
      {"opacity[1]", "sorted"});
  bad([](TransferFunction& t) { t.opacity[1].alpha = 2.0f; }, {"opacity[1]", "alpha 2", "[0,1]"});
  bad([](TransferFunction& t) { t.opacity[0].alpha = std::nanf(""); }, {"opacity[0]", "alpha"});
  bad([](TransferFunction& t) { t.color[0].x = std::nan(""); }, {"color[0]", "finite"});
  bad([](TransferFunction& t) { t.color[1].rgb = Vec3f(255, 0, 0); }, {"color[1]", "0..255"});
  bad([](TransferFunction& t) { t.color.clear(); }, {"no color points"});
  bad([](TransferFunction& t) { t.opacity.clear(); }, {"no opacity points"});
  bad([](TransferFunction& t) { t.unitDistance = -1; }, {"unit distance"});
  bad([](TransferFunction& t) { t.unitDistance = INFINITY; }, {"unit distance"});
}

TEST(TransferFunction, EveryPresetParsesAndValidates) {
  for (const auto& name : colorMapPresetNames()) {
    SCOPED_TRACE(name);
    const auto tf = parseTransferFunction("", name);
    EXPECT_EQ(tf.space, TfSpace::Normalized);
    EXPECT_FALSE(tf.colorSpace.has_value());
  }
  // Each opacity form with its placeholders filled in.
  for (const char* spec : {"ramp", "ramp:0.2:0.7", "step:0.5", "step:0.5:0.2", "tent:0.5:0.2",
                           "tent:0.5:0.2:0.6", "constant:0.3", "Step:0.1"}) {
    SCOPED_TRACE(spec);
    parseTransferFunction(spec, "");
  }
  EXPECT_EQ(opacityPresetNames().size(), 5u);
  ASSERT_GE(colorMapPresetNames().size(), 6u);
  // ParaView's names are accepted too.
  EXPECT_TRUE(findColorMapPreset("Cool to Warm"));
  EXPECT_TRUE(findColorMapPreset("Viridis (matplotlib)"));
}

TEST(TransferFunction, PresetDefinitions) {
  const auto ramp = parseTransferFunction("", "");  // defaults: ramp, cool-to-warm
  EXPECT_FLOAT_EQ(ramp.opacityAt(0.3), 0.3f);
  EXPECT_TRUE(ramp.colorAt(0.0).isApprox(Vec3f(0.230f, 0.299f, 0.754f), 2e-3f));
  EXPECT_TRUE(ramp.colorAt(1.0).isApprox(Vec3f(0.706f, 0.016f, 0.150f), 2e-3f));
  const auto tent = parseTransferFunction("tent:0.5:0.2:0.6", "viridis");
  EXPECT_FLOAT_EQ(tent.opacityAt(0.4), 0.0f);
  EXPECT_FLOAT_EQ(tent.opacityAt(0.45), 0.3f);
  EXPECT_FLOAT_EQ(tent.opacityAt(0.5), 0.6f);
  EXPECT_FLOAT_EQ(tent.opacityAt(0.6), 0.0f);
  EXPECT_TRUE(tent.colorAt(0.0).isApprox(Vec3f(0.267f, 0.0049f, 0.3294f), 1e-3f));
  EXPECT_TRUE(tent.colorAt(1.0).isApprox(Vec3f(0.9932f, 0.9062f, 0.1439f), 1e-3f));
  const auto c = parseTransferFunction("constant:0.25", "red");
  EXPECT_FLOAT_EQ(c.opacityAt(-3), 0.25f);
  EXPECT_EQ(c.colorAt(0.7), Vec3f(1, 0, 0));
  const auto g = parseTransferFunction("ramp:0.2:0.4", "grayscale");
  EXPECT_FLOAT_EQ(g.opacityAt(0.3), 0.5f);
  EXPECT_TRUE(g.colorAt(0.5).isApprox(Vec3f(0.5f, 0.5f, 0.5f)));
}

// The medical presets pick the materials they are named for, at the values those materials
// have: CT in Hounsfield units (air -1000, fat -100, soft tissue 40, contrast 350, bone 1000).
TEST(TransferFunction, MedicalPresetsShowTheirMaterials) {
  for (const auto& name : transferFunctionPresetNames()) {
    SCOPED_TRACE(name);
    const auto tf = parseTransferFunction(name, "");
    EXPECT_EQ(tf.space, name.rfind("ct-", 0) == 0 ? TfSpace::Data : TfSpace::Normalized);
    EXPECT_FALSE(tf.colorSpace.has_value());
    EXPECT_EQ(tf.opacityAt(tf.space == TfSpace::Data ? -1000.0 : 0.0), 0.0f);  // air, background
    EXPECT_EQ(parseTransferFunction("", name).color.size(), tf.color.size());  // as a colour map
  }
  const auto bone = parseTransferFunction("CT-Bone", "");
  EXPECT_EQ(bone.opacityAt(40), 0.0f);
  EXPECT_GT(bone.opacityAt(1000), 0.5f);
  const auto skin = parseTransferFunction("ct-skin", "");
  EXPECT_EQ(skin.opacityAt(-700), 0.0f);
  EXPECT_GT(skin.opacityAt(40), 0.5f);
  const auto soft = parseTransferFunction("ct-soft-tissue", "");
  EXPECT_GT(soft.opacityAt(40), 0.05f);
  EXPECT_LT(soft.opacityAt(40), 0.3f);
  EXPECT_GT(soft.opacityAt(1000), 0.5f);
  const auto vessels = parseTransferFunction("ct-vessels", "");
  EXPECT_EQ(vessels.opacityAt(40), 0.0f);
  EXPECT_GT(vessels.opacityAt(350), 2.0f * vessels.opacityAt(1000));
  EXPECT_GT(vessels.colorAt(350).x(), 2.0f * vessels.colorAt(350).y());  // red
  const auto mra = parseTransferFunction("mr-vessels", "");
  EXPECT_EQ(mra.opacityAt(0.3), 0.0f);
  EXPECT_GT(mra.opacityAt(0.9), 0.5f);
  // A colour map replaces the preset's colours and keeps its opacities (in their own space).
  const auto recoloured = parseTransferFunction("ct-bone", "viridis");
  EXPECT_EQ(recoloured.space, TfSpace::Data);
  EXPECT_EQ(recoloured.colorSpace, TfSpace::Normalized);
  EXPECT_GT(recoloured.opacityAt(1000), 0.5f);
  EXPECT_FALSE(findTransferFunctionPreset("ct-lung"));
}

TEST(TransferFunction, CoolToWarmIsMorelandsMsh) {
  // Our diverging interpolation (used for ParaView presets) reproduces the sampled map.
  const auto tf = parseTransferFunction("", "cool-to-warm");
  const Vec3d cool(0.230, 0.299, 0.754), warm(0.706, 0.016, 0.150);
  for (double t : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    const Vec3f ours = interpolateColor(cool, warm, t, ColorInterpolation::Diverging).cast<float>();
    EXPECT_LT((ours - tf.colorAt(t)).cwiseAbs().maxCoeff(), 0.01f) << "t = " << t;
  }
  // Lab round trip.
  const Vec3d c(0.2, 0.5, 0.8);
  EXPECT_LT((labToRgb(rgbToLab(c)) - c).norm(), 1e-3);
}

TEST(TransferFunction, InlineForms) {
  const auto tf = parseTransferFunction("0:0, 0.5:0.2,0.5:1 ,1:1", "0:0:0:1,1:1:1:0");
  ASSERT_EQ(tf.opacity.size(), 4u);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.25), 0.1f);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.5), 1.0f);
  EXPECT_TRUE(tf.colorAt(0.5).isApprox(Vec3f(0.5f, 0.5f, 0.5f)));
  EXPECT_FLOAT_EQ(parseTransferFunction("+.5:1", "").opacityAt(-9), 1.0f);
}

TEST(TransferFunction, BadSpecsSayWhatIsAccepted) {
  expectError([] { parseTransferFunction("bogus", ""); },
              {"opacity 'bogus'", "ramp", "step:ISO", "x:a", "JSON"});
  expectError([] { parseTransferFunction("", "plasma-ish"); },
              {"colour map 'plasma-ish'", "viridis", "cool-to-warm", "x:r:g:b", "JSON"});
  expectError([] { parseTransferFunction("step", ""); }, {"step:ISO[:A]"});
  expectError([] { parseTransferFunction("step:abc", ""); }, {"step:ISO[:A]"});
  expectError([] { parseTransferFunction("step:0.5:2", ""); }, {"[0,1]"});
  expectError([] { parseTransferFunction("tent:0.5:0", ""); }, {"WIDTH > 0"});
  expectError([] { parseTransferFunction("ramp:0.7:0.2", ""); }, {"LO < HI"});
  expectError([] { parseTransferFunction("0:0,0.5", ""); }, {"point 2 '0.5'", "x:a"});
  expectError([] { parseTransferFunction("0:0,,1:1", ""); }, {"point 2"});
  expectError([] { parseTransferFunction("0:0:1", ""); }, {"x:a"});
  expectError([] { parseTransferFunction("0:nan", ""); }, {"x:a"});
  expectError([] { parseTransferFunction("", "0:1:0"); }, {"x:r:g:b"});
  expectError([] { parseTransferFunction("0.5:0,0.2:1", ""); },
              {"opacity '0.5:0,0.2:1'", "sorted"});
  expectError([] { parseTransferFunction("0:2", ""); }, {"alpha 2"});
  expectError([] { parseTransferFunction("", "0:1:0:300"); }, {"0..255"});
}

TEST(TransferFunction, OurJsonRoundTrip) {
  const auto dir = scratchDir();
  TransferFunction tf;
  tf.space = TfSpace::Data;
  tf.color = {{-1.5, Vec3f(0.1f, 0.2f, 0.3f)}, {2.25, Vec3f(1.0f, 0.5f, 0.0f)}};
  tf.opacity = {{0.0, 0.0f}, {0.7, 0.0f}, {0.7, 0.9f}, {3.0, 1.0f / 3.0f}};
  tf.unitDistance = 0.125;
  const auto path = (dir / "tf.json").string();
  saveTransferFunctionJson(tf, path);
  const auto back = loadTransferFunctionJson(path);
  EXPECT_EQ(back.space, TfSpace::Data);
  EXPECT_FALSE(back.colorSpace.has_value());
  ASSERT_EQ(back.color.size(), 2u);
  ASSERT_EQ(back.opacity.size(), 4u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.color[i].x, tf.color[i].x);
    EXPECT_EQ(back.color[i].rgb, tf.color[i].rgb);
  }
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(back.opacity[i].x, tf.opacity[i].x);
    EXPECT_EQ(back.opacity[i].alpha, tf.opacity[i].alpha);
  }
  EXPECT_EQ(back.unitDistance, 0.125);
  // Through the parser: the file's colours are used unless a colour map is given.
  const auto p = parseTransferFunction(path, "");
  EXPECT_EQ(p.color.size(), 2u);
  EXPECT_EQ(p.unitDistance, 0.125);
  const auto q = parseTransferFunction(path, "viridis");
  EXPECT_EQ(q.space, TfSpace::Data);
  EXPECT_EQ(q.colorPointSpace(), TfSpace::Normalized);  // mixed: resolved separately
  const auto r = q.resolved(0.0, 10.0);
  EXPECT_EQ(r.opacity[1].x, 0.7);
  EXPECT_EQ(r.color.back().x, 10.0);
  // Mixed spaces survive the file too.
  saveTransferFunctionJson(q, path);
  const auto q2 = loadTransferFunctionJson(path);
  EXPECT_EQ(q2.space, TfSpace::Data);
  EXPECT_EQ(q2.colorPointSpace(), TfSpace::Normalized);
}

TEST(TransferFunction, JsonWithOnlyOneList) {
  const auto dir = scratchDir();
  const auto colors = writeFile(dir / "colors.json", R"({"color": [[0, 0, 0, 0], [1, 1, 1, 1]]})");
  const auto alphas = writeFile(dir / "alphas.json",
                                R"({"space": "data", "opacity": [[10, 0], [20, 1]],
                                    "unit_distance": 2})");
  const auto tf = parseTransferFunction(alphas, colors);
  EXPECT_EQ(tf.space, TfSpace::Data);
  EXPECT_EQ(tf.colorPointSpace(), TfSpace::Normalized);
  EXPECT_EQ(tf.unitDistance, 2.0);
  EXPECT_FLOAT_EQ(tf.opacityAt(15), 0.5f);
  // No colour given anywhere: ParaView's default.
  const auto d = parseTransferFunction(alphas, "");
  const auto ref = parseTransferFunction("", "cool-to-warm");
  ASSERT_EQ(d.color.size(), ref.color.size());
  EXPECT_EQ(d.color[7].rgb, ref.color[7].rgb);
  expectError([&] { parseTransferFunction(colors, ""); }, {"no opacity points", "colour map"});
  expectError([&] { parseTransferFunction("", alphas); }, {"has no colours"});
}

TEST(TransferFunction, ParaViewPresetIsRescaled) {
  const auto dir = scratchDir();
  // As ParaView 5.x writes it (Choose Preset > Export), two presets in one file.
  const auto path = writeFile(dir / "presets.json", R"([
    {
      "ColorSpace" : "RGB",
      "Creator" : "Me",
      "Name" : "My Map",
      "NanColor" : [1, 1, 0],
      "RGBPoints" : [-1, 0, 0, 1,  0, 1, 1, 1,  1, 1, 0, 0],
      "Points" : [-1, 0, 0.5, 0,  0.5, 0.2, 0.5, 0,  1, 1, 0.5, 0]
    },
    {
      "ColorSpace" : "Diverging",
      "Name" : "Cool Warm Copy",
      "RGBPoints" : [0, 0.23, 0.299, 0.754, 250, 0.706, 0.016, 0.15]
    },
    {
      "ColorSpace" : "Step",
      "Name" : "Steps",
      "RGBPoints" : [0, 1, 0, 0,  1, 0, 1, 0,  2, 0, 0, 1]
    }
  ])");
  const auto tf = loadTransferFunctionJson(path);  // the first one
  EXPECT_EQ(tf.space, TfSpace::Normalized);
  ASSERT_EQ(tf.color.size(), 3u);
  EXPECT_EQ(tf.color[0].x, 0.0);
  EXPECT_EQ(tf.color[1].x, 0.5);
  EXPECT_EQ(tf.color[2].x, 1.0);
  EXPECT_TRUE(tf.colorAt(0.25).isApprox(Vec3f(0.5f, 0.5f, 1.0f)));
  ASSERT_EQ(tf.opacity.size(), 3u);
  EXPECT_DOUBLE_EQ(tf.opacity[1].x, 0.75);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.875), 0.6f);
  // Its opacities and colours as a whole transfer function.
  const auto whole = parseTransferFunction(path, "");
  EXPECT_EQ(whole.color.size(), 3u);
  EXPECT_FLOAT_EQ(whole.resolved(-10, 10).opacityAt(5.0), 0.2f);

  // Named, Diverging: sampled densely into RGB, matching our Cool to Warm.
  const auto cw = parseTransferFunction("ramp", path + "#Cool Warm Copy");
  EXPECT_GE(cw.color.size(), 64u);
  const auto ref = parseTransferFunction("ramp", "cool-to-warm");
  for (double x : {0.1, 0.25, 0.5, 0.75, 0.9})
    EXPECT_LT((cw.colorAt(x) - ref.colorAt(x)).cwiseAbs().maxCoeff(), 0.01f) << x;

  // Step: a segment takes its right node's colour.
  const auto st = loadTransferFunctionJson(path + "#steps");
  EXPECT_EQ(st.colorAt(0.25), Vec3f(0, 1, 0));
  EXPECT_EQ(st.colorAt(0.75), Vec3f(0, 0, 1));
  EXPECT_EQ(st.colorAt(-1), Vec3f(1, 0, 0));

  expectError([&] { loadTransferFunctionJson(path + "#Nope"); },
              {"no preset named 'Nope'", "'My Map'", "'Cool Warm Copy'"});
  expectError([&] { parseTransferFunction(path + "#Cool Warm Copy", ""); }, {"no opacity"});
}

TEST(TransferFunction, ParaViewMidpointAndSharpness) {
  const auto dir = scratchDir();
  const auto path = writeFile(dir / "pv.json", R"([{"Name": "x",
      "Points": [0, 0, 0.25, 0,  1, 1, 0.5, 1,  2, 0, 0.5, 0.5,  3, 1, 0.5, 0]}])");
  const auto tf = loadTransferFunctionJson(path);
  const double third = 1.0 / 3.0;
  // Segment 1: linear with its halfway value at a quarter of the way.
  EXPECT_FLOAT_EQ(tf.opacityAt(0.25 * third), 0.5f);
  EXPECT_FLOAT_EQ(tf.opacityAt(0.125 * third), 0.25f);
  // Segment 2: sharpness 1, a step at the midpoint.
  EXPECT_FLOAT_EQ(tf.opacityAt(third + 0.49 * third), 1.0f);
  EXPECT_FLOAT_EQ(tf.opacityAt(third + 0.51 * third), 0.0f);
  // Segment 3: a curve, monotone between its ends and halfway at the midpoint.
  EXPECT_NEAR(tf.opacityAt(2.5 * third), 0.5f, 1e-6);
  float last = 0.0f;
  for (int k = 0; k <= 20; ++k) {
    const float a = tf.opacityAt(2 * third + k * third / 20);
    EXPECT_GE(a, last - 1e-6f);
    last = a;
  }
}

TEST(TransferFunction, BadFiles) {
  const auto dir = scratchDir();
  expectError([&] { parseTransferFunction((dir / "missing.json").string(), ""); },
              {"missing.json", "no such file"});
  expectError([&] { parseTransferFunction("", (dir / "missing.json").string()); },
              {"no such file"});
  const auto broken = writeFile(dir / "broken.json", "{\"opacity\": [[0, 1],");
  expectError([&] { parseTransferFunction(broken, ""); }, {"broken.json", "not valid JSON"});
  const auto neither = writeFile(dir / "neither.json", R"({"space": "normalized"})");
  expectError([&] { parseTransferFunction(neither, ""); }, {"neither", "color", "opacity"});
  const auto typo = writeFile(dir / "typo.json", R"({"opacities": [[0, 1]]})");
  expectError([&] { parseTransferFunction(typo, ""); }, {"unknown key \"opacities\"", "opacity"});
  const auto shape = writeFile(dir / "shape.json", R"({"opacity": [[0, 1, 2]]})");
  expectError([&] { parseTransferFunction(shape, ""); }, {"opacity[0]", "[x, a]"});
  const auto space = writeFile(dir / "space.json", R"({"space": "world", "opacity": [[0, 1]]})");
  expectError([&] { parseTransferFunction(space, ""); }, {"\"space\"", "normalized", "data"});
  const auto alpha = writeFile(dir / "alpha.json", R"({"opacity": [[0, 0], [1, 2]]})");
  expectError([&] { parseTransferFunction(alpha, ""); }, {"alpha.json", "opacity[1]", "alpha 2"});
  const auto pvBad = writeFile(dir / "pv.json", R"([{"Name": "a", "RGBPoints": [0, 1, 0]}])");
  expectError([&] { parseTransferFunction("", pvBad); }, {"RGBPoints", "4 per point"});
  const auto indexed =
      writeFile(dir / "indexed.json", R"([{"Name": "c", "IndexedColors": [1, 0, 0]}])");
  expectError([&] { parseTransferFunction("", indexed); }, {"IndexedColors"});
  const auto cs =
      writeFile(dir / "cs.json", R"([{"Name": "c", "ColorSpace": "XYZ", "RGBPoints": [0,0,0,0]}])");
  expectError([&] { parseTransferFunction("", cs); }, {"ColorSpace", "Diverging"});
  expectError([&] { parseTransferFunction(neither + "#Name", ""); }, {"not one"});
}

}  // namespace
}  // namespace mfadvr
