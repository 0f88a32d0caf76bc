// mfadvr_render_vs_vtk: frame time of every reconstruction method of our ray caster against VTK
// 9.1's vtkFixedPointVolumeRayCastMapper, side by side in one run (DESIGN.md sections 4 and 6;
// docs/benchmarks.md). The scene is the Gaussian beam sampled at N^3 on [-1,1]^3; the MFA model
// interpolates it (degree 2, N^3 control points, as the paper). Both renderers get the same
// volume, camera, transfer function, lighting coefficients, image size and sample distance.
//
// Debian's VTK needs an X display even off screen: run under `xvfb-run -a`.
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

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

namespace {

using namespace mfadvr;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
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

// One VTK pipeline per volume: image data, mapper, property, renderer, off-screen window.
class VtkScene {
 public:
  VtkScene(const StructuredGrid& grid, const RenderSettings& s) {
    image_->SetDimensions(static_cast<int>(grid.dims[0]), static_cast<int>(grid.dims[1]),
                          static_cast<int>(grid.dims[2]));
    image_->SetOrigin(grid.origin[0], grid.origin[1], grid.origin[2]);
    image_->SetSpacing(grid.spacing[0], grid.spacing[1], grid.spacing[2]);
    vtkNew<vtkFloatArray> scalars;
    scalars->SetName("value");
    scalars->SetNumberOfComponents(1);
    scalars->SetNumberOfTuples(static_cast<vtkIdType>(grid.values.size()));
    // Both are x fastest.
    for (size_t i = 0; i < grid.values.size(); ++i)
      scalars->SetValue(static_cast<vtkIdType>(i), static_cast<float>(grid.values[i]));
    image_->GetPointData()->SetScalars(scalars);

    mapper_->SetInputData(image_);
    mapper_->AutoAdjustSampleDistancesOff();
    mapper_->LockSampleDistanceToInputSpacingOff();
    mapper_->SetSampleDistance(static_cast<float>(s.sampleDistance));
    mapper_->SetInteractiveSampleDistance(static_cast<float>(s.sampleDistance));
    mapper_->SetImageSampleDistance(1.0f);
    mapper_->SetMinimumImageSampleDistance(1.0f);
    mapper_->SetMaximumImageSampleDistance(1.0f);

    // The resolved transfer function, point by point (a repeated x replaces the earlier point in
    // VTK; the presets used here have none).
    for (const ColorPoint& p : s.transferFunction.color)
      color_->AddRGBPoint(p.x, p.rgb[0], p.rgb[1], p.rgb[2]);
    for (const OpacityPoint& p : s.transferFunction.opacity) opacity_->AddPoint(p.x, p.alpha);
    property_->SetColor(color_);
    property_->SetScalarOpacity(opacity_);
    property_->SetInterpolationTypeToLinear();
    property_->SetScalarOpacityUnitDistance(s.opacityUnitDistance);
    property_->SetAmbient(s.lighting.ambient);
    property_->SetDiffuse(s.lighting.diffuse);
    property_->SetSpecular(s.lighting.specular);
    property_->SetSpecularPower(s.lighting.specularPower);
    volume_->SetMapper(mapper_);
    volume_->SetProperty(property_);

    renderer_->AddVolume(volume_);
    renderer_->SetBackground(s.background[0], s.background[1], s.background[2]);
    // A headlight like the one the renderer would create (vtkRenderer::CreateLight), but with a
    // white ambient colour: vtkLight's default ambient colour is black, and the fixed-point
    // mapper's shading tables multiply the property's Ambient by it, so VTK's default scene has
    // no ambient term at all. Ours is ambient * TF colour.
    light_->SetLightTypeToHeadlight();
    light_->SetAmbientColor(1.0, 1.0, 1.0);
    light_->SetDiffuseColor(1.0, 1.0, 1.0);
    light_->SetSpecularColor(1.0, 1.0, 1.0);
    light_->SetIntensity(1.0);
    renderer_->AddLight(light_);
    renderer_->AutomaticLightCreationOff();
    window_->SetOffScreenRendering(1);
    window_->SetMultiSamples(0);
    window_->SetSize(s.width, s.height);
    window_->AddRenderer(renderer_);

    vtkCamera* c = renderer_->GetActiveCamera();
    c->SetPosition(s.camera.position.data());
    c->SetFocalPoint(s.camera.focalPoint.data());
    c->SetViewUp(s.camera.viewUp.data());
    c->SetViewAngle(s.camera.viewAngle);
    c->SetParallelProjection(s.camera.parallelProjection);
    c->SetParallelScale(s.camera.parallelScale);
    renderer_->ResetCameraClippingRange();  // not ResetCamera: keep our framing exactly
  }

  void setShade(bool shade) { property_->SetShade(shade ? 1 : 0); }

  // One full re-render; returns its wall time.
  double render() {
    renderer_->GetActiveCamera()->Modified();
    renderer_->ResetCameraClippingRange();
    const auto start = Clock::now();
    window_->Render();
    window_->WaitForCompletion();  // the frame is on screen, not just queued
    return secondsSince(start);
  }

  // The window's RGB, flipped so that row 0 is at the top like ours.
  Image8 readBack() {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window_);
    grab->SetInputBufferTypeToRGB();
    grab->ReadFrontBufferOff();
    grab->Update();
    vtkImageData* out = grab->GetOutput();
    int dims[3];
    out->GetDimensions(dims);
    auto* data = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetScalars());
    if (!data || data->GetNumberOfComponents() != 3)
      throw Error("VTK read-back did not give 8-bit RGB");
    Image8 img;
    img.width = dims[0];
    img.height = dims[1];
    img.channels = 3;
    img.data.resize(size_t(3) * dims[0] * dims[1]);
    const unsigned char* src = data->GetPointer(0);
    const size_t row = size_t(3) * dims[0];
    for (int y = 0; y < dims[1]; ++y)
      std::copy_n(src + size_t(dims[1] - 1 - y) * row, row, img.data.data() + size_t(y) * row);
    return img;
  }

 private:
  vtkNew<vtkImageData> image_;
  vtkNew<vtkFixedPointVolumeRayCastMapper> mapper_;
  vtkNew<vtkColorTransferFunction> color_;
  vtkNew<vtkPiecewiseFunction> opacity_;
  vtkNew<vtkVolumeProperty> property_;
  vtkNew<vtkVolume> volume_;
  vtkNew<vtkRenderer> renderer_;
  vtkNew<vtkLight> light_;
  vtkNew<vtkRenderWindow> window_;
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
    const Model model = encodeStructured(grid, fit);
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

    VtkScene vtk(grid, s);
    for (const bool shade : shadings) {
      s.shade = shade;
      const std::string tag = std::to_string(n) + (shade ? "_shaded" : "_unshaded");

      vtk.setShade(shade);
      Row vtkRow{"vtk-fixedpt", 0, 0, 0};
      vtkRow.setup = vtk.render();  // first frame: builds tables (and gradients when shaded)
      std::vector<double> times;
      for (int r = 0; r < o.repeats; ++r) times.push_back(vtk.render());
      vtkRow.seconds = median(times);
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
        row.seconds = median(times);
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
        std::snprintf(line, sizeof line, " mfa %.3f s = %.2fx VTK (target <= 2: %s);",
                      frame[ReconstructionMethod::Mfa], ratio, ratio <= 2.0 ? "met" : "MISSED");
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
