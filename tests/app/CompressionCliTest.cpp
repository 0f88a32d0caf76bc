// `encode` with control-point coding and budgets, and `decode`, end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "app/CliRunner.h"
#include "core/model/ModelFile.h"

namespace mfadvr {
namespace {

using test::runMfadvr;

// A 20 x 18 x 16 8-bit scan: a smooth blob with a sharp-edged cube in it.
std::string writeByteVolume(const std::filesystem::path& dir, std::vector<std::uint8_t>* values) {
  const auto path = dir / "scan_20x18x16_uint8.raw";
  values->clear();
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 18; ++y)
      for (int x = 0; x < 20; ++x) {
        const double r2 = (x - 9.5) * (x - 9.5) + (y - 8.5) * (y - 8.5) + (z - 7.5) * (z - 7.5);
        double v = 200.0 * std::exp(-r2 / 40.0);
        if (x > 4 && x < 9 && y > 3 && y < 8 && z > 5 && z < 10) v += 50.0;
        values->push_back(static_cast<std::uint8_t>(std::lround(v)));
      }
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(values->data()),
             static_cast<std::streamsize>(values->size()));
  return path.string();
}

nlohmann::json jsonOf(const test::CliResult& r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "): " << r.out << r.err;
    return {};
  }
}

// --dequantize: the smoothest model within half a step of every sample decodes back exactly
// too, and says so in its report; bad steps and combinations are usage errors.
TEST(CompressionCli, DequantizedScansDecodeBackExactly) {
  const auto dir = test::scratchDir();
  std::vector<std::uint8_t> input;
  const std::string raw = writeByteVolume(dir, &input);
  const std::string model = (dir / "smooth.mfa").string();
  const auto r = runMfadvr("encode " + raw + " --dequantize --json -q -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = jsonOf(r);
  EXPECT_EQ(j["dequantize"]["step"], 1.0);
  EXPECT_TRUE(j["dequantize"]["rounds_back"].get<bool>());
  EXPECT_GT(j["dequantize"]["iterations"].get<int>(), 1);
  EXPECT_LE(j["max_error"].get<double>(), 0.5);
  EXPECT_EQ(j["coding"]["method"], "zfp");
  const std::string out = (dir / "back.raw").string();
  ASSERT_EQ(runMfadvr("decode " + model + " -q -o " + out).status, 0);
  const std::string back = test::slurp(out);
  ASSERT_EQ(back.size(), input.size());
  EXPECT_EQ(std::memcmp(back.data(), input.data(), input.size()), 0);
  const auto text = runMfadvr("encode " + raw + " --dequantize 1");
  EXPECT_NE(text.out.find("dequantize      step 1"), std::string::npos) << text.out;

  EXPECT_EQ(runMfadvr("encode " + raw + " --dequantize -1 -q").status, 2);
  EXPECT_EQ(runMfadvr("encode " + raw + " --dequantize abc -q").status, 2);
  const auto offLattice = runMfadvr("encode " + raw + " --dequantize 0.3 -q");
  EXPECT_NE(offLattice.status, 0);
  EXPECT_NE(offLattice.err.find("not multiples of the step"), std::string::npos) << offLattice.err;
  const auto floats = runMfadvr("encode builtin:marschner-lobb:12 --dequantize -q");
  EXPECT_NE(floats.status, 0);
  EXPECT_NE(floats.err.find("give the step"), std::string::npos) << floats.err;
}

TEST(CompressionCli, IntegerScansAreCodedByDefaultAndDecodeBackExactly) {
  const auto dir = test::scratchDir();
  std::vector<std::uint8_t> input;
  const std::string raw = writeByteVolume(dir, &input);
  const std::string model = (dir / "scan.mfa").string();
  const auto r = runMfadvr("encode " + raw + " --json -q -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = jsonOf(r);
  EXPECT_EQ(j["coding"]["method"], "zfp");
  EXPECT_LE(j["model_bytes"].get<std::int64_t>(),
            static_cast<std::int64_t>(input.size()) + 2048);  // header and knots
  EXPECT_LT(j["max_error"].get<double>(), 0.5);
  EXPECT_EQ(static_cast<std::int64_t>(std::filesystem::file_size(model)),
            j["model_bytes"].get<std::int64_t>());

  const std::string out = (dir / "back.raw").string();
  const auto d = runMfadvr("decode " + model + " -q -o " + out);
  ASSERT_EQ(d.status, 0) << d.err;
  EXPECT_NE(d.out.find("20 x 18 x 16 uint8"), std::string::npos) << d.out;
  const std::string back = test::slurp(out);
  ASSERT_EQ(back.size(), input.size());
  EXPECT_EQ(std::memcmp(back.data(), input.data(), input.size()), 0);
  // Written atomically: no temporary file is left beside it.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();

  // info names the coding.
  const auto info = runMfadvr("info " + model);
  EXPECT_NE(info.out.find("control coding  zfp"), std::string::npos) << info.out;
  // --lossless: the fitted model bit for bit, larger than the input.
  const auto l = runMfadvr("encode " + raw + " --lossless --json -q");
  ASSERT_EQ(l.status, 0) << l.err;
  EXPECT_EQ(jsonOf(l)["coding"]["method"], "lossless");
}

// ZFP in a process that has CFITSIO loaded first, as every ParaView process has: its functions
// named stream_open, stream_close, ... take the global names, and ZFP must still decode
// (ZfpLibrary.h). Preloading it puts it first; the sanitizers' runtime must come first instead.
TEST(CompressionCli, ZfpModelsDecodeWithCfitsioLoadedFirst) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "LD_PRELOAD ahead of the AddressSanitizer runtime is refused by it; the "
                  "release build runs this test, and mfadvr_zfp_isolation_tests covers both";
#endif
  const char* cfitsio = "/usr/lib/x86_64-linux-gnu/libcfitsio.so.10";
  if (!std::filesystem::exists(cfitsio)) GTEST_SKIP() << cfitsio << " is not installed";
  const auto dir = test::scratchDir();
  std::vector<std::uint8_t> input;
  const std::string raw = writeByteVolume(dir, &input);
  const std::string model = (dir / "scan.mfa").string();
  const std::string preload = std::string("LD_PRELOAD=") + cfitsio;
  const auto e = runMfadvr("encode " + raw + " -q -o " + model, preload);
  ASSERT_EQ(e.status, 0) << e.err;
  const std::string out = (dir / "back.raw").string();
  const auto d = runMfadvr("decode " + model + " -q -o " + out, preload);
  ASSERT_EQ(d.status, 0) << d.err;
  const std::string back = test::slurp(out);
  ASSERT_EQ(back.size(), input.size());
  EXPECT_EQ(std::memcmp(back.data(), input.data(), input.size()), 0);
}

// A ZFP that cannot be loaded is an error that says so and what to do, with no output.
TEST(CompressionCli, AnUnusableZfpIsAClearError) {
  const auto dir = test::scratchDir();
  std::vector<std::uint8_t> input;
  const std::string raw = writeByteVolume(dir, &input);
  const std::string model = (dir / "scan.mfa").string();
  ASSERT_EQ(runMfadvr("encode " + raw + " -q -o " + model).status, 0);
  const std::string out = (dir / "back.raw").string();
  const auto d = runMfadvr("decode " + model + " -q -o " + out,
                           "MFADVR_ZFP_LIBRARY=" + (dir / "no-such-libzfp.so").string());
  EXPECT_NE(d.status, 0);
  EXPECT_NE(d.err.find("ZFP"), std::string::npos) << d.err;
  EXPECT_NE(d.err.find("no-such-libzfp.so"), std::string::npos) << d.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  // Models without zfp-coded control points need no ZFP.
  const std::string plain = (dir / "plain.mfa").string();
  const auto f = runMfadvr("encode " + raw + " --coding float32 -q -o " + plain,
                           "MFADVR_ZFP_LIBRARY=/nonexistent");
  EXPECT_EQ(f.status, 0) << f.err;
}

TEST(CompressionCli, BudgetsAreRespectedAndReported) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "ml.mfa").string();
  const auto r =
      runMfadvr("encode builtin:marschner-lobb:32 --bits-per-sample 1 --json -q -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = jsonOf(r);
  const double samples = 32.0 * 32 * 32;
  // The control points take at most the budget; the header and knots add under 2 KB.
  EXPECT_LE(j["model_bytes"].get<double>(), samples / 8 + 2048);
  EXPECT_NE(j["coding"]["note"].get<std::string>().find("candidates"), std::string::npos);

  const auto p = runMfadvr("encode builtin:marschner-lobb:32 --psnr 60 --json -q");
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_GE(jsonOf(p)["psnr"].get<double>(), 60.0);

  // The text report shows the rate and the PSNR.
  const auto t = runMfadvr("encode builtin:marschner-lobb:32 --rms-error 1e-3 -q");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_NE(t.out.find("bits/sample"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("psnr"), std::string::npos) << t.out;

  const auto impossible = runMfadvr("encode builtin:marschner-lobb:16 --psnr 300 -q");
  EXPECT_EQ(impossible.status, 1);
  EXPECT_NE(impossible.err.find("no model"), std::string::npos) << impossible.err;
}

TEST(CompressionCli, ContradictingOptionsAreUsageErrors) {
  for (const char* args : {"--coding gzip", "--coding lossless --coding-tolerance 0.1",
                           "--psnr 40 --bits-per-sample 1", "--psnr -3", "--coding-tolerance 0",
                           "--psnr 40 --coding-tolerance 0.5", "--lossless --coding zfp"}) {
    const auto r = runMfadvr(std::string("encode builtin:marschner-lobb:8 -q ") + args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  }
  const auto adaptive = runMfadvr("encode builtin:marschner-lobb:8 -q --psnr 40 --max-error 1e-2");
  EXPECT_EQ(adaptive.status, 1) << adaptive.err;
  EXPECT_NE(adaptive.err.find("--max-error"), std::string::npos) << adaptive.err;
}

TEST(CompressionCli, DecodeWritesGridsAndRefusesWhatItCannot) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "ml.mfa").string();
  ASSERT_EQ(runMfadvr("encode builtin:marschner-lobb:12 -q -o " + model).status, 0);
  const std::string nrrd = (dir / "ml.nrrd").string();
  const auto d = runMfadvr("decode " + model + " -q --samples 7,6,5 --type float32 -o " + nrrd);
  ASSERT_EQ(d.status, 0) << d.err;
  const std::string bytes = test::slurp(nrrd);
  const size_t body = bytes.find("\n\n");
  ASSERT_NE(body, std::string::npos);
  EXPECT_NE(bytes.find("sizes: 7 6 5"), std::string::npos);
  EXPECT_EQ(bytes.size() - body - 2, 7u * 6 * 5 * 4);
  // The first sample is the model's value at its box corner.
  float first;
  std::memcpy(&first, bytes.data() + body + 2, 4);
  EXPECT_NEAR(first, loadModel(model).value(Vec3d(-1, -1, -1)), 1e-5);

  const std::string nhdr = (dir / "ml.nhdr").string();
  ASSERT_EQ(runMfadvr("decode " + model + " -q -o " + nhdr).status, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "ml.raw"));
  EXPECT_NE(test::slurp(nhdr).find("data file: ml.raw"), std::string::npos);

  EXPECT_EQ(runMfadvr("decode " + model + " -q -o " + (dir / "x.png").string()).status, 2);
  EXPECT_EQ(runMfadvr("decode " + model + " -q --type uint128 -o " + nrrd).status, 2);
  EXPECT_EQ(runMfadvr("decode " + model + " -q --samples 1 -o " + nrrd).status, 2);
  const auto missing = runMfadvr("decode " + (dir / "none.mfa").string() + " -q -o " + nrrd);
  EXPECT_EQ(missing.status, 1);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

}  // namespace
}  // namespace mfadvr
