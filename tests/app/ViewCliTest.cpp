// `mfadvr view`: the interactive viewer is tested headless, by rendering one frame off screen
// (--screenshot) under the virtual display the CLI test program runs on (tests/CMakeLists.txt).
// Its frame goes through vtkMFAVolumeMapper in a VTK scene set up from the render options, so
// comparing it with `render` checks the whole chain: options -> VTK scene -> mapper -> pixels.
#include <gtest/gtest.h>

#include <fstream>

#include "TestSupport.h"
#include "app/CliRunner.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngFile.h"

namespace mfadvr {
namespace {

using test::runMfadvr;

TEST(CliView, ScreenshotMatchesRenderForEveryMethod) {
  const auto dir = test::scratchDir();
  const std::string scene = " --size 96x80 --azimuth 30 --elevation 20 --tf step:0.5 -q";
  for (const char* method : {"mfa", "tricubic", "truth"}) {
    for (const char* shade : {"", " --shade"}) {
      const std::string view = (dir / "view.png").string(), render = (dir / "render.png").string();
      const std::string common = std::string(" --method ") + method + shade + scene;
      const auto v = runMfadvr("view builtin:marschner-lobb:33 --screenshot " + view + common);
      ASSERT_EQ(v.status, 0) << v.err;
      EXPECT_NE(v.out.find(method), std::string::npos) << v.out;
      const auto r = runMfadvr("render builtin:marschner-lobb:33 -o " + render + common);
      ASSERT_EQ(r.status, 0) << r.err;
      // Measured: identical for mfa; within one 8-bit level for the others.
      const double psnr = compareImages(readPng(view), readPng(render)).psnr;
      EXPECT_GT(psnr, 48.0) << method << shade;
    }
  }
}

// A time-varying model: --time picks the instant (the frame `render --time` gives), the
// benchmark times changing the time, and --time outside the range is an error.
TEST(CliView, ShowsAnyInstantOfATimeVaryingModel) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "blobs.mfa").string();
  ASSERT_EQ(runMfadvr("encode builtin:orbiting-blobs:16x16x16x5 -q -o " + model).status, 0);
  const std::string scene = " --size 64x64 --azimuth 30 --tf step:0.4 -q";
  const std::string view = (dir / "view.png").string(), render = (dir / "render.png").string();
  const auto v = runMfadvr("view " + model + " --time 0.6 --screenshot " + view + scene);
  ASSERT_EQ(v.status, 0) << v.err;
  ASSERT_EQ(runMfadvr("render " + model + " --time 0.6 -o " + render + scene).status, 0);
  EXPECT_GT(compareImages(readPng(view), readPng(render)).psnr, 48.0);
  const auto b = runMfadvr("view " + model + " --benchmark 3" + scene);
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_NE(b.out.find("changing the time:"), std::string::npos) << b.out;
  EXPECT_EQ(runMfadvr("view " + model + " --time 5 --screenshot " + view + scene).status, 1);
}

// The blend, isovalue, clipping, cropping, gradient- and curvature-classification options reach
// the viewer's mapper: its frame is render's.
TEST(CliView, ScreenshotMatchesRenderForBlendModesAndClipping) {
  const auto dir = test::scratchDir();
  const std::string scene = " --size 96x80 --azimuth 30 --elevation 20 -q";
  const std::string boxes = (dir / "boxes.json").string();
  std::ofstream(boxes) << R"({"boxes": [{"value": [0.3, 0.8], "gradient": [1, 9], "opacity": 0.7,
                                          "color": [1, 0.6, 0.2]}]})";
  for (const std::string& options : std::vector<std::string>{
           " --blend max", " --blend iso --iso 0.5 --shade", " --clip-plane 0,0,0,1,0.2,0",
           " --crop -1,0.5,-1,1,-0.5,1 --blend additive", " --gradient-opacity 0:0,3:1 --shade",
           " --tf2d " + boxes, " --curvature-tf mean --shade",
           " --blend iso --iso 0.5 --contours 2 --curvature-tf ridges-valleys"}) {
    const std::string view = (dir / "view.png").string(), render = (dir / "render.png").string();
    const auto v =
        runMfadvr("view builtin:marschner-lobb:33 --screenshot " + view + options + scene);
    ASSERT_EQ(v.status, 0) << options << ": " << v.err;
    const auto r = runMfadvr("render builtin:marschner-lobb:33 -o " + render + options + scene);
    ASSERT_EQ(r.status, 0) << options << ": " << r.err;
    EXPECT_GT(compareImages(readPng(view), readPng(render)).psnr, 48.0) << options;
  }
}

// A mesh offers its own field (method mesh) beside its model; the frame is render's.
TEST(CliView, AMeshRendersAsItselfToo) {
  const auto dir = test::scratchDir();
  const std::string mesh = (dir / "cubes.vtk").string();
  test::writeLegacyTetMesh(mesh, test::cubeMesh(3, [](int, int, int) { return true; }),
                           [](const Vec3d& p) { return p.x() * p.y() + p.z(); });
  const std::string view = (dir / "view.png").string(), render = (dir / "render.png").string();
  const std::string common = " --method mesh --size 64x48 --azimuth 30 --elevation 20 -q";
  const auto v = runMfadvr("view " + mesh + " --screenshot " + view + common);
  ASSERT_EQ(v.status, 0) << v.err;
  EXPECT_NE(v.out.find("mesh"), std::string::npos) << v.out;
  ASSERT_EQ(runMfadvr("render " + mesh + " -o " + render + common).status, 0);
  EXPECT_GT(compareImages(readPng(view), readPng(render)).psnr, 48.0);
}

TEST(CliView, RejectsMethodsTheInputCannotProvide) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "ml.mfa").string();
  ASSERT_EQ(runMfadvr("encode builtin:marschner-lobb:17 -q -o " + model).status, 0);
  const std::string shot = (dir / "shot.png").string();
  // A model file holds no samples for the grid filters.
  const auto r = runMfadvr("view " + model + " --method trilinear --screenshot " + shot);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("available: mfa, truth"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(shot));
  const auto ok = runMfadvr("view " + model + " --screenshot " + shot + " --size 32x32");
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_TRUE(std::filesystem::exists(shot));
}

}  // namespace
}  // namespace mfadvr
