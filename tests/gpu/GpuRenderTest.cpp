// The CUDA backend against the CPU ray caster: the same scenes and settings through both
// drivers of the shared per-ray integration; the images agree up to float rounding (PSNR >= 50 dB
// on 8-bit RGB) and the counters nearly exactly. Without a usable GPU every GPU test skips and
// prints why; the device-status tests run everywhere.
//
// This program is self-contained on purpose (synthetic scenes, no data files): scripts/
// pack-gpu-check.sh bundles it with its shared libraries for a GPU machine without packages.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "GpuTestScenes.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/field/GridField.h"
#include "core/field/GridFilters.h"
#include "core/field/ModelField.h"
#include "core/image/ImageMetrics.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"
#include "gpu/CudaRenderer.h"

namespace mfadvr {
namespace {

using gpu::CudaRenderer;
using namespace test;

double psnr(const Image& a, const Image& b) {
  return compareImages(toImage8(a), toImage8(b)).psnr;
}

void expectCountsAgree(const RenderStats& gpu, const RenderStats& cpu) {
  EXPECT_EQ(gpu.rays, cpu.rays);
  EXPECT_EQ(gpu.raysHit, cpu.raysHit);
  // Rounding can move a sample across a mask or cell boundary, or a ray across the threshold.
  EXPECT_NEAR(double(gpu.samples), double(cpu.samples), 1e-3 * double(cpu.samples) + 2);
  EXPECT_NEAR(double(gpu.skipped), double(cpu.skipped), 1e-3 * double(cpu.skipped) + 2);
  EXPECT_NEAR(double(gpu.terminated), double(cpu.terminated), 1e-3 * double(cpu.rays) + 2);
}

class Gpu : public ::testing::Test {
 protected:
  void SetUp() override {
    const gpu::CudaDeviceStatus status = gpu::cudaDeviceStatus();
    if (!status.usable) GTEST_SKIP() << status.describe();
    renderer_ = std::make_unique<CudaRenderer>();
  }

  // Renders `model` on both devices and compares.
  void compareModel(const Model& model, const RenderSettings& s, const std::string& what) {
    RenderStats cpuStats, gpuStats;
    const Image cpu = renderVolume(ModelField(model), s, &cpuStats);
    const Image gpu = renderer_->renderModel(ModelField(model), s, &gpuStats);
    ASSERT_EQ(gpu.width, cpu.width);
    const double db = psnr(gpu, cpu);
    EXPECT_GE(db, 50.0) << what;
    expectCountsAgree(gpuStats, cpuStats);
    ++compared_;
  }

  std::unique_ptr<CudaRenderer> renderer_;
  int compared_ = 0;
};

TEST_F(Gpu, ModelImagesMatchTheCpuForEveryDegree) {
  for (int p = 1; p <= 5; ++p)  // 5: the run-time-degree kernel with equal degrees
    for (bool shade : {false, true}) {
      const Model& m = mlModel(p);
      compareModel(m, settingsFor(m.domain().min, m.domain().max, transferFunctions()[0], shade),
                   "degree " + std::to_string(p) + (shade ? " shaded" : ""));
    }
  const Model& mixed = mixedDegreeModel();
  compareModel(mixed,
               settingsFor(mixed.domain().min, mixed.domain().max, transferFunctions()[1], true),
               "mixed degrees");
}

TEST_F(Gpu, EveryTransferFunctionWithAndWithoutSkipping) {
  for (const Model* m : {&mlModel(3), &maskedModel()})
    for (const TransferFunction& tf : transferFunctions())
      for (bool skip : {true, false}) {
        RenderSettings s = settingsFor(m->domain().min, m->domain().max, tf, true);
        s.skipEmptySpace = skip;
        compareModel(*m, s,
                     std::string(m->mask().empty() ? "unmasked" : "masked") +
                         (skip ? ", skipping" : ", no skipping"));
      }
  EXPECT_EQ(compared_, 24);
}

TEST_F(Gpu, SkippingLeavesTheGpuImageUnchanged) {
  const Model& m = maskedModel();
  RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[2], true);
  RenderStats on, off;
  const Image a = renderer_->renderModel(ModelField(m), s, &on);
  s.skipEmptySpace = false;
  const Image b = renderer_->renderModel(ModelField(m), s, &off);
  EXPECT_GT(on.skipped, 0);
  EXPECT_EQ(off.skipped, 0);
  EXPECT_GE(psnr(a, b), 60.0);
}

TEST_F(Gpu, ShadingWithSeveralLightsAndParallelProjection) {
  const Model& m = mlModel(2);
  RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[0], true);
  s.lighting.lights.push_back({Vec3d(1, -1, -0.5), Vec3f(1.0f, 0.6f, 0.3f), 0.8f});
  s.lighting.lights.push_back({Vec3d(-1, 0.5, -1), Vec3f(0.3f, 0.5f, 1.0f), 0.6f});
  s.lighting.specular = 0.5f;
  compareModel(m, s, "three lights");
  s.camera.parallelProjection = true;
  compareModel(m, s, "parallel projection");
}

TEST_F(Gpu, EarlyTerminationAndRayEnds) {
  const Model& m = mlModel(3);
  RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[3], false);
  s.earlyTerminationOpacity = 0.5;
  compareModel(m, s, "early termination at 0.5");
  s.rayEnd.assign(std::size_t(s.width) * s.height, 0.0f);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      s.rayEnd[std::size_t(y) * s.width + x] = x < s.width / 2 ? 2.0f + 0.01f * y : INFINITY;
  compareModel(m, s, "ray ends");
}

TEST_F(Gpu, ModelIsKeptBetweenFramesAndReplacedByAnother) {
  const Model& a = mlModel(2);
  const Model& b = mlModel(3);
  const RenderSettings s =
      settingsFor(a.domain().min, a.domain().max, transferFunctions()[0], true);
  const Image a1 = renderer_->renderModel(ModelField(a), s, nullptr);
  const Image b1 = renderer_->renderModel(ModelField(b), s, nullptr);
  const Image a2 = renderer_->renderModel(ModelField(a), s, nullptr);
  EXPECT_EQ(a1.rgba, a2.rgba);
  EXPECT_NE(a1.rgba, b1.rgba);
}

TEST_F(Gpu, GradientOpacityAndTwoDimensionalTransferFunctions) {
  const Model& m = mlModel(3);
  for (bool shade : {false, true}) {
    RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[0], shade);
    s.gradientOpacity = {{0.5, 0.0f}, {2.0, 1.0f}};
    compareModel(m, s, std::string("gradient opacity") + (shade ? ", shaded" : ""));
    s.gradientOpacity.clear();
    s.transferFunction2D = stripedTransferFunction2D();
    compareModel(m, s, std::string("2-D transfer function") + (shade ? ", shaded" : ""));
  }
}

TEST_F(Gpu, CurvatureTransferFunctionsAndContours) {
  const Model& m = mlModel(3);
  const double k = 8.0 / (m.domain().max - m.domain().min).norm();
  for (bool shade : {false, true}) {
    RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[0], shade);
    s.curvatureTransferFunction = curvaturePreset("mean", k);
    compareModel(m, s, std::string("mean curvature") + (shade ? ", shaded" : ""));
    s.curvatureTransferFunction.reset();
    s.contourPixels = 2.0;
    compareModel(m, s, std::string("contours") + (shade ? ", shaded" : ""));
  }
}

TEST_F(Gpu, TrilinearMatchesTheCpu) {
  const GridField<TrilinearFilter> field(mlGrid());
  for (bool shade : {false, true}) {
    const RenderSettings s = settingsFor(field.boxMin(), field.boxMax(),
                                         transferFunctions()[5].resolved(-0.1, 1.1), shade);
    RenderStats cpuStats, gpuStats;
    const Image cpu = renderVolume(field, s, &cpuStats);
    const Image gpu = renderer_->renderTrilinear(field.grid(), s, &gpuStats);
    EXPECT_GE(psnr(gpu, cpu), 50.0) << (shade ? "shaded" : "unshaded");
    expectCountsAgree(gpuStats, cpuStats);
  }
}

TEST(GpuDevice, StatusIsConsistent) {
  const gpu::CudaDeviceStatus s = gpu::cudaDeviceStatus();
  if (s.usable) {
    EXPECT_TRUE(s.reason.empty());
    EXPECT_FALSE(s.name.empty());
    EXPECT_GE(s.computeMajor * 10 + s.computeMinor, 75);
    EXPECT_GT(s.totalMemory, 0u);
    EXPECT_GE(s.driverVersion, 12000);
  } else {
    EXPECT_FALSE(s.reason.empty());
    EXPECT_NE(s.describe().find(s.reason), std::string::npos);
    std::printf("no usable CUDA GPU here: %s\n", s.reason.c_str());
  }
  EXPECT_GE(s.runtimeVersion, 12000);  // the toolkit this was built with
}

TEST(GpuDevice, RendererRefusesWithTheReasonWhenNoGpuIsUsable) {
  const gpu::CudaDeviceStatus s = gpu::cudaDeviceStatus();
  if (s.usable) GTEST_SKIP() << "a GPU is usable here: " << s.describe();
  try {
    CudaRenderer r;
    FAIL() << "constructed without a usable GPU";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(s.reason), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mfadvr
