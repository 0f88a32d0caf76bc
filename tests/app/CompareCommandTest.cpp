// End-to-end tests of `mfadvr compare`: text and JSON output, exit codes, the difference image.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "TestSupport.h"
#include "app/CliRunner.h"
#include "core/image/PngFile.h"

namespace mfadvr {
namespace {

using Result = test::CliResult;
using test::slurp;
Result run(const std::string& args) {
  return test::runMfadvr(args);
}

Image8 gradient(int w, int h, int channels, int offset) {
  Image8 im{w, h, channels, std::vector<std::uint8_t>(static_cast<size_t>(w) * h * channels)};
  for (size_t i = 0; i < im.data.size(); ++i)
    im.data[i] = static_cast<std::uint8_t>((i * 7 + offset) % 256);
  return im;
}

TEST(CliCompare, IdenticalImagesGiveNullPsnrInJson) {
  const auto dir = test::scratchDir();
  const std::string a = (dir / "a.png").string(), b = (dir / "b.png").string();
  writePng(a, gradient(20, 15, 3, 0));
  Image8 withAlpha = gradient(20, 15, 3, 0);
  // Same RGB with an alpha channel added: alpha is ignored, so still identical.
  Image8 rgba{20, 15, 4, {}};
  for (size_t i = 0; i < withAlpha.data.size(); i += 3) {
    rgba.data.insert(rgba.data.end(), withAlpha.data.begin() + i, withAlpha.data.begin() + i + 3);
    rgba.data.push_back(static_cast<std::uint8_t>(i));
  }
  writePng(b, rgba);
  Result r = run("compare " + a + " " + b + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["a"], a);
  EXPECT_EQ(j["b"], b);
  EXPECT_EQ(j["width"], 20);
  EXPECT_EQ(j["height"], 15);
  EXPECT_EQ(j["mse"], 0.0);
  EXPECT_TRUE(j["psnr"].is_null());
  EXPECT_NEAR(j["ssim"].get<double>(), 1.0, 1e-12);
  EXPECT_EQ(j["identical"], true);
  for (const char* c : {"r", "g", "b"}) {
    EXPECT_EQ(j["channels"][c]["mse"], 0.0) << c;
    EXPECT_TRUE(j["channels"][c]["psnr"].is_null()) << c;
  }
  r = run("compare " + a + " " + b);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("inf"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("identical"), std::string::npos) << r.out;
}

TEST(CliCompare, DifferentImagesAndDiffOutput) {
  const auto dir = test::scratchDir();
  const std::string a = (dir / "a.png").string(), b = (dir / "b.png").string(),
                    d = (dir / "d.png").string();
  writePng(a, gradient(16, 12, 3, 0));
  writePng(b, gradient(16, 12, 3, 2));
  Result r = run("compare " + a + " " + b + " --json --diff " + d + " --gain 10");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["identical"], false);
  EXPECT_GT(j["mse"].get<double>(), 0.0);
  EXPECT_GT(j["psnr"].get<double>(), 0.0);
  EXPECT_LT(j["ssim"].get<double>(), 1.0);
  ASSERT_TRUE(std::filesystem::exists(d));
  const Image8 diff = readPng(d);
  EXPECT_EQ(diff.width, 16);
  EXPECT_EQ(diff.height, 12);
  EXPECT_EQ(diff.channels, 3);
  EXPECT_EQ(diff.data[0], 20);  // |0 - 2| * 10

  r = run("compare " + a + " " + b);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* s : {"MSE", "PSNR", "SSIM", "mean"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << " in " << r.out;
  EXPECT_EQ(run("compare --help").status, 0);
}

TEST(CliCompare, FailuresExitOne) {
  const auto dir = test::scratchDir();
  const std::string a = (dir / "a.png").string(), b = (dir / "b.png").string(),
                    d = (dir / "d.png").string();
  writePng(a, gradient(16, 12, 3, 0));
  writePng(b, gradient(12, 16, 3, 0));
  Result r = run("compare " + a + " " + b + " --diff " + d);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("differ in size"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(d));

  r = run("compare " + a + " " + (dir / "missing.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("missing.png"), std::string::npos) << r.err;
  std::ofstream(dir / "junk.png") << "not a png at all";
  r = run("compare " + (dir / "junk.png").string() + " " + a);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("not a PNG"), std::string::npos) << r.err;

  r = run("compare " + a + " " + a + " --diff " + (dir / "nowhere" / "d.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(run("compare " + a).status, 2);
  EXPECT_EQ(run("compare " + a + " " + a + " --gain -1").status, 2);
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
}

}  // namespace
}  // namespace mfadvr
