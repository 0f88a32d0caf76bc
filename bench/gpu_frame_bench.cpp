// Frame time of the CUDA backend against the CPU ray caster in the same run (docs/benchmarks.md):
// shaded 1024x1024 frames of a 256^3 degree-3 model and a 512^3 degree-2 model of Marschner-Lobb.
//
//   build/release/bench/mfadvr_gpu_bench [--size 1024x1024] [--frames 5] [--cpu-frames 2]
//                                       [--scenes 256:3,512:2] [--no-cpu]
//                                       [--model FILE.mfa ... [--tf step:0.2]]
//                                       [--blend MODE [--iso F]]
//
// The control points are the function's samples on the control grid (no fit: the frame time
// does not depend on how control points were found, and a 512^3 fit would dominate the run).
// Frame times are medians; the GPU's include the per-frame uploads (transfer-function table,
// empty-space flags) and the image's read-back, its kernel time is listed apart. The first GPU
// frame (model upload, kernel load) is reported separately. Without a usable GPU it says why and
// measures the CPU alone. `--model` adds scenes of saved models (a sparse scan: the TF hides the
// air), each rendered with empty-space skipping on and off on both devices. Self-contained:
// scripts/pack-gpu-check.sh bundles it for a GPU machine. `--blend` renders every scene in
// another blend mode (as render --blend); the isosurface of `--blend iso` is at the fraction
// `--iso` of each model's value range.
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "core/analytic/BuiltinFunction.h"
#include "core/field/ModelField.h"
#include "core/image/ImageMetrics.h"
#include "core/model/ModelFile.h"
#include "core/render/BlendMode.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/RayCaster.h"
#include "gpu/CudaRenderer.h"

namespace mfadvr {
namespace {

struct Scene {
  int n = 256, degree = 3;
};

Model sampledModel(const BuiltinFunction& f, int n, int degree) {
  const Vec3d lo = BuiltinFunction::domainMin(), hi = BuiltinFunction::domainMax();
  std::vector<float> ctrl(std::size_t(n) * n * n);
  const double h = (hi[0] - lo[0]) / (n - 1);
  tbb::parallel_for(0, n, [&](int k) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        ctrl[i + std::size_t(n) * (j + std::size_t(n) * k)] =
            static_cast<float>(f.value(Vec3d(lo[0] + i * h, lo[1] + j * h, lo[2] + k * h)));
  });
  const KnotVector knots = KnotVector::clampedUniform(degree, n);
  return Model(TensorBSpline({knots, knots, knots}, std::move(ctrl)), DomainBox{lo, hi}, 0.0, 1.0);
}

// A shaded frame of the whole model seen from (azimuth, elevation) degrees.
RenderSettings shadedFrame(const Model& m, int width, int height, double azimuth,
                           double elevation) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.camera.resetToBounds(m.domain().min, m.domain().max);
  s.camera.azimuth(azimuth);
  s.camera.elevation(elevation);
  s.shade = true;
  return s;
}

RenderSettings sceneSettings(const Model& m, int width, int height, int n) {
  RenderSettings s = shadedFrame(m, width, height, 30, 20);
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{0.0, Vec3f(0.2f, 0.3f, 1.0f)}, {1.0, Vec3f(1.0f, 0.8f, 0.3f)}};
  s.transferFunction.opacity = {{0.0, 0.0f}, {0.45, 0.0f}, {0.55, 0.8f}, {1.0, 0.8f}};
  const double spacing = (m.domain().max[0] - m.domain().min[0]) / (n - 1);
  s.sampleDistance = 0.5 * spacing;
  s.opacityUnitDistance = spacing;
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string cpuName() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

// A saved model, shaded, camera at 20/10 degrees, step half the smallest control spacing.
RenderSettings modelSettings(const Model& m, int width, int height, const std::string& tf) {
  RenderSettings s = shadedFrame(m, width, height, 20, 10);
  s.transferFunction = parseTransferFunction(tf, "").resolved(m.valueMin(), m.valueMax());
  double spacing = 1e300;
  for (int a = 0; a < 3; ++a)
    spacing = std::min(spacing, (m.domain().max[a] - m.domain().min[a]) /
                                    std::max(1, m.spline().knots(a).controlCount() - 1));
  s.sampleDistance = 0.5 * spacing;
  s.opacityUnitDistance = spacing;
  return s;
}

// `s` in the blend mode `blend`; an isosurface at the fraction `isoFraction` of the value range.
RenderSettings withBlend(RenderSettings s, const Model& m, BlendMode blend, double isoFraction) {
  s.blend = blend;
  if (blend == BlendMode::Iso)
    s.isoSurfaces = {{m.valueMin() + isoFraction * (m.valueMax() - m.valueMin()), {}, {}}};
  return s;
}

// Median frame and the last frame's image and counts of one device, skipping on or off.
struct Timed {
  double frame = 0.0, kernel = 0.0, first = 0.0;
  RenderStats stats;
  Image image;
};

Timed timeFrames(gpu::CudaRenderer* gpuRenderer, const ModelField& field, const RenderSettings& s,
                 int frames) {
  Timed t;
  std::vector<double> times, kernel;
  t.image =
      gpuRenderer ? gpuRenderer->renderModel(field, s, &t.stats) : renderVolume(field, s, &t.stats);
  t.first = t.stats.seconds;
  for (int i = 0; i < std::max(frames, 1); ++i) {
    t.image = gpuRenderer ? gpuRenderer->renderModel(field, s, &t.stats)
                          : renderVolume(field, s, &t.stats);
    times.push_back(t.stats.seconds);
    if (gpuRenderer) kernel.push_back(gpuRenderer->lastKernelSeconds());
  }
  t.frame = median(times);
  if (!kernel.empty()) t.kernel = median(kernel);
  return t;
}

void runModelScene(const std::string& path, const std::string& tf, BlendMode blend,
                   double isoFraction, int width, int height, int frames, int cpuFrames, bool noCpu,
                   gpu::CudaRenderer* gpuRenderer) {
  const Model model = loadModel(path);
  RenderSettings s = withBlend(modelSettings(model, width, height, tf), model, blend, isoFraction);
  EmptySpaceCache cache;
  const ModelField field(model, &cache);
  const std::string name = std::filesystem::path(path).filename().string();
  std::printf("\n%s: %dx%dx%d control points, degree %d, TF %s, step %.4g\n", name.c_str(),
              model.spline().knots(0).controlCount(), model.spline().knots(1).controlCount(),
              model.spline().knots(2).controlCount(), model.spline().knots(0).degree(), tf.c_str(),
              s.sampleDistance);
  std::printf("%-4s %-8s %10s %9s %10s %11s %11s %s\n", "dev", "skipping", "frame s", "fps",
              "kernel s", "M samples", "M skipped", "image vs skipping off");
  for (gpu::CudaRenderer* dev : {gpuRenderer, static_cast<gpu::CudaRenderer*>(nullptr)}) {
    if (dev == nullptr && noCpu) continue;
    std::optional<Timed> on;
    for (bool skip : {true, false}) {
      s.skipEmptySpace = skip;
      const Timed t = timeFrames(dev, field, s, dev ? frames : cpuFrames);
      std::printf("%-4s %-8s %10.4f %9.2f %10s %11.1f %11.1f", dev ? "cuda" : "cpu",
                  skip ? "on" : "off", t.frame, 1.0 / t.frame,
                  dev ? std::to_string(t.kernel).c_str() : "-", t.stats.samples / 1e6,
                  t.stats.skipped / 1e6);
      if (on) {
        const auto a = toImage8(on->image), b = toImage8(t.image);
        std::printf(" %s",
                    a.data == b.data
                        ? "identical"
                        : ("PSNR " + std::to_string(compareImages(a, b).psnr) + " dB").c_str());
      }
      std::printf("\n");
      if (skip) on = t;
    }
    if (dev == nullptr) break;
  }
}

int run(int argc, char** argv) {
  std::string size = "1024x1024", scenes = "256:3,512:2";
  int frames = 5, cpuFrames = 2;
  bool noCpu = false;
  std::vector<std::string> models;
  std::string tf = "step:0.2", blendName = "composite";
  double isoFraction = 0.5;
  CLI::App app("GPU (CUDA) against CPU frame time of the MFA ray caster");
  app.add_option("--size", size, "Image size WxH")->capture_default_str();
  app.add_option("--frames", frames, "Timed GPU frames (median)")->capture_default_str();
  app.add_option("--cpu-frames", cpuFrames, "Timed CPU frames (median)")->capture_default_str();
  app.add_option("--scenes", scenes, "N:DEGREE list (N^3 control points)")->capture_default_str();
  app.add_flag("--no-cpu", noCpu, "GPU frames only");
  app.add_option("--model", models, "Saved models (.mfa) to render as extra scenes")
      ->check(CLI::ExistingFile);
  app.add_option("--tf", tf, "Opacity TF of the --model scenes (as render --tf)")
      ->capture_default_str();
  app.add_option("--blend", blendName, "Blend mode of every scene (" + blendModeChoices() + ")")
      ->capture_default_str();
  app.add_option("--iso", isoFraction, "--blend iso: the isovalue, a fraction of the value range")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const std::optional<BlendMode> blend = parseBlendMode(blendName);
  if (!blend) {
    std::fprintf(stderr, "--blend: expected one of %s\n", blendModeChoices().c_str());
    return 1;
  }
  int width = 0, height = 0;
  if (std::sscanf(size.c_str(), "%dx%d", &width, &height) != 2 || width <= 0 || height <= 0) {
    std::fprintf(stderr, "--size: expected WxH\n");
    return 1;
  }
  std::vector<Scene> list;
  for (std::size_t at = 0; at < scenes.size();) {
    const std::size_t end = std::min(scenes.find(',', at), scenes.size());
    Scene sc;
    if (std::sscanf(scenes.substr(at, end - at).c_str(), "%d:%d", &sc.n, &sc.degree) != 2 ||
        sc.n < 8 || sc.degree < 1 || sc.degree > 7 || sc.n <= sc.degree) {
      std::fprintf(stderr, "--scenes: expected N:DEGREE,... (N >= 8, 1 <= DEGREE <= 7)\n");
      return 1;
    }
    list.push_back(sc);
    at = end + 1;
  }

  const gpu::CudaDeviceStatus status = gpu::cudaDeviceStatus();
  std::optional<gpu::CudaRenderer> gpuRenderer;
  if (status.usable) gpuRenderer.emplace();
  std::printf("GPU: %s (CUDA runtime %s)\n", status.describe().c_str(),
              gpu::cudaVersionString(status.runtimeVersion).c_str());
  std::printf("CPU: %s, %d threads\n", cpuName().c_str(), tbb::info::default_concurrency());
  std::printf(
      "%dx%d, shaded, %s blend, Marschner-Lobb, step = half the control spacing, "
      "skipping on\n\n",
      width, height, blendModeName(*blend));
  std::printf("%-10s %-4s %10s %9s %10s %10s %11s %9s\n", "scene", "dev", "frame s", "fps",
              "kernel s", "first s", "M samples", "speed-up");
  const auto f = makeBuiltin("marschner-lobb");
  for (const Scene& sc : list) {
    const auto buildStart = std::chrono::steady_clock::now();
    const Model model = sampledModel(*f, sc.n, sc.degree);
    const double buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count();
    const RenderSettings s =
        withBlend(sceneSettings(model, width, height, sc.n), model, *blend, isoFraction);
    EmptySpaceCache cache;  // as a viewer: flags built once for the TF
    const ModelField field(model, &cache);
    const std::string name = std::to_string(sc.n) + "^3 p=" + std::to_string(sc.degree);
    std::optional<Image> gpuImage, cpuImage;
    double gpuFrame = 0.0, cpuFrame = 0.0;
    if (gpuRenderer) {
      RenderStats stats;
      gpuImage = gpuRenderer->renderModel(field, s, &stats);
      const double first = stats.seconds;
      std::vector<double> times, kernel;
      for (int i = 0; i < frames; ++i) {
        gpuImage = gpuRenderer->renderModel(field, s, &stats);
        times.push_back(stats.seconds);
        kernel.push_back(gpuRenderer->lastKernelSeconds());
      }
      gpuFrame = median(times);
      std::printf("%-10s %-4s %10.4f %9.1f %10.4f %10.3f %11.1f %9s\n", name.c_str(), "cuda",
                  gpuFrame, 1.0 / gpuFrame, median(kernel), first, stats.samples / 1e6, "");
    }
    if (!noCpu) {
      RenderStats stats;
      std::vector<double> times;
      for (int i = 0; i < std::max(cpuFrames, 1); ++i) {
        cpuImage = renderVolume(field, s, &stats);
        times.push_back(stats.seconds);
      }
      cpuFrame = median(times);
      std::printf("%-10s %-4s %10.4f %9.2f %10s %10s %11.1f", name.c_str(), "cpu", cpuFrame,
                  1.0 / cpuFrame, "-", "-", stats.samples / 1e6);
      if (gpuRenderer) std::printf(" %8.1fx", cpuFrame / gpuFrame);
      std::printf("\n");
    }
    if (gpuImage && cpuImage)
      std::printf("%-10s GPU vs CPU image: PSNR %.2f dB (model built in %.1f s)\n", name.c_str(),
                  compareImages(toImage8(*gpuImage), toImage8(*cpuImage)).psnr, buildSeconds);
  }
  for (const std::string& path : models)
    runModelScene(path, tf, *blend, isoFraction, width, height, frames, cpuFrames, noCpu,
                  gpuRenderer ? &*gpuRenderer : nullptr);
  if (!gpuRenderer) std::printf("\nno GPU figures: %s\n", status.reason.c_str());
  return 0;
}

}  // namespace
}  // namespace mfadvr

int main(int argc, char** argv) {
  try {
    return mfadvr::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mfadvr_gpu_bench: %s\n", e.what());
    return 1;
  }
}
