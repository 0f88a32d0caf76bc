// `--device auto|cpu|cuda` of `mfadvr render`: the choice is reported, `auto` falls back to the
// CPU with the reason, `cuda` fails cleanly (exit 1, no output file) where no GPU can render, and
// where one can, its image agrees with the CPU's.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "TestSupport.h"
#include "app/CliRunner.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngFile.h"

namespace mfadvr {
namespace {

using test::runMfadvr;

const std::string kScene = "render builtin:marschner-lobb:16 --size 48x40 --shade --json";

TEST(CliDevice, CpuAndAutoReportTheirDevice) {
  const auto dir = test::scratchDir();
  const std::string cpuPng = (dir / "device_cpu.png").string();
  const auto cpu = runMfadvr(kScene + " --device cpu -o " + cpuPng);
  ASSERT_EQ(cpu.status, 0) << cpu.err;
  const auto jc = nlohmann::json::parse(cpu.out);
  EXPECT_EQ(jc["device"], "cpu");
  EXPECT_NE(jc["device_description"].get<std::string>().find("CPU"), std::string::npos);

  const std::string autoPng = (dir / "device_auto.png").string();
  const auto chosen = runMfadvr(kScene + " --device auto -o " + autoPng);
  ASSERT_EQ(chosen.status, 0) << chosen.err;
  const auto ja = nlohmann::json::parse(chosen.out);
  const std::string device = ja["device"];
  ASSERT_TRUE(device == "cpu" || device == "cuda") << device;
  const auto metrics = compareImages(readPng(autoPng), readPng(cpuPng));
  if (device == "cpu") {
    // The fallback says why the GPU was not used.
    EXPECT_NE(ja["device_description"].get<std::string>().find("; "), std::string::npos)
        << ja["device_description"];
    EXPECT_TRUE(std::isinf(metrics.psnr)) << "the same CPU renderer gave another image";
  } else {
    EXPECT_GE(metrics.psnr, 50.0);
  }
}

TEST(CliDevice, CudaFailsCleanlyWithoutAGpuAndMatchesTheCpuWithOne) {
  const auto dir = test::scratchDir();
  const auto probe = runMfadvr(kScene + " --device auto -o " + (dir / "probe.png").string());
  ASSERT_EQ(probe.status, 0) << probe.err;
  const bool gpu = nlohmann::json::parse(probe.out)["device"] == "cuda";
  const auto png = dir / "device_cuda.png";
  std::filesystem::remove(png);
  const auto r = runMfadvr(kScene + " --device cuda -o " + png.string());
  if (!gpu) {
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("device 'cuda'"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(png));
  } else {
    ASSERT_EQ(r.status, 0) << r.err;
    const auto cpu = runMfadvr(kScene + " --device cpu -o " + (dir / "cpu_ref.png").string());
    ASSERT_EQ(cpu.status, 0);
    EXPECT_GE(compareImages(readPng(png.string()), readPng((dir / "cpu_ref.png").string())).psnr,
              50.0);
  }
}

TEST(CliDevice, MethodsTheGpuDoesNotRenderAreRefusedOrFallBack) {
  const auto dir = test::scratchDir();
  const auto png = dir / "device_refused.png";
  std::filesystem::remove(png);
  for (const std::string args :
       {"--method tricubic", "--gradient central", "--method vtk-fixedpoint"}) {
    const auto r = runMfadvr(kScene + " --device cuda " + args + " -o " + png.string());
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_NE(r.err.find("device 'cuda'"), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(png)) << args;
  }
  const auto fallback = runMfadvr(kScene + " --device auto --method tricubic -o " + png.string());
  ASSERT_EQ(fallback.status, 0) << fallback.err;
  const auto j = nlohmann::json::parse(fallback.out);
  EXPECT_EQ(j["device"], "cpu");
  EXPECT_NE(j["device_description"].get<std::string>().find("tricubic"), std::string::npos);
  EXPECT_NE(runMfadvr(kScene + " --device tpu -o " + png.string()).status, 0);
}

}  // namespace
}  // namespace mfadvr
