// A mesh's exact boundary through the command line: encode stores it (and --no-boundary does
// not), info shows it, query's inside column follows it where the voxel mask cannot. And the
// mesh's cell samples (--cell-samples) in encode's report and refusals, and the mesh rendered as
// itself (--method mesh).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "app/CliRunner.h"

namespace mfadvr {
namespace {

// A legacy VTK mesh of the unit cubes of a 4^3 grid less a cavity (the central 2^3 cubes) and a
// notch (the corner cube at 3,3,3), 6 tetrahedra a cube, with the point scalar x + y + z.
void writeHoledMesh(const std::filesystem::path& path) {
  const test::TetMesh m = test::cubeMesh(4, [](int i, int j, int k) {
    const bool cavity = i >= 1 && i <= 2 && j >= 1 && j <= 2 && k >= 1 && k <= 2;
    return !cavity && !(i == 3 && j == 3 && k == 3);
  });
  test::writeLegacyTetMesh(path, m, [](const Vec3d& p) { return p.sum(); });
}

TEST(BoundaryCli, EncodeStoresTheBoundaryAndQueryFollowsIt) {
  const auto dir = test::scratchDir();
  const std::string mesh = (dir / "holed.vtk").string();
  writeHoledMesh(mesh);
  const std::string exact = (dir / "exact.mfa").string(), masked = (dir / "masked.mfa").string();
  // A coarse mask (a node per grid point): it counts the notch and the cavity's middle in.
  auto r = test::runMfadvr("encode " + mesh + " -o " + exact + " --mask-res 5 --ctrl 5 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  // Outer hull 6 x 16 squares (the notch trades 3 outer squares for 3 inner ones), cavity
  // 6 x 4 squares; 2 triangles a square.
  EXPECT_EQ(j["boundary"]["triangles"], 240);
  r = test::runMfadvr("encode " + mesh + " -o " + masked + " --mask-res 5 --ctrl 5 --no-boundary");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("boundary   "), std::string::npos) << r.out;

  r = test::runMfadvr("info " + exact + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["boundary"]["triangles"], 240);
  r = test::runMfadvr("info " + exact);
  EXPECT_NE(r.out.find("boundary        240 triangles"), std::string::npos) << r.out;
  r = test::runMfadvr("info " + masked + " --json");
  EXPECT_TRUE(nlohmann::json::parse(r.out)["boundary"].is_null()) << r.out;

  // In the mesh, in the notch, in the cavity.
  std::ofstream(dir / "points.txt") << "0.5 0.5 0.5\n3.5 3.5 3.5\n1.5 1.5 1.5\n";
  const std::string points = " --points " + (dir / "points.txt").string();
  auto insideColumn = [](const std::string& csv) {
    std::string column;
    std::istringstream in(csv);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) column += line.back();
    return column;
  };
  r = test::runMfadvr("query " + exact + points);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(insideColumn(r.out), "100") << r.out;
  r = test::runMfadvr("query " + masked + points);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(insideColumn(r.out), "111") << r.out;  // the mask's half-node blur

  // The render path reads the boundary from the file (its pixels: DomainBoundaryTest).
  r = test::runMfadvr("render " + exact + " -o " + (dir / "exact.png").string() +
                      " --size 64x64 --tf ramp --json");
  ASSERT_EQ(r.status, 0) << r.err;
}

TEST(BoundaryCli, CellSamplesAreCountedAndBadCountsRefused) {
  const auto dir = test::scratchDir();
  const std::string mesh = (dir / "holed.vtk").string();
  writeHoledMesh(mesh);
  const std::string model = (dir / "cells.mfa").string();
  auto r = test::runMfadvr("encode " + mesh + " -o " + model + " --cell-samples 4 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["points"], 125);
  EXPECT_EQ(j["cell_samples"], 4 * 6 * (64 - 8 - 1));  // 4 in each tetrahedron of 55 cubes
  // By default a mesh gets one (the centroid) in each tetrahedron; not with --max-error or
  // --smooth auto, whose bound and choice concern the measured points.
  r = test::runMfadvr("encode " + mesh + " -o " + model + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["cell_samples"], 6 * (64 - 8 - 1));
  for (const std::string& without :
       {std::string("--cell-samples 0"), std::string("--max-error 0.5"),
        std::string("--smooth auto")}) {
    r = test::runMfadvr("encode " + mesh + " -o " + model + " --json " + without);
    ASSERT_EQ(r.status, 0) << without << ": " << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["cell_samples"], 0) << without;
  }
  const std::string refused = (dir / "refused.mfa").string();
  for (const std::string& bad : {mesh + " --cell-samples 2", mesh + " --cell-samples x",
                                 std::string("builtin:gaussian-beam:16 --cell-samples 1")}) {
    r = test::runMfadvr("encode " + bad + " -o " + refused);
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_NE(r.err.find("--cell-samples"), std::string::npos) << bad << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(refused)) << bad;
  }
}

// --method mesh: the mesh's own field through our ray caster; inputs without a mesh are refused
// with the method's name and no image.
TEST(BoundaryCli, MethodMeshRendersTheMeshAndRefusesInputsWithoutOne) {
  const auto dir = test::scratchDir();
  const std::string mesh = (dir / "holed.vtk").string();
  writeHoledMesh(mesh);
  const std::string image = (dir / "mesh.png").string();
  auto r = test::runMfadvr("render " + mesh + " --method mesh --size 48x40 -o " + image);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("mesh, 48x40"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::is_regular_file(image));
  // The model renders the same data through the same rays: close to the mesh's image.
  const std::string model = (dir / "model.png").string();
  r = test::runMfadvr("render " + mesh + " --size 48x40 -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::runMfadvr("compare " + model + " " + image + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto psnr = nlohmann::json::parse(r.out)["psnr"];  // null: identical
  EXPECT_TRUE(psnr.is_null() || psnr.get<double>() > 30.0) << r.out;

  const std::string cloud = (dir / "cloud.csv").string();
  {
    std::ofstream f(cloud);
    f << "x,y,z,value\n0,0,0,1\n1,0,0,2\n0,1,0,3\n0,0,1,4\n1,1,1,5\n";
  }
  const std::string refused = (dir / "refused.png").string();
  for (const std::string& input : {cloud, std::string("builtin:gaussian-beam:16")}) {
    r = test::runMfadvr("render " + input + " --method mesh --size 16x16 -o " + refused);
    EXPECT_NE(r.status, 0) << input;
    EXPECT_NE(r.err.find("mesh"), std::string::npos) << input << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(refused)) << input;
  }
}

}  // namespace
}  // namespace mfadvr
