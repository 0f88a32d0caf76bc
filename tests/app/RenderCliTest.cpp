// End-to-end tests of `mfadvr render` and `mfadvr demo`.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "TestSupport.h"
#include "app/CliRunner.h"
#include "core/image/PngFile.h"

namespace mfadvr {
namespace {

using test::runMfadvr;

TEST(CliRender, EveryMethodRendersABuiltin) {
  const auto dir = test::scratchDir();
  for (const char* method :
       {"mfa", "truth", "nearest", "trilinear", "tricubic", "catmull-rom", "bspline"}) {
    const std::string png = (dir / (std::string(method) + ".png")).string();
    const auto r = runMfadvr(std::string("render builtin:marschner-lobb:12 --size 40x30 --shade "
                                         "--method ") +
                             method + " -o " + png + " --json");
    ASSERT_EQ(r.status, 0) << method << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["method"], method);
    EXPECT_EQ(j["width"], 40);
    EXPECT_EQ(j["height"], 30);
    EXPECT_GT(j["samples"].get<long>(), 0);
    EXPECT_GT(j["rays_hit"].get<long>(), 0);
    const Image8 image = readPng(png);
    EXPECT_EQ(image.width, 40);
    EXPECT_EQ(image.height, 30);
    EXPECT_EQ(image.channels, 3);
    // Not a blank image: some pixel differs from the black background.
    bool lit = false;
    for (auto v : image.data) lit |= v > 20;
    EXPECT_TRUE(lit) << method;
  }
}

// --blend, --clip-plane, --crop and --depth: each mode renders, the depth image has its size
// and NaN where rays miss, bad values are usage errors and nothing is written.
TEST(CliRender, BlendModesClippingCroppingAndDepth) {
  const auto dir = test::scratchDir();
  const std::string base = "render builtin:marschner-lobb:12 --size 40x30 --method trilinear ";
  for (const char* mode : {"composite", "max", "min", "average", "additive"}) {
    const std::string png = (dir / (std::string(mode) + ".png")).string();
    const std::string depth = (dir / (std::string(mode) + ".nrrd")).string();
    const auto r = runMfadvr(base + "--blend " + mode + " --clip-plane 0,0,0,1,1,0 --crop " +
                             "-1,1,-1,0.5,-1,1 --depth " + depth + " -o " + png);
    ASSERT_EQ(r.status, 0) << mode << ": " << r.err;
    EXPECT_EQ(readPng(png).width, 40);
    std::ifstream in(depth, std::ios::binary);
    const std::string nrrd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_NE(nrrd.find("sizes: 40 30\n"), std::string::npos) << nrrd.substr(0, 200);
    const size_t data = nrrd.find("\n\n") + 2;
    ASSERT_EQ(nrrd.size() - data, 40u * 30u * 4u);
    float corner, centre;
    std::memcpy(&corner, nrrd.data() + data, 4);  // the top-left ray misses the box
    std::memcpy(&centre, nrrd.data() + data + 4 * (15 * 40 + 25), 4);
    EXPECT_TRUE(std::isnan(corner)) << mode;
    EXPECT_GT(centre, 0.0f) << mode;
  }
  const std::string png = (dir / "bad.png").string();
  for (const char* bad :
       {"--blend mean", "--blend average --average-range 2,1", "--average-range 0,1",
        "--clip-plane 0,0,0,0,0,0", "--clip-plane 1,2,3", "--crop 1,0,0,1,0,1"}) {
    const auto r = runMfadvr(base + bad + " -o " + png);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(png)) << bad;
  }
}

TEST(CliRender, GradientOpacityAndTwoDimensionalTransferFunctions) {
  const auto dir = test::scratchDir();
  const std::string base = "render builtin:marschner-lobb:12 --size 40x30 -q ";
  const std::string boxes = (dir / "boxes.json").string();
  {
    std::ofstream f(boxes);
    f << R"({"boxes": [{"value": [0.2, 0.9], "gradient": [0, 8], "color": [1, 0.5, 0],
                        "opacity": 0.6}]})";
  }
  Image8 table;
  table.width = 8;
  table.height = 4;
  table.channels = 4;
  table.data.assign(8 * 4 * 4, 200);
  const std::string tablePng = (dir / "table.png").string();
  writePng(tablePng, table);
  for (const std::string& args : std::vector<std::string>{
           "--gradient-opacity 0:0,2:1", "--gradient-opacity 0:0,2:1 --shade --method trilinear",
           "--tf2d " + boxes, "--tf2d " + boxes + " --shade --method tricubic",
           "--tf2d " + tablePng + " --tf2d-range 0,10",
           "--tf2d " + tablePng + " --tf2d-range 0,1,0,10"}) {
    const std::string png = (dir / "x.png").string();
    std::filesystem::remove(png);
    const auto r = runMfadvr(base + args + " -o " + png);
    ASSERT_EQ(r.status, 0) << args << ": " << r.err;
    EXPECT_EQ(readPng(png).width, 40) << args;
  }
  const std::string png = (dir / "bad.png").string();
  for (const std::string& bad : std::vector<std::string>{
           "--gradient-opacity 1", "--gradient-opacity 1:2", "--gradient-opacity 2:1,1:1",
           "--gradient-opacity -1:1", "--gradient-opacity 0:0,1:1 --blend max",
           "--tf2d " + boxes + " --blend iso --iso 0.5", "--tf2d " + tablePng,
           "--tf2d " + tablePng + " --tf2d-range 1,0", "--tf2d " + tablePng + " --tf2d-range 0,1,2",
           "--tf2d-range 0,1", "--tf2d " + (dir / "missing.json").string(), "--tf2d " + png}) {
    const auto r = runMfadvr(base + bad + " -o " + png);
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_FALSE(r.err.empty()) << bad;
    EXPECT_FALSE(std::filesystem::exists(png)) << bad;
  }
}

TEST(CliRender, CurvatureTransferFunctionsAndContours) {
  const auto dir = test::scratchDir();
  const std::string base = "render builtin:marschner-lobb:12 --size 40x30 -q ";
  const std::string boxes = (dir / "curvature.json").string();
  {
    std::ofstream f(boxes);
    f << R"({"boxes": [{"k1": [0, 50], "k2": [-50, 50], "color": [0, 1, 0], "weight": 0.8}]})";
  }
  const std::string plainPng = (dir / "plain.png").string();
  ASSERT_EQ(runMfadvr(base + "-o " + plainPng).status, 0);
  const Image8 plain = readPng(plainPng);
  for (const std::string& args : std::vector<std::string>{
           "--curvature-tf mean", "--curvature-tf ridges-valleys:0.5 --shade",
           "--curvature-tf gaussian --method tricubic", "--curvature-tf " + boxes, "--contours 2",
           "--contours 1.5 --contour-color 1,0,0 --shade --method bspline",
           "--blend iso --iso 0.5 --contours 2 --shade",
           "--blend iso --iso 0.5 --curvature-tf mean"}) {
    const std::string png = (dir / "x.png").string();
    std::filesystem::remove(png);
    const auto r = runMfadvr(base + args + " -o " + png);
    ASSERT_EQ(r.status, 0) << args << ": " << r.err;
    const Image8 image = readPng(png);
    EXPECT_EQ(image.width, 40) << args;
    EXPECT_NE(image.data, plain.data) << args << ": the curvature changed nothing";
  }
  const std::string png = (dir / "bad.png").string();
  for (const std::string& bad : std::vector<std::string>{
           "--curvature-tf ridges", "--curvature-tf mean:0", "--curvature-tf mean:k",
           "--curvature-tf " + (dir / "missing.json").string(), "--contours -1",
           "--contours 2 --contour-color 2,0,0", "--contours 2 --blend max",
           "--curvature-tf mean --method vtk-fixedpoint"}) {
    const auto r = runMfadvr(base + bad + " -o " + png);
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_FALSE(r.err.empty()) << bad;
    EXPECT_FALSE(std::filesystem::exists(png)) << bad;
  }
}

TEST(CliRender, ImagesIndependentOfThreadsAndFloatOutput) {
  const auto dir = test::scratchDir();
  const std::string common =
      "render builtin:gaussian-beam:16 --method tricubic --size 33x17 --shade --azimuth 20 -q ";
  ASSERT_EQ(runMfadvr(common + "--threads 1 -o " + (dir / "a.png").string()).status, 0);
  ASSERT_EQ(runMfadvr(common + "--threads 2 --alpha -o " + (dir / "b.png").string() + " --float " +
                      (dir / "b.nrrd").string())
                .status,
            0);
  const Image8 a = readPng((dir / "a.png").string()), b = readPng((dir / "b.png").string());
  ASSERT_EQ(b.channels, 4);
  for (size_t p = 0; p < size_t(33 * 17); ++p)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(a.data[p * 3 + c], b.data[p * 4 + c]);
  EXPECT_TRUE(std::filesystem::exists(dir / "b.nrrd"));
}

TEST(CliRender, ModelOfABuiltinKnowsItsTruthAndSamples) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "ml.mfa").string();
  ASSERT_EQ(runMfadvr("encode builtin:marschner-lobb:14 -o " + model).status, 0);
  for (const char* args : {"--method mfa", "--method truth", "--method trilinear",
                           "--gradient-from mfa", "--gradient-from bspline --gradient central"}) {
    const auto r = runMfadvr("render " + model + " --size 24x24 --shade -q " + args + " -o " +
                             (dir / "x.png").string());
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
  }
}

TEST(CliRender, CameraFileAndOptions) {
  const auto dir = test::scratchDir();
  const auto camera = dir / "camera.json";
  std::ofstream(camera) << R"({"position": [0, 0, -6], "focal_point": [0, 0, 0],
                              "view_up": [0, 1, 0], "view_angle": 40})";
  auto r = runMfadvr("render builtin:gaussian-beam:12 --size 20x20 -q --camera " + camera.string() +
                     " -o " + (dir / "a.png").string());
  EXPECT_EQ(r.status, 0) << r.err;
  r = runMfadvr(
      "render builtin:gaussian-beam:12 --size 20x20 -q --parallel --zoom 2 --elevation 90 "
      "--tf step:0.3 --colormap viridis --light 1,0,0,0.5 --shade --background 1,1,1 "
      "--step 0.05 --unit-distance 0.2 --ert 1.5 --range 0,300 -o " +
      (dir / "b.png").string());
  EXPECT_EQ(r.status, 0) << r.err;
  std::ofstream(dir / "bad-camera.json") << R"({"positon": [0, 0, 5]})";
  r = runMfadvr("render builtin:gaussian-beam:12 --size 20x20 --camera " +
                (dir / "bad-camera.json").string() + " -o " + (dir / "c.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("positon"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.png"));
}

TEST(CliRender, BadArgumentsFailCleanly) {
  const auto dir = test::scratchDir();
  const std::string out = " -o " + (dir / "x.png").string();
  const std::string in = "render builtin:gaussian-beam:8 --size 16x16";
  test::CliResult r0;
  EXPECT_EQ(runMfadvr(in + " --method cubic" + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --size 0x10" + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --size 10" + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --position 1,2" + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --background 2,0,0" + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --method mfa --gradient-from trilinear" + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --step -1" + out).status, 2);
  // 0 is not a silent "default", and a step that would take hours is refused up front.
  EXPECT_EQ(runMfadvr(in + " --step 0" + out).status, 2);
  r0 = runMfadvr(in + " --step 1e-9" + out);
  EXPECT_EQ(r0.status, 2);
  EXPECT_NE(r0.err.find("samples along a ray"), std::string::npos) << r0.err;
  EXPECT_EQ(runMfadvr(in).status, 2);  // no output
  auto r = runMfadvr(in + " --tf nonsense" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("ramp"), std::string::npos) << r.err;  // lists the accepted forms
  r = runMfadvr(in + " --position 0,0,0 --focal-point 0,0,0" + out);
  EXPECT_EQ(r.status, 1);
  r = runMfadvr("render " + (dir / "missing.mfa").string() + out);
  EXPECT_EQ(r.status, 1);
  // A model cannot offer grid methods unless it came from a builtin.
  r = runMfadvr("render " + (dir / "missing.nrrd").string() + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(CliRender, WarnsWhenTheTransferFunctionGivesTheDataOneOpacity) {
  const auto dir = test::scratchDir();
  const std::string common =
      "render builtin:marschner-lobb:12 --size 16x16 -o " + (dir / "tf.png").string() + " ";
  // Marschner-Lobb takes values in [0, 1]: all of it above ct-skin's -400 HU.
  auto r = runMfadvr(common + "--tf ct-skin");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the transfer function gives every value of the data"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("the same opacity 0.6"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Hounsfield"), std::string::npos) << r.err;
  r = runMfadvr(common + "--tf ramp --range 2,3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("opacity 0: the image will be empty"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--range 2,3"), std::string::npos) << r.err;
  // A function that shows something, and -q, say nothing.
  for (const char* quiet : {"--tf step:0.5", "--tf ct-skin -q"}) {
    r = runMfadvr(common + quiet);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("warning"), std::string::npos) << quiet << ": " << r.err;
  }
}

TEST(CliRender, ModelTooLargeForTheMemoryIsRefusedBeforeLoading) {
  const auto dir = test::scratchDir();
  const std::string single = (dir / "one.mfa").string(), blocks = (dir / "blocks.mfa").string();
  ASSERT_EQ(runMfadvr("encode builtin:marschner-lobb:24 -o " + single).status, 0);
  ASSERT_EQ(runMfadvr("encode builtin:marschner-lobb:24 --blocks 2,1,1 -o " + blocks).status, 0);
  const std::string png = (dir / "x.png").string();
  for (const std::string& model : {single, blocks}) {
    // 24^3 control points need about 5 B each (control points, flags): 70 KB.
    const auto r =
        runMfadvr("render " + model + " --size 32x32 -o " + png, "MFADVR_MEMORY_LIMIT=50K");
    EXPECT_EQ(r.status, 1) << model;
    EXPECT_NE(r.err.find("needs about"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("50 KB are available"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(png));
    EXPECT_EQ(
        runMfadvr("render " + model + " --size 32x32 -o " + png, "MFADVR_MEMORY_LIMIT=1G").status,
        0);
    std::filesystem::remove(png);
  }
  EXPECT_NE(runMfadvr("render " + blocks + " -o " + png, "MFADVR_MEMORY_LIMIT=50K")
                .err.find("control points in 2 blocks"),
            std::string::npos);
  const std::string nrrd = (dir / "x.nrrd").string();
  const auto decode = runMfadvr("decode " + single + " -q -o " + nrrd, "MFADVR_MEMORY_LIMIT=50K");
  EXPECT_EQ(decode.status, 1);
  EXPECT_NE(decode.err.find("decoding " + single + " needs about"), std::string::npos)
      << decode.err;
  EXPECT_FALSE(std::filesystem::exists(nrrd));
  const auto bad = runMfadvr("render " + single + " -o " + png, "MFADVR_MEMORY_LIMIT=lots");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.err.find("MFADVR_MEMORY_LIMIT: 'lots' is not a memory size"), std::string::npos)
      << bad.err;
}

TEST(CliRender, BlocksThatDoNotFitTogetherAreReadOneAtATime) {
  // 2 x 2 x 2 blocks: all of them need more than the limit, two at a time (the first block is
  // kept) fit. The image is the one rendered with every block in memory, byte for byte.
  const auto dir = test::scratchDir();
  const std::string blocks = (dir / "blocks.mfa").string();
  ASSERT_EQ(runMfadvr("encode builtin:marschner-lobb:40 --blocks 2,2,2 -o " + blocks).status, 0);
  const std::string whole = (dir / "whole.png").string(),
                    streamed = (dir / "streamed.png").string();
  const std::string args = " --shade --tf step:0.5 --size 48x40 --azimuth 35 --elevation 20 -o ";
  // Two frames: all blocks in memory (one frame reads them one at a time whatever the memory).
  const auto all =
      runMfadvr("render " + blocks + " --frames 2" + args + whole, "MFADVR_MEMORY_LIMIT=1G");
  ASSERT_EQ(all.status, 0) << all.err;
  EXPECT_EQ(all.err.find("one at a time"), std::string::npos) << all.err;
  const auto one = runMfadvr("render " + blocks + args + streamed, "MFADVR_MEMORY_LIMIT=250K");
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_NE(one.err.find("its 8 blocks would need about"), std::string::npos) << one.err;
  EXPECT_NE(one.err.find("read one at a time"), std::string::npos) << one.err;
  EXPECT_EQ(test::slurp(whole), test::slurp(streamed));
  // Less than two blocks: refused with the figure for all of them, nothing written.
  std::filesystem::remove(streamed);
  const auto none = runMfadvr("render " + blocks + args + streamed, "MFADVR_MEMORY_LIMIT=60K");
  EXPECT_EQ(none.status, 1);
  EXPECT_NE(none.err.find("in 8 blocks, about"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("one at a time"), std::string::npos) << none.err;
  EXPECT_FALSE(std::filesystem::exists(streamed));
}

TEST(CliDemo, WritesImagesMontageAndMetrics) {
  const auto dir = test::scratchDir() / "demo";
  const auto r = runMfadvr("demo --size 96x96 --json --out " + dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* f :
       {"truth.png", "mfa.png", "trilinear.png", "montage.png", "model.mfa", "summary.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  // Each panel has a caption band below it (method, PSNR, SSIM): dark text on white. Panels
  // narrower than their caption are widened, so only the first one's place is known.
  const Image8 montage = readPng((dir / "montage.png").string());
  EXPECT_GE(montage.width, 3 * 96 + 2 * 8);
  ASSERT_GT(montage.height, 96 + 3 * 8);
  int dark = 0;
  for (int y = 96; y < montage.height; ++y)
    for (int x = 0; x < montage.width; ++x)
      if (montage.data[3 * (static_cast<size_t>(y) * montage.width + x)] < 64) ++dark;
  EXPECT_GT(dark, 3 * 100);  // about 200 text pixels per caption at scale 1
  const Image8 truth = readPng((dir / "truth.png").string());
  for (int x = 0; x < 96; ++x)
    EXPECT_EQ(montage.data[3 * (static_cast<size_t>(50) * montage.width + x)],
              truth.data[3 * (static_cast<size_t>(50) * 96 + x)]);
  ASSERT_EQ(j["methods"].size(), 3u);
  EXPECT_EQ(j["methods"][0]["method"], "truth");
  EXPECT_TRUE(j["methods"][0]["psnr"].is_null());  // identical to itself
  const double mfa = j["methods"][1]["psnr"], trilinear = j["methods"][2]["psnr"];
  EXPECT_GT(mfa, trilinear);
}

}  // namespace
}  // namespace mfadvr
