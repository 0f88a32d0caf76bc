// mfadvr_render_vs_vtk: frame time of every reconstruction method of our ray caster against VTK
// 9.1's vtkFixedPointVolumeRayCastMapper, side by side in one run (docs/benchmarks.md;
// docs/architecture.md, Cost model of the renderer). The scene is the Gaussian beam sampled at N^3
// on [-1,1]^3; the MFA model interpolates it (degree 2, N^3 control points, as the paper). Both
// renderers get the same volume, camera, transfer function, lighting coefficients, image size and
// sample distance (the VTK scene comes from the mfadvr_vtkrender library, as `mfadvr render
// --method vtk-fixedpoint`).
//
// Debian's VTK needs an X display even off screen: run under `xvfb-run -a`.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/image/Image.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngFile.h"
#include "core/render/ReconstructionMethod.h"
#include "core/render/RenderSettings.h"
#include "core/render/TransferFunction.h"
#include "core/util/Error.h"
#include "vtkrender/VtkBaselineRenderer.h"

namespace {

using namespace mfadvr;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

struct Options {
  std::string sizes = "64,128,256";
  int width = 1000, height = 1000, repeats = 3;
  std::string shade = "both";
  std::string methods;  // empty: every method
  std::string outDir;
  std::string tf = "ramp", colormap = "cool-to-warm";
  double azimuth = 30.0, elevation = 20.0;
};

struct Row {
  std::string method;
  double seconds = 0, setup = 0;
  double samples = 0;  // per frame; 0 when unknown (VTK)
};

void printRow(int n, bool shade, const Row& r, double vtkSeconds) {
  char rate[32] = "-", samples[32] = "-";
  if (r.samples > 0) {
    std::snprintf(samples, sizeof samples, "%.1f", r.samples / 1e6);
    std::snprintf(rate, sizeof rate, "%.1f", r.samples / r.seconds / 1e6);
  }
  std::printf("%5d^3  %-8s  %-12s  %9.3f  %8.3f  %9s  %9s  %7.2f\n", n,
              shade ? "shaded" : "unshaded", r.method.c_str(), r.seconds, r.setup, samples, rate,
              r.seconds / vtkSeconds);
  std::fflush(stdout);
}

int run(const Options& o) {
  std::vector<int> sizes;
  for (const auto& s : splitCommas(o.sizes)) {
    int n = 0;
    try {
      n = std::stoi(s);
    } catch (const std::logic_error&) {
    }
    if (n < 4 || n > 1024) throw Error("--sizes: each size must be 4..1024, got '" + s + "'");
    sizes.push_back(n);
  }
  if (sizes.empty()) throw Error("--sizes: no sizes");
  std::vector<bool> shadings;
  if (o.shade == "both" || o.shade == "off") shadings.push_back(false);
  if (o.shade == "both" || o.shade == "on") shadings.push_back(true);
  std::vector<ReconstructionMethod> methods;
  for (const auto& m : o.methods.empty() ? reconstructionMethodNames() : splitCommas(o.methods))
    methods.push_back(parseReconstructionMethod(m));
  if (!o.outDir.empty()) std::filesystem::create_directories(o.outDir);

  const auto truth = makeBuiltin("gaussian-beam");
  // The function's range (Vmin 0, Vmax 255): the same TF for every size and method.
  const TransferFunction tf = parseTransferFunction(o.tf, o.colormap).resolved(0.0, 255.0);

  std::printf(
      "mfadvr_render_vs_vtk: Gaussian beam, %dx%d, median of %d frames, %u hardware "
      "threads (both renderers use all)\n",
      o.width, o.height, o.repeats, std::thread::hardware_concurrency());
  std::printf(
      "TF: opacity '%s', colours '%s' on [0,255]; camera: framed, azimuth %g, elevation %g;"
      " step = half the grid spacing, opacity unit distance = the spacing\n\n",
      o.tf.c_str(), o.colormap.c_str(), o.azimuth, o.elevation);

  struct Agreement {
    int n;
    bool shade;
    ImageComparison cmp;
  };
  std::vector<Agreement> agreements;
  std::vector<std::string> summary;
  bool headerPrinted = false;

  for (const int n : sizes) {
    const StructuredGrid grid = sampleBuiltin(*truth, {n, n, n});
    StructuredFitOptions fit;
    fit.degree = {2, 2, 2};
    fit.controlCounts = {n, n, n};
    const auto encodeStart = Clock::now();
    const Model model = fitStructured(grid, fit);
    const double encodeSeconds = secondsSince(encodeStart);
    std::printf("%d^3: MFA encode (p = 2, %d^3 control points) %.3f s\n", n, n, encodeSeconds);

    SceneData scene;
    scene.model = &model;
    scene.grid = &grid;
    scene.truth = truth.get();
    scene.differenceStep = grid.spacing;

    RenderSettings s;
    s.width = o.width;
    s.height = o.height;
    s.camera.resetToBounds(grid.boxMin(), grid.boxMax());
    s.camera.azimuth(o.azimuth);
    s.camera.elevation(o.elevation);
    s.camera.validate();
    s.transferFunction = tf;
    const double spacing = grid.spacing.minCoeff();
    s.opacityUnitDistance = spacing;
    s.sampleDistance = 0.5 * spacing;
    s.earlyTerminationOpacity = 0.99;
    s.threads = 0;

    VtkBaselineRenderer vtk(VtkMethod::FixedPoint, {&grid, nullptr}, s);
    for (const bool shade : shadings) {
      s.shade = shade;
      const std::string tag = std::to_string(n) + (shade ? "_shaded" : "_unshaded");

      vtk.setShade(shade);
      Row vtkRow{"vtk-fixedpt", 0, 0, 0};
      // First frame: builds tables (and gradients when shaded); then the timed frames.
      const VtkFrameTimes vtkTimes = vtk.renderFrames(1 + o.repeats);
      vtkRow.setup = vtkTimes.firstSeconds;
      vtkRow.seconds = vtkTimes.medianSeconds;
      std::vector<double> times;
      const Image8 vtkImage = vtk.readBack();
      if (!o.outDir.empty()) writePng(o.outDir + "/" + tag + "_vtk.png", vtkImage);

      if (!headerPrinted) {
        std::printf("\n%7s  %-8s  %-12s  %9s  %8s  %9s  %9s  %7s\n", "size", "shading", "method",
                    "frame s", "setup s", "M samples", "M samp/s", "vs VTK");
        headerPrinted = true;
      }
      printRow(n, shade, vtkRow, vtkRow.seconds);

      std::map<ReconstructionMethod, double> frame;
      std::optional<Image8> trilinearImage;
      for (const ReconstructionMethod m : methods) {
        MethodSpec spec;
        spec.method = m;
        Row row{methodName(m), 0, 0, 0};
        times.clear();
        Image image;
        MethodRenderStats stats;
        for (int r = 0; r < o.repeats; ++r) {
          image = renderMethod(scene, spec, s, &stats);
          times.push_back(stats.seconds);
        }
        row.seconds = medianSeconds(times);
        row.setup = stats.setupSeconds;
        row.samples = static_cast<double>(stats.samples);
        frame[m] = row.seconds;
        const Image8 image8 = toImage8(image);
        if (m == ReconstructionMethod::Trilinear) trilinearImage = image8;
        if (!o.outDir.empty()) writePng(o.outDir + "/" + tag + "_" + row.method + ".png", image8);
        printRow(n, shade, row, vtkRow.seconds);
      }
      if (!trilinearImage) {  // the agreement check needs our trilinear image
        MethodSpec spec;
        spec.method = ReconstructionMethod::Trilinear;
        trilinearImage = toImage8(renderMethod(scene, spec, s));
      }
      agreements.push_back({n, shade, compareImages(*trilinearImage, vtkImage)});

      char line[256];
      std::string text = std::to_string(n) + "^3 " + (shade ? "shaded:  " : "unshaded:");
      if (frame.count(ReconstructionMethod::Trilinear)) {
        const double ratio = frame[ReconstructionMethod::Trilinear] / vtkRow.seconds;
        std::snprintf(line, sizeof line, " trilinear %.3f s = %.2fx VTK (target <= 1: %s);",
                      frame[ReconstructionMethod::Trilinear], ratio,
                      ratio <= 1.0 ? "met" : "MISSED");
        text += line;
      }
      if (frame.count(ReconstructionMethod::Mfa)) {
        const double ratio = frame[ReconstructionMethod::Mfa] / vtkRow.seconds;
        // <= 2: the first renderer's target; <= 0.33: the CPU hot path's (docs/benchmarks.md).
        std::snprintf(line, sizeof line, " mfa %.3f s = %.2fx VTK (target <= 2: %s, <= 0.33: %s);",
                      frame[ReconstructionMethod::Mfa], ratio, ratio <= 2.0 ? "met" : "MISSED",
                      ratio <= 0.33 ? "met" : "MISSED");
        text += line;
      }
      std::snprintf(line, sizeof line, " VTK %.3f s (first frame %.3f s)", vtkRow.seconds,
                    vtkRow.setup);
      summary.push_back(text + line);
    }
  }

  std::printf(
      "\nTargets (frame time, median; VTK = vtkFixedPointVolumeRayCastMapper, trilinear):\n");
  for (const auto& line : summary) std::printf("  %s\n", line.c_str());
  std::printf("\nScene check, VTK's image against our trilinear image (8-bit RGB, whole image):\n");
  for (const auto& a : agreements)
    std::printf("  %d^3 %-8s  PSNR %6.2f dB  SSIM %.4f  (MSE %.2f)%s\n", a.n,
                a.shade ? "shaded" : "unshaded", a.cmp.psnr, a.cmp.ssim, a.cmp.mse,
                a.cmp.psnr < 20.0 ? "  <- LOW: the scenes may differ" : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "Frame time of every reconstruction method against VTK's "
      "vtkFixedPointVolumeRayCastMapper (Gaussian beam; run under xvfb-run -a)"};
  app.add_option("--sizes", o.sizes, "Grid sizes N (N^3 samples), comma-separated")
      ->capture_default_str();
  app.add_option("--width", o.width, "Image width")
      ->check(CLI::Range(1, 8192))
      ->capture_default_str();
  app.add_option("--height", o.height, "Image height")
      ->check(CLI::Range(1, 8192))
      ->capture_default_str();
  app.add_option("--repeats", o.repeats, "Timed frames per case (median reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--shade", o.shade, "Shading: both, on or off")
      ->check(CLI::IsMember({"both", "on", "off"}))
      ->capture_default_str();
  app.add_option("--methods", o.methods, "Our methods, comma-separated [default: all]");
  app.add_option("--out", o.outDir, "Write every image as PNG into this folder");
  app.add_option("--tf", o.tf, "Opacity preset (as mfadvr render --tf)")->capture_default_str();
  app.add_option("--colormap", o.colormap, "Colour map (as mfadvr render --colormap)")
      ->capture_default_str();
  app.add_option("--azimuth", o.azimuth, "Camera azimuth after framing, degrees")
      ->capture_default_str();
  app.add_option("--elevation", o.elevation, "Camera elevation after framing, degrees")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "mfadvr_render_vs_vtk: " << e.what() << "\n";
    return 1;
  }
}
