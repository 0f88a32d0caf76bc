// End-to-end tests of `mfadvr render --method vtk-*`: VTK's own renderers as baselines. The test
// program runs under a virtual X display (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "app/CliRunner.h"
#include "core/image/PngFile.h"

namespace mfadvr {
namespace {

using test::runMfadvr;

// Pixels that differ clearly from a black background.
int litPixels(const Image8& image) {
  int lit = 0;
  for (size_t p = 0; p < image.data.size() / image.channels; ++p)
    lit += image.data[p * image.channels] + image.data[p * image.channels + 1] +
               image.data[p * image.channels + 2] >
           30;
  return lit;
}

TEST(CliVtkRender, EveryBaselineRendersABuiltin) {
  const auto dir = test::scratchDir();
  for (const char* method : {"vtk-fixedpoint", "vtk-bunyk", "vtk-zsweep", "vtk-pt"}) {
    const std::string png = (dir / (std::string(method) + ".png")).string();
    const auto r = runMfadvr(std::string("render builtin:gaussian-beam:10 --size 48x40 --shade "
                                         "--azimuth 30 --frames 2 --json --method ") +
                             method + " -o " + png);
    ASSERT_EQ(r.status, 0) << method << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["method"], method);
    EXPECT_EQ(j["width"], 48);
    EXPECT_EQ(j["height"], 40);
    EXPECT_EQ(j["frames"], 2);
    EXPECT_EQ(j["frame_seconds"].size(), 2u);
    EXPECT_GT(j["seconds"]["first_frame"].get<double>(), 0.0);
    EXPECT_GT(j["seconds"]["render"].get<double>(), 0.0);
    EXPECT_EQ(j["points"], 1000);
    const bool fixed = std::string(method) == "vtk-fixedpoint";
    EXPECT_EQ(j["tetrahedralized"], !fixed);
    EXPECT_EQ(j["cells"], (fixed ? 1 : 5) * 9 * 9 * 9);
    EXPECT_EQ(j["shade"], fixed);  // only the fixed-point ray caster shades
    EXPECT_EQ(j["sample_distance"].is_null(), !fixed);
    const Image8 image = readPng(png);
    EXPECT_EQ(image.width, 48);
    EXPECT_EQ(image.height, 40);
    EXPECT_EQ(image.channels, 3);
    EXPECT_GT(litPixels(image), 50) << method;
  }
}

TEST(CliVtkRender, WarnsWhenTheTransferFunctionGivesTheDataOneOpacity) {
  const auto dir = test::scratchDir();
  const auto r = runMfadvr(
      "render builtin:gaussian-beam:10 --size 16x16 --method vtk-fixedpoint "
      "--tf '0:0,0.2:0' -o " +
      (dir / "empty.png").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the transfer function gives every value of the data"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("opacity 0: the image will be empty"), std::string::npos) << r.err;
}

TEST(CliVtkRender, TextOutputReportsFirstAndMedianFrame) {
  const auto dir = test::scratchDir();
  const auto r =
      runMfadvr("render builtin:marschner-lobb:8 --size 32x32 --method vtk-bunyk -q -o " +
                (dir / "a.png").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("vtkUnstructuredGridVolumeRayCastMapper"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("median of 2 frames after the first"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("first frame"), std::string::npos) << r.out;
  // Ignored settings are pointed out.
  const auto w = runMfadvr(
      "render builtin:marschner-lobb:8 --size 32x32 --method vtk-zsweep "
      "--shade --step 0.1 --frames 1 -o " +
      (dir / "b.png").string());
  ASSERT_EQ(w.status, 0) << w.err;
  EXPECT_NE(w.err.find("--shade is ignored"), std::string::npos) << w.err;
  EXPECT_NE(w.err.find("--step is ignored"), std::string::npos) << w.err;
  EXPECT_NE(w.out.find("one frame"), std::string::npos) << w.out;
}

TEST(CliVtkRender, OurMethodsTimeFramesToo) {
  const auto dir = test::scratchDir();
  const auto r = runMfadvr(
      "render builtin:gaussian-beam:8 --size 16x16 --method trilinear "
      "--frames 3 --json -o " +
      (dir / "a.png").string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["frames"], 3);
  EXPECT_EQ(j["frame_seconds"].size(), 3u);
  EXPECT_TRUE(j["seconds"].contains("first_frame"));
}

TEST(CliVtkRender, TetrahedralMeshFromSharedData) {
  const auto spx = test::dataFile("spx.vtk");
  if (spx.empty()) GTEST_SKIP() << "spx.vtk not in " << test::dataDir();
  const auto dir = test::scratchDir();
  for (const char* method : {"vtk-bunyk", "vtk-zsweep", "vtk-pt"}) {
    const std::string png = (dir / (std::string(method) + ".png")).string();
    const auto r = runMfadvr("render " + spx.string() + " --size 64x64 --elevation 30 --frames 2 " +
                             "--json --method " + method + " -o " + png);
    ASSERT_EQ(r.status, 0) << method << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["points"], 2896);
    EXPECT_EQ(j["cells"], 12936);
    EXPECT_EQ(j["tetrahedralized"], false);
    EXPECT_EQ(j["seconds"]["encode"], 0.0);  // the mesh is rendered, not encoded
    EXPECT_GT(litPixels(readPng(png)), 100) << method;
  }
  // The fixed-point ray caster renders grids only.
  const auto r = runMfadvr("render " + spx.string() + " --size 16x16 --method vtk-fixedpoint -o " +
                           (dir / "x.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("regular grids"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("vtk-bunyk"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(CliVtkRender, BadCombinationsFailClearly) {
  const auto dir = test::scratchDir();
  const auto cloud = dir / "cloud.csv";
  {
    std::ofstream out(cloud);
    for (int i = 0; i < 40; ++i)
      out << (i % 4) << " " << (i / 4 % 3) << " " << (i / 12) << " " << i << "\n";
  }
  const std::string out = " -o " + (dir / "x.png").string();
  // A point cloud has no cells for the tetrahedral mappers, and is no grid.
  auto r = runMfadvr("render " + cloud.string() + " --size 16x16 --method vtk-bunyk" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("point cloud"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("tetrahedra"), std::string::npos) << r.err;
  r = runMfadvr("render " + cloud.string() + " --size 16x16 --method vtk-fixedpoint" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("regular grids"), std::string::npos) << r.err;
  // Options that only our ray caster has are usage errors.
  const std::string in = "render builtin:gaussian-beam:8 --size 16x16 --method vtk-fixedpoint";
  EXPECT_EQ(runMfadvr(in + " --alpha" + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --float " + (dir / "x.nrrd").string() + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --gradient central" + out).status, 2);
  EXPECT_EQ(runMfadvr(in + " --frames 0" + out).status, 2);
  EXPECT_EQ(runMfadvr("render builtin:gaussian-beam:8 --method vtk-raycast" + out).status, 2);
  // A model of a builtin is rendered from its recomputed samples; other models hold no data.
  const std::string model = (dir / "beam.mfa").string();
  ASSERT_EQ(runMfadvr("encode builtin:gaussian-beam:8 -q -o " + model).status, 0);
  r = runMfadvr("render " + model + " --size 16x16 --method vtk-zsweep --frames 1" + out);
  EXPECT_EQ(r.status, 0) << r.err;
  std::filesystem::remove(dir / "x.png");
  const std::string cloudModel = (dir / "cloud.mfa").string();
  ASSERT_EQ(runMfadvr("encode " + cloud.string() + " --ctrl 4 -q -o " + cloudModel).status, 0);
  r = runMfadvr("render " + cloudModel + " --size 16x16 --method vtk-bunyk" + out);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("model file does not hold"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(CliVtkRender, NoDisplaySaysToUseXvfb) {
  const auto dir = test::scratchDir();
  const auto r = runMfadvr("render builtin:gaussian-beam:8 --size 16x16 --method vtk-bunyk -o " +
                           (dir / "x.png").string());
  ASSERT_EQ(r.status, 0) << r.err;  // the test itself has a display
  // CliRunner appends the arguments to the program path; `env -u` must come first, so run the
  // program through the shell directly.
  const std::string cmd = "env -u DISPLAY " + std::string(MFADVR_EXE) +
                          " render builtin:gaussian-beam:8 --size 16x16 --method vtk-bunyk -o " +
                          (dir / "y.png").string() + " 2>" + (dir / "err.txt").string();
  const int raw = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), 1);
  const std::string err = test::slurp(dir / "err.txt");
  EXPECT_NE(err.find("xvfb-run -a"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir / "y.png"));
}

}  // namespace
}  // namespace mfadvr
