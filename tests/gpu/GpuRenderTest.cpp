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
#include "core/analytic/BuiltinSeries.h"
#include "core/encode/StructuredEncoder.h"
#include "core/encode/TimeSeriesEncoder.h"
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

// `relative`: how far the sample counts may differ. Rounding can move a sample across a mask or
// cell boundary, or a ray across the threshold; the isosurface walk's counts (evaluations per
// knot-span cell and per bracketed crossing, to a tolerance) move more (0.15 % seen on an H200).
void expectCountsAgree(const RenderStats& gpu, const RenderStats& cpu, const std::string& what,
                       double relative = 1e-3) {
  EXPECT_EQ(gpu.rays, cpu.rays) << what;
  EXPECT_EQ(gpu.raysHit, cpu.raysHit) << what;
  EXPECT_NEAR(double(gpu.samples), double(cpu.samples), relative * double(cpu.samples) + 2) << what;
  EXPECT_NEAR(double(gpu.skipped), double(cpu.skipped), relative * double(cpu.skipped) + 2) << what;
  EXPECT_NEAR(double(gpu.terminated), double(cpu.terminated), 1e-3 * double(cpu.rays) + 2) << what;
}

class Gpu : public ::testing::Test {
 protected:
  void SetUp() override {
    const gpu::CudaDeviceStatus status = gpu::cudaDeviceStatus();
    if (!status.usable) GTEST_SKIP() << status.describe();
    renderer_ = std::make_unique<CudaRenderer>();
  }

  // Renders `model` on both devices and compares. `countsAgree`: the device skips as the CPU
  // does (composite and iso blends); the other blends sample every step on the GPU, so only
  // their rays and hits are compared.
  void compareModel(const Model& model, const RenderSettings& s, const std::string& what,
                    bool countsAgree = true) {
    RenderStats cpuStats, gpuStats;
    const Image cpu = renderVolume(ModelField(model), s, &cpuStats);
    const Image gpu = renderer_->renderModel(ModelField(model), s, &gpuStats);
    ASSERT_EQ(gpu.width, cpu.width);
    const double db = psnr(gpu, cpu);
    EXPECT_GE(db, 50.0) << what;
    if (countsAgree) {
      expectCountsAgree(gpuStats, cpuStats, what, s.blend == BlendMode::Iso ? 5e-3 : 1e-3);
    } else {
      EXPECT_EQ(gpuStats.rays, cpuStats.rays) << what;
      EXPECT_NEAR(double(gpuStats.raysHit), double(cpuStats.raysHit),
                  1e-3 * double(cpuStats.rays) + 2)
          << what;
    }
    if (s.depth) expectDepthsAgree(gpu, cpu, what);
    ++compared_;
  }

  // Depth images: the same pixels have a depth, and the depths agree to a sample step (a
  // rounding can move the first contributing sample by one step).
  static void expectDepthsAgree(const Image& gpu, const Image& cpu, const std::string& what) {
    ASSERT_EQ(gpu.depth.size(), cpu.depth.size()) << what;
    std::size_t differ = 0, far = 0;
    for (std::size_t i = 0; i < cpu.depth.size(); ++i) {
      const bool a = std::isnan(gpu.depth[i]), b = std::isnan(cpu.depth[i]);
      if (a != b)
        ++differ;
      else if (!a && std::abs(gpu.depth[i] - cpu.depth[i]) > 0.0101f)
        ++far;
    }
    EXPECT_LE(differ, 2 + cpu.depth.size() / 1000) << what << ": pixels with a depth on one device";
    EXPECT_LE(far, 2 + cpu.depth.size() / 1000) << what << ": depths more than a step apart";
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

TEST_F(Gpu, EveryBlendModeWithDepthsWithAndWithoutSkipping) {
  for (const Model* m : {&mlModel(3), &maskedModel()})
    for (BlendMode blend : {BlendMode::Maximum, BlendMode::Minimum, BlendMode::Average,
                            BlendMode::Additive, BlendMode::Iso})
      for (bool skip : {true, false}) {
        const bool iso = blend == BlendMode::Iso;
        // A transparent low end, so that maximum intensity skips on the CPU.
        RenderSettings s =
            settingsFor(m->domain().min, m->domain().max, transferFunctions()[1], iso);
        s.blend = blend;
        s.skipEmptySpace = skip;
        s.depth = true;
        if (blend == BlendMode::Average) s.averageRange = std::make_pair(0.2, 0.9);
        if (iso) s.isoSurfaces = {{0.3, Vec3f(1.0f, 0.8f, 0.2f), 0.6f}, {0.7, {}, {}}};
        compareModel(*m, s,
                     std::string(blendModeName(blend)) + (m->mask().empty() ? "" : ", masked") +
                         (skip ? ", skipping" : ", no skipping"),
                     iso);
      }
  EXPECT_EQ(compared_, 20);
}

TEST_F(Gpu, ClippingPlanesAndCroppingBox) {
  for (const Model* m : {&mlModel(3), &maskedModel()})
    for (BlendMode blend : {BlendMode::Composite, BlendMode::Maximum, BlendMode::Iso}) {
      const Vec3d lo = m->domain().min, hi = m->domain().max, mid = 0.5 * (lo + hi);
      RenderSettings s = settingsFor(lo, hi, transferFunctions()[0], true);
      s.blend = blend;
      if (blend == BlendMode::Iso) s.isoSurfaces = {{0.5, {}, {}}};
      s.depth = true;
      s.clipPlanes = {{mid, Vec3d(1, 0.3, 0).normalized()}, {mid, Vec3d(0, 0.2, -1).normalized()}};
      s.crop = DomainBox{lo + 0.1 * (hi - lo), hi - 0.05 * (hi - lo)};
      compareModel(*m, s,
                   std::string(blendModeName(blend)) + " clipped and cropped" +
                       (m->mask().empty() ? "" : ", masked"),
                   blend != BlendMode::Maximum);
    }
}

TEST_F(Gpu, CurvatureOnIsosurfaces) {
  const Model& m = mlModel(3);
  RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[0], true);
  s.blend = BlendMode::Iso;
  s.isoSurfaces = {{0.5, {}, {}}};
  s.curvatureTransferFunction =
      curvaturePreset("ridges-valleys", 8.0 / (m.domain().max - m.domain().min).norm());
  compareModel(m, s, "ridges and valleys on an isosurface");
  s.curvatureTransferFunction.reset();
  s.contourPixels = 1.5;
  compareModel(m, s, "contours on an isosurface");
}

TEST_F(Gpu, TimeVaryingModelsAtInstantsBetweenTheSteps) {
  const BuiltinVolumeSeries series("builtin:orbiting-blobs:20x20x20x5");
  EncodeOptions spatial;
  spatial.degree = {3, 3, 3};
  spatial.controlCounts = {14, 14, 14};
  const TimeVaryingModel tv = encodeTimeSeries(series, spatial, TimeSeriesOptions{}, nullptr);
  ASSERT_TRUE(tv.hasTime());
  for (double t : {tv.timeAxis().begin, 0.37 * tv.timeAxis().begin + 0.63 * tv.timeAxis().end}) {
    const Model m = tv.at(t);
    RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[5], true);
    s.transferFunction = transferFunctions()[5].resolved(m.valueMin(), m.valueMax());
    compareModel(m, s, "time " + std::to_string(t));
  }
}

TEST_F(Gpu, MeshBoundaryIsExactOnTheGpuToo) {
  const Model& m = boundedModel();
  for (bool shade : {false, true})
    for (bool skip : {true, false}) {
      RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[3], shade);
      s.skipEmptySpace = skip;
      compareModel(
          m, s,
          std::string("mesh boundary") + (shade ? ", shaded" : "") + (skip ? ", skipping" : ""));
    }
  for (BlendMode blend : {BlendMode::Maximum, BlendMode::Iso}) {
    RenderSettings s = settingsFor(m.domain().min, m.domain().max, transferFunctions()[1], true);
    s.blend = blend;
    s.depth = true;
    if (blend == BlendMode::Iso) s.isoSurfaces = {{0.5, {}, {}}};
    compareModel(m, s, std::string("mesh boundary, ") + blendModeName(blend),
                 blend == BlendMode::Iso);
  }
  // The mask alone (no boundary) gives another image: the boundary is what the GPU used.
  Model maskOnly = m;
  maskOnly.setBoundary(nullptr);
  const RenderSettings s =
      settingsFor(m.domain().min, m.domain().max, transferFunctions()[3], true);
  const Image bounded = renderer_->renderModel(ModelField(m), s, nullptr);
  const Image masked = renderer_->renderModel(ModelField(maskOnly), s, nullptr);
  EXPECT_LT(psnr(bounded, masked), 40.0);
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
    expectCountsAgree(gpuStats, cpuStats, shade ? "trilinear, shaded" : "trilinear");
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
