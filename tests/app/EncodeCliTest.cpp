// `encode` and `render` with adaptive bounds, scattered inputs and masks, end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "TestSupport.h"
#include "app/CliRunner.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "io/MedicalTestFiles.h"  // gzipBytes

namespace mfadvr {
namespace {

using test::runMfadvr;

nlohmann::json parseJson(const test::CliResult& r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "): " << r.out << r.err;
    return {};
  }
}

// A CSV point cloud: a smooth function at random points in a ball of radius 1.
std::string writeBallCloud(const std::filesystem::path& dir, int count) {
  const auto path = dir / "ball.csv";
  std::ofstream out(path);
  out << "x,y,z,temperature\n";
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int written = 0; written < count;) {
    const double x = u(rng), y = u(rng), z = u(rng);
    if (x * x + y * y + z * z > 1) continue;
    out << x << "," << y << "," << z << "," << std::exp(-(x * x + 2 * y * y + z * z)) << "\n";
    ++written;
  }
  return path.string();
}

TEST(EncodeCli, AdaptiveReachesTheBoundAndReportsRounds) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "ml.mfa").string();
  const auto r = runMfadvr("encode builtin:marschner-lobb:61 --max-error 1e-2 --json -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = parseJson(r);
  EXPECT_TRUE(j["adaptive"]["reached"].get<bool>());
  EXPECT_LE(j["max_relative_error"].get<double>(), 1e-2);
  EXPECT_EQ(j["adaptive"]["rounds"].get<int>(), static_cast<int>(j["adaptive"]["history"].size()));
  EXPECT_EQ(j["encoder"], "structured-least-squares-adaptive");
  EXPECT_EQ(loadModel(model).spline().counts()[0], j["control_counts"][0].get<std::int64_t>());
  // Text report names the outcome.
  const auto t = runMfadvr("encode builtin:marschner-lobb:61 --max-error 1e-2");
  EXPECT_NE(t.out.find("reached after"), std::string::npos) << t.out;
}

TEST(EncodeCli, LimitsWarnOrFailWithStrict) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "best.mfa").string();
  const std::string args = "encode builtin:marschner-lobb:41 --max-error 1e-4 --max-ctrl 10 ";
  const auto warn = runMfadvr(args + "-o " + model);
  EXPECT_EQ(warn.status, 0) << warn.err;
  EXPECT_NE(warn.err.find("not reached"), std::string::npos) << warn.err;
  EXPECT_TRUE(std::filesystem::exists(model));  // the best model

  const std::string strictModel = (dir / "strict.mfa").string();
  const auto strict = runMfadvr(args + "--strict -o " + strictModel);
  EXPECT_EQ(strict.status, 3) << strict.err;
  EXPECT_NE(strict.err.find("nothing written"), std::string::npos) << strict.err;
  EXPECT_FALSE(std::filesystem::exists(strictModel));
}

TEST(EncodeCli, RejectsContradictoryOptions) {
  for (const std::string args :
       {"builtin:gaussian-beam:16 --max-ctrl 8", "builtin:gaussian-beam:16 --max-error 0",
        "builtin:gaussian-beam:16 --max-error -1", "builtin:gaussian-beam:16 --strict",
        "builtin:gaussian-beam:16 --smooth -0.1", "builtin:gaussian-beam:16 --smooth nan",
        "builtin:gaussian-beam:16 --smooth inf", "builtin:gaussian-beam:16 --smooth automatic",
        "builtin:gaussian-beam:16 --no-mask", "builtin:gaussian-beam:16 --no-boundary",
        "builtin:gaussian-beam:16 --max-error 1e-2 --max-rounds 0"}) {
    const auto r = runMfadvr("encode " + args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  }
  const auto dir = test::scratchDir();
  const std::string cloud = writeBallCloud(dir, 200);
  for (const std::string args :
       {" --smooth -1", " --mask-res 1", " --no-mask --mask-res 16", " --spacing 2"}) {
    const auto r = runMfadvr("encode " + cloud + args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  }
}

// Point clouds (and meshes) take --smooth auto too: lambda by hold-out cross-validation, said
// in the report and in --json, and the model holds it.
TEST(EncodeCli, ScatteredDataChooseTheirSmoothing) {
  const auto dir = test::scratchDir();
  const std::string cloud = writeBallCloud(dir, 2000);
  const std::string model = (dir / "auto.mfa").string();
  const auto r = runMfadvr("encode " + cloud + " --smooth auto --ctrl 8 --json -q -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = parseJson(r);
  EXPECT_TRUE(j["smoothing"]["automatic"].get<bool>());
  EXPECT_TRUE(j["smoothing"]["noise_estimate"].is_null());
  EXPECT_NE(j["smoothing"]["note"].get<std::string>().find("hold-out cross-validation"),
            std::string::npos);
  const double lambda = j["smoothing"]["lambda"].get<double>();
  EXPECT_GT(lambda, 0.0);
  EXPECT_DOUBLE_EQ(j["solver"]["smoothing"].get<double>(), lambda);
  const auto text = runMfadvr("encode " + cloud + " --smooth auto --ctrl 8 -o " + model);
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("by hold-out cross-validation"), std::string::npos) << text.out;
}

// Grids take --smooth L and --smooth auto; the report and the model say what was chosen.
TEST(EncodeCli, GridSmoothingIsReportedAndStored) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "smooth.mfa").string();
  const auto fixed = runMfadvr("encode builtin:gaussian-beam:24 --smooth 0.05 --json -o " + model);
  ASSERT_EQ(fixed.status, 0) << fixed.err;
  auto j = parseJson(fixed);
  EXPECT_DOUBLE_EQ(j["smoothing"]["lambda"].get<double>(), 0.05);
  EXPECT_FALSE(j["smoothing"]["automatic"].get<bool>());
  EXPECT_DOUBLE_EQ(loadModel(model).provenance().smoothing, 0.05);
  const auto info = runMfadvr("info " + model);
  EXPECT_NE(info.out.find("smoothing       lambda 0.05"), std::string::npos) << info.out;

  const auto automatic = runMfadvr("encode builtin:gaussian-beam:24 --smooth auto -o " + model);
  ASSERT_EQ(automatic.status, 0) << automatic.err;
  EXPECT_NE(automatic.out.find("by generalized cross-validation"), std::string::npos)
      << automatic.out;
  EXPECT_GT(loadModel(model).provenance().smoothing, 0.0);

  // Blocks share one lambda, chosen on the whole grid.
  const std::string blocks = (dir / "blocks.mfa").string();
  const auto b =
      runMfadvr("encode builtin:gaussian-beam:24 --smooth auto --blocks 2,1,1 --json -o " + blocks);
  ASSERT_EQ(b.status, 0) << b.err;
  j = parseJson(b);
  ASSERT_EQ(j["block_reports"].size(), 2u);
  const double lambda = j["block_reports"][0]["smoothing"]["lambda"].get<double>();
  EXPECT_GT(lambda, 0.0);
  EXPECT_EQ(j["block_reports"][1]["smoothing"]["lambda"].get<double>(), lambda);
}

// A job larger than the machine fails at once, saying what it needs and what there is.
TEST(EncodeCli, RefusesWhatDoesNotFitInMemory) {
  const auto r = runMfadvr("encode builtin:marschner-lobb:40000 -q");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("needs about"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("available"), std::string::npos) << r.err;
}

TEST(EncodeCli, PointCloudGetsACoverageMaskAndRenders) {
  const auto dir = test::scratchDir();
  const std::string cloud = writeBallCloud(dir, 3000);
  const std::string model = (dir / "ball.mfa").string();
  const auto r = runMfadvr("encode " + cloud + " --ctrl 10 --json -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = parseJson(r);
  EXPECT_EQ(j["points"], 3000);
  EXPECT_EQ(j["input_kind"], "point cloud");
  EXPECT_EQ(j["mask"]["kind"], "point-coverage");
  // A ball covers about pi/6 of its box.
  EXPECT_GT(j["mask"]["inside_fraction"].get<double>(), 0.35);
  EXPECT_LT(j["mask"]["inside_fraction"].get<double>(), 0.85);
  EXPECT_LT(j["rms_relative_error"].get<double>(), 0.02);
  const Model m = loadModel(model);
  EXPECT_FALSE(m.inside(m.domain().max));  // a box corner
  EXPECT_TRUE(m.inside(Vec3d::Zero()));
  EXPECT_EQ(m.provenance().field, "temperature");

  const std::string png = (dir / "ball.png").string();
  const auto render = runMfadvr("render " + model + " -o " + png + " --size 40x40 -q");
  EXPECT_EQ(render.status, 0) << render.err;
  EXPECT_TRUE(std::filesystem::exists(png));
  // Rendering the CSV directly encodes it on the fly; grid methods cannot use it.
  const auto direct = runMfadvr("render " + cloud + " --ctrl 8 -o " + png + " --size 32x32 -q");
  EXPECT_EQ(direct.status, 0) << direct.err;
  const auto grid = runMfadvr("render " + cloud + " --method trilinear -o " + png + " -q");
  EXPECT_EQ(grid.status, 1);
  EXPECT_NE(grid.err.find("--method mfa"), std::string::npos) << grid.err;

  const auto noMask = runMfadvr("encode " + cloud + " --ctrl 8 --no-mask --json");
  EXPECT_TRUE(parseJson(noMask)["mask"].is_null());
}

TEST(EncodeCli, MeshFromSharedData) {
  const auto spx = test::dataFile("spx.vtk");
  if (spx.empty()) GTEST_SKIP() << "spx.vtk not present";
  const auto dir = test::scratchDir();
  const std::string model = (dir / "spx.mfa").string();
  const auto r = runMfadvr("encode " + spx.string() + " --mask-res 48 --json -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = parseJson(r);
  EXPECT_EQ(j["input_kind"], "tetrahedral mesh");
  EXPECT_EQ(j["points"], 2896);
  EXPECT_EQ(j["mask"]["kind"], "mesh-occupancy");
  EXPECT_EQ(j["mask"]["dims"].get<Index3>().at(0) <= 48, true);
  const auto info = runMfadvr("info " + model);
  EXPECT_NE(info.out.find("mesh-occupancy"), std::string::npos) << info.out;
}

}  // namespace
}  // namespace mfadvr

namespace mfadvr {
namespace {

// A cut volume, an absurd header and a model from NaN samples: exit 1, the reason, no model.
TEST(EncodeCli, RefusesCutAndAbsurdInputsWithoutOutput) {
  const auto dir = test::scratchDir();
  const std::string header =
      "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 40 40 40\nencoding: raw\n\n";
  std::ofstream(dir / "cut.nrrd", std::ios::binary) << header << std::string(30000, '\1');
  std::ofstream(dir / "absurd.nrrd", std::ios::binary)
      << "NRRD0004\ntype: float\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n\n"
      << "abcd";
  std::ofstream(dir / "nan_2x2x2_float32.raw", std::ios::binary)
      << std::string(7 * 4, '\0') << std::string("\x00\x00\xc0\x7f", 4);  // the last is NaN
  for (const auto& [file, reason] : std::vector<std::pair<std::string, std::string>>{
           {"cut.nrrd", "holds only 30,000 bytes"},
           {"absurd.nrrd", "4,000,000,000,000,000 bytes"},
           {"nan_2x2x2_float32.raw", "nan"}}) {
    const auto model = dir / (file + ".mfa");
    const auto r =
        test::runMfadvr("encode " + (dir / file).string() + " --degree 1 -o " + model.string());
    EXPECT_EQ(r.status, 1) << file;
    EXPECT_NE(r.err.find(reason), std::string::npos) << file << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(model)) << file;
  }
}

// A thin grid (an AMR patch, a slab): the default degree 3 needs 4 samples per axis, so without
// --degree the short axis gets samples - 1; an explicit --degree is kept (and refused).
TEST(EncodeCli, DefaultDegreeFitsShortAxes) {
  const auto dir = test::scratchDir();
  const auto file = (dir / "thin_6x3x5_uint8.raw").string();
  std::ofstream(file, std::ios::binary) << std::string(6 * 3 * 5, '\7');
  const auto r = runMfadvr("encode " + file + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(parseJson(r)["degree"], nlohmann::json({3, 2, 3}));
  EXPECT_NE(r.err.find("axis y has 3 samples: degree 2"), std::string::npos) << r.err;
  const auto fixed = runMfadvr("encode " + file + " --degree 3");
  EXPECT_EQ(fixed.status, 1);
  EXPECT_NE(fixed.err.find("too few for degree 3"), std::string::npos) << fixed.err;
}

// A finite-volume style image: a 3-component cell array only, 6 x 5 x 4 points.
TEST(EncodeCli, CellDataAndComponentOptions) {
  const auto dir = test::scratchDir();
  std::ostringstream values;
  for (int n = 0; n < 5 * 4 * 3; ++n) values << n << " 0 " << 2 * n << " ";
  std::ofstream(dir / "fv.vti")
      << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\">\n"
         "<ImageData WholeExtent=\"0 5 0 4 0 3\" Origin=\"0 0 0\" Spacing=\"2 2 2\">\n"
         "<Piece Extent=\"0 5 0 4 0 3\"><CellData>\n"
         "<DataArray type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\" "
         "format=\"ascii\">"
      << values.str() << "</DataArray>\n</CellData></Piece></ImageData></VTKFile>\n";
  const std::string file = (dir / "fv.vti").string();
  const auto vector = runMfadvr("encode " + file + " --degree 1");
  EXPECT_EQ(vector.status, 1);
  EXPECT_NE(vector.err.find("--component"), std::string::npos) << vector.err;
  const auto model = (dir / "fv.mfa").string();
  const auto r =
      runMfadvr("encode " + file + " --degree 1 --component magnitude --json -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = parseJson(r);
  EXPECT_EQ(j["field"], "velocity_magnitude");
  EXPECT_EQ(j["field_association"], "cell data");
  // Cell centres: 5 x 4 x 3 samples from (1, 1, 1) on; the largest magnitude is sqrt(5) * 59.
  EXPECT_NEAR(j["value_max"].get<double>(), std::sqrt(5.0) * 59.0, 1e-3);
  EXPECT_EQ(j["samples"], nlohmann::json({5, 4, 3}));
  const auto info = runMfadvr("info " + model);
  EXPECT_NE(info.out.find("velocity_magnitude"), std::string::npos) << info.out;
  for (const std::string bad : {" --component -1", " --component x", " --association edge"}) {
    const auto b = runMfadvr("encode " + file + bad);
    EXPECT_EQ(b.status, 2) << bad << "\n" << b.err;
  }
}

}  // namespace
}  // namespace mfadvr

namespace mfadvr {
namespace {

TEST(EncodeCli, BlocksWriteAMultiBlockModelThatInfoAndRenderRead) {
  using test::runMfadvr;
  const auto dir = test::scratchDir();
  const std::string blocks = (dir / "ml-blocks.mfa").string();
  const auto r =
      runMfadvr("encode builtin:marschner-lobb:33 --degree 2 --blocks 2,1,2 --json -o " + blocks);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["blocks"], nlohmann::json({2, 1, 2}));
  EXPECT_EQ(j["ghost_layers"].get<int>(), 6);  // 2 x (degree + 1)
  EXPECT_EQ(j["block_reports"].size(), 4u);
  EXPECT_LT(j["max_relative_error"].get<double>(), 1e-5);  // interpolating fits

  const auto info = runMfadvr("info --json " + blocks);
  ASSERT_EQ(info.status, 0) << info.err;
  const auto ij = nlohmann::json::parse(info.out);
  EXPECT_EQ(ij["format"], "mfadvr-blocks");
  EXPECT_EQ(ij["entries"].size(), 4u);
  EXPECT_EQ(ij["entries"][0]["degree"], nlohmann::json({2, 2, 2}));
  EXPECT_EQ(runMfadvr("info " + blocks).status, 0);

  // Rendered block by block and composited, it looks like the single model.
  const std::string single = (dir / "ml.mfa").string();
  ASSERT_EQ(runMfadvr("encode builtin:marschner-lobb:33 --degree 2 -q -o " + single).status, 0);
  const std::string a = (dir / "blocks.png").string(), b = (dir / "single.png").string();
  const std::string view = " --size 96x96 --shade --azimuth 30 --elevation 20 -q -o ";
  ASSERT_EQ(runMfadvr("render " + blocks + view + a).status, 0);
  ASSERT_EQ(runMfadvr("render " + single + view + b).status, 0);
  const auto cmp = runMfadvr("compare --json " + b + " " + a);
  ASSERT_EQ(cmp.status, 0) << cmp.err;
  EXPECT_GT(nlohmann::json::parse(cmp.out)["psnr"].get<double>(), 40.0) << cmp.out;

  // Blocks apply to grids, without adaptive fitting; --ghost needs --blocks.
  EXPECT_NE(runMfadvr("encode builtin:marschner-lobb:33 --blocks 40,1,1 -q").status, 0);
  EXPECT_NE(runMfadvr("encode builtin:marschner-lobb:33 --ghost 2").status, 0);
  EXPECT_NE(runMfadvr("encode builtin:marschner-lobb:33 --blocks 2 --max-error 1e-2").status, 0);
  EXPECT_NE(runMfadvr("render " + blocks + " --method trilinear -q -o " + a).status, 0);
  // Commands made for one model say what the file is.
  const auto query = runMfadvr("query " + blocks + " 0 0 0");
  EXPECT_EQ(query.status, 1);
  EXPECT_NE(query.err.find("multi-block"), std::string::npos) << query.err;
  const auto viewer = runMfadvr("view " + blocks + " --screenshot " + a);
  EXPECT_EQ(viewer.status, 1);
  EXPECT_NE(viewer.err.find("multi-block"), std::string::npos) << viewer.err;
}

// Out of core: a raw file or a built-in whose in-core encoding needs more than the memory limit
// is encoded block by block into a multi-block model, with a note saying so.
TEST(EncodeCli, InputsLargerThanTheMemoryLimitAreEncodedInBlocks) {
  const auto dir = test::scratchDir();
  const std::string raw = (dir / "ramp_80x72x66_uint8.raw").string();
  {
    std::ofstream out(raw, std::ios::binary);
    for (int k = 0; k < 66; ++k)
      for (int j = 0; j < 72; ++j)
        for (int i = 0; i < 80; ++i) out.put(static_cast<char>((i * 3 + j * 2 + k * k) % 251));
  }
  const std::string model = (dir / "ramp.mfa").string();
  const auto r =
      runMfadvr("encode " + raw + " --memory-limit 3M --coding float32 --json -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("--blocks auto"), std::string::npos) << r.err;
  const auto j = parseJson(r);
  const auto blocks = j["blocks"].get<std::array<int, 3>>();
  EXPECT_GT(blocks[0] * blocks[1] * blocks[2], 1);
  EXPECT_GT(j["peak_memory_bytes"].get<double>(), 0.0);
  EXPECT_GT(j["input_megabytes_per_second"].get<double>(), 0.0);
  // Every block interpolates its samples.
  EXPECT_LT(j["max_relative_error"].get<double>(), 1e-5);
  const auto info = runMfadvr("info --json " + model);
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_EQ(parseJson(info)["format"], "mfadvr-blocks");

  // Within the limit: one model, as before. --blocks auto splits at most 256 intervals per block.
  const auto single = runMfadvr("encode " + raw + " --memory-limit 8G -q -o " + model);
  ASSERT_EQ(single.status, 0) << single.err;
  EXPECT_EQ(single.err.find("--blocks auto"), std::string::npos) << single.err;
  EXPECT_NO_THROW(loadModel(model));
  const auto automatic = runMfadvr("encode builtin:marschner-lobb:33 --blocks auto --json");
  ASSERT_EQ(automatic.status, 0) << automatic.err;
  EXPECT_EQ(parseJson(automatic)["blocks"], nlohmann::json({1, 1, 1}));

  for (const std::string bad : {" --memory-limit 0", " --memory-limit 12Q", " --memory-limit -1G"})
    EXPECT_EQ(runMfadvr("encode " + raw + bad).status, 2) << bad;
}

// A header format whose samples are streamed (here NRRD with gzip data) is encoded block by
// block from the file as a raw file of the same samples is: the same control points per block.
TEST(EncodeCli, StreamedHeaderFormatsAreEncodedInBlocksLikeRawFiles) {
  const auto dir = test::scratchDir();
  std::string samples;
  for (int k = 0; k < 40; ++k)
    for (int j = 0; j < 36; ++j)
      for (int i = 0; i < 44; ++i) samples += static_cast<char>((i * 5 + j * j + 3 * k) % 253);
  const std::string raw = (dir / "ramp_44x36x40_uint8.raw").string();
  std::ofstream(raw, std::ios::binary) << samples;
  const std::string nrrd = (dir / "ramp.nrrd").string();
  std::ofstream(nrrd, std::ios::binary)
      << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 44 36 40\nencoding: gzip\n\n"
      << test::gzipBytes(samples);
  const std::string a = (dir / "raw.mfa").string(), b = (dir / "nrrd.mfa").string();
  for (const auto& [input, model] : {std::pair{raw, a}, std::pair{nrrd, b}}) {
    const auto r = runMfadvr("encode " + input + " --blocks 2 --coding float32 -q -o " + model);
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const auto fromRaw = loadBlockModels(a), fromNrrd = loadBlockModels(b);
  ASSERT_EQ(fromRaw.size(), 8u);
  ASSERT_EQ(fromNrrd.size(), fromRaw.size());
  for (size_t i = 0; i < fromRaw.size(); ++i)
    EXPECT_EQ(test::values(fromNrrd[i].model.spline().controlPoints()),
              test::values(fromRaw[i].model.spline().controlPoints()))
        << "block " << i;
}

}  // namespace
}  // namespace mfadvr
