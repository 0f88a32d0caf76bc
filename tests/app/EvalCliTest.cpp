// `mfadvr eval paper`: usage errors, an unknown experiment, and a small run without VTK or
// plots (the whole quick evaluation is the EvalPaper.QuickSmoke test).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "CliRunner.h"

using mfadvr::test::runMfadvr;
using mfadvr::test::slurp;

namespace {

std::filesystem::path tmp(const std::string& name) {
  const auto p = std::filesystem::path(MFADVR_TEST_TMP_DIR) / name;
  std::filesystem::remove_all(p);
  return p;
}

}  // namespace

TEST(CliEval, NeedsTheEvaluationAndAnOutputFolder) {
  EXPECT_EQ(runMfadvr("eval").status, 2);
  const auto r = runMfadvr("eval paper --quick");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
}

TEST(CliEval, UnknownExperimentListsTheKnownOnesAndWritesNothing) {
  const auto out = tmp("eval_cli_unknown");
  const auto r =
      runMfadvr("eval paper --quick --no-vtk --out " + out.string() + " --only tables,speed");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("unknown experiment 'speed'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("performance"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(CliEval, QuickTablesWithoutVtkOrPlots) {
  const auto out = tmp("eval_cli_tables");
  const auto r =
      runMfadvr("eval paper --quick --no-vtk --no-plots -q --only tables --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("report: "), std::string::npos);
  const std::string report = slurp(out / "report.md");
  EXPECT_NE(report.find("Table 2 (value and gradient), 64x64x64"), std::string::npos);
  EXPECT_NE(report.find("Machine and software"), std::string::npos);
  EXPECT_TRUE(std::filesystem::is_regular_file(out / "table1_gradient.csv"));
  EXPECT_FALSE(std::filesystem::exists(out / "plots"));
  EXPECT_TRUE(r.err.empty()) << r.err;  // -q
}

TEST(CliEval, MissingInputFileStopsBeforeWritingAnything) {
  const auto out = tmp("eval_cli_missing_volume");
  const auto r = runMfadvr("eval paper --quick --no-vtk --no-plots -q --only structured --out " +
                           out.string() + " --volume " + (out / "nowhere.nrrd").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("nowhere.nrrd"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

namespace {

// Runs one gallery with a corrupt input file as its only input: the gallery skips it, says why
// in the report, and the run exits 1.
void expectCorruptInputSkipped(const std::string& experiment, const std::string& option,
                               const std::string& fileName, const std::string& contents) {
  const auto dir = tmp("eval_cli_corrupt_" + experiment + "_input");
  std::filesystem::create_directories(dir);
  const auto bad = dir / fileName;
  std::ofstream(bad) << contents;
  const auto out = tmp("eval_cli_corrupt_" + experiment);
  const auto r =
      runMfadvr("eval paper --quick --no-vtk --no-plots -q --only " + experiment + " --data " +
                dir.string() + " --out " + out.string() + " " + option + " " + bad.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("input skipped: " + experiment + ": " + bad.string()), std::string::npos)
      << r.err;
  const std::string report = slurp(out / "report.md");
  EXPECT_NE(report.find("could not be loaded, skipped"), std::string::npos) << report;
  EXPECT_NE(report.find("Inputs skipped"), std::string::npos) << report;
}

}  // namespace

TEST(CliEval, UnreadableVolumeIsSkippedAndReported) {
  expectCorruptInputSkipped("structured", "--volume", "broken.nrrd",
                            "NRRD0004\ntype: float\ndimension: 3\nsizes: 4 4\nencoding: raw\n\n");
}

TEST(CliEval, UnreadableMeshIsSkippedAndReported) {
  expectCorruptInputSkipped(
      "unstructured", "--mesh", "broken.vtu",
      "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"4\"");
}

TEST(CliEval, CompressionStudyWritesItsTable) {
  const auto out = tmp("eval_compression");
  // No standard data: the study runs on Marschner-Lobb alone and says which files it missed.
  const auto r = runMfadvr("eval compression --quick -q --data " + (out / "no-data").string() +
                           " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = slurp(out / "compression_rd.csv");
  EXPECT_EQ(csv.rfind("volume,rate,method,bits_per_sample,volume_psnr,image_psnr,image_ssim,"
                      "memory_bytes\n",
                      0),
            0u)
      << csv;
  for (const char* method : {"mfa-coded", "mfa-ls-float32", "zfp-rate", "downsampled-cubic"})
    EXPECT_NE(csv.find(method), std::string::npos) << method;
  const std::string report = slurp(out / "report.md");
  EXPECT_NE(report.find("rate-distortion against ZFP"), std::string::npos);
  EXPECT_NE(report.find("fuel_64x64x64_uint8.raw"), std::string::npos) << "names the missing file";
  EXPECT_EQ(runMfadvr("eval compression --quick").status, 2);  // --out is required
}
