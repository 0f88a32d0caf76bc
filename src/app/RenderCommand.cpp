// mfadvr render INPUT -o OUT.png [--method M] [--gradient-from M] [scene options] [--json]
#include <nlohmann/json.hpp>

#include <chrono>
#include <iostream>

#include "app/Commands.h"
#include "app/EncodeCliOptions.h"
#include "app/OptionParsing.h"
#include "app/RenderOptions.h"
#include "app/SceneLoader.h"
#include "core/image/FloatImageFile.h"
#include "core/image/PngFile.h"
#include "core/util/Error.h"
#include "io/ScatteredLoader.h"
#include "io/VolumeLoader.h"

namespace mfadvr::app {

namespace {

std::string methodList() {
  std::string list;
  for (const auto& n : reconstructionMethodNames()) list += (list.empty() ? "" : "|") + n;
  return list;
}

}  // namespace

Command addRenderCommand(CLI::App& app) {
  struct Options {
    std::string input, output, floatOutput, method, gradientFrom, gradient = "analytic";
    std::string spacing, origin, field;
    EncodeCliOptions encode;
    bool json = false, quiet = false, alpha = false;
    RenderOptions render;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "render", "Ray-cast a volume image of an MFA model, a grid filter or the analytic truth");
  sub->add_option("input", o->input,
                  "A model (.mfa), a volume, mesh or point file, or builtin:NAME[:N|:NXxNYxNZ]\n" +
                      supportedVolumeFormats() + "\n" + supportedScatteredFormats())
      ->required();
  sub->add_option("-o,--output", o->output, "PNG to write (8-bit RGB; RGBA with --alpha)")
      ->required();
  sub->add_option("--method", o->method,
                  "Reconstruction: " + methodList() +
                      " [default: mfa; a non-model input is encoded first with the encoding "
                      "options]")
      ->check(CLI::IsMember(reconstructionMethodNames()));
  sub->add_option("--gradient-from", o->gradientFrom,
                  "Gradient test (paper Table 1): value from the truth, gradient from this method")
      ->check(CLI::IsMember(reconstructionMethodNames()));
  sub->add_option("--gradient", o->gradient,
                  "analytic (derivative of the reconstruction) or central (central differences "
                  "one data spacing apart)")
      ->check(CLI::IsMember({"analytic", "central"}))
      ->capture_default_str();
  sub->add_flag("--alpha", o->alpha, "Write RGBA (alpha = accumulated opacity)");
  sub->add_option("--float", o->floatOutput,
                  "Also write the linear float RGBA image as NRRD (for analysis)");
  o->render.addTo(sub);
  o->encode.addTo(sub, "Encoding (non-model inputs rendered with mfa)");
  const char* in = "Input";
  sub->add_option("--spacing", o->spacing, "Sample spacing S or SX,SY,SZ (overrides the file's)")
      ->group(in);
  sub->add_option("--origin", o->origin, "Position of the first sample X,Y,Z")->group(in);
  sub->add_option("--field", o->field, "Scalar array to render")->group(in);
  sub->add_flag("--json", o->json, "Print timings and counts as JSON");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  auto run = [o]() -> int {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    MethodSpec spec;
    if (!o->gradientFrom.empty()) {
      spec.gradientFrom = parseReconstructionMethod(o->gradientFrom);
      spec.method = ReconstructionMethod::Truth;
      if (!o->method.empty() && parseReconstructionMethod(o->method) != ReconstructionMethod::Truth)
        throw CLI::ValidationError("--gradient-from",
                                   "the gradient test takes the value from the truth; drop "
                                   "--method or use --method truth");
    } else if (!o->method.empty()) {
      spec.method = parseReconstructionMethod(o->method);
    }
    spec.gradient =
        o->gradient == "central" ? GradientMode::CentralDifference : GradientMode::Analytic;
    SceneNeeds needs;
    for (auto m : {std::optional(spec.method), spec.gradientFrom}) {
      if (!m) continue;
      needs.model |= *m == ReconstructionMethod::Mfa;
      needs.grid |= isGridMethod(*m);
    }

    SceneLoadOptions load;
    load.encode = o->encode.parse();
    load.volume = parseVolumeLoadOptions(o->spacing, o->origin, o->field);
    const bool progress = wantProgress(o->quiet || o->json);
    load.progress = progress;

    const LoadedScene scene = loadScene(o->input, needs, load);
    RenderSettings settings = o->render.settingsFor(scene);
    if (progress) settings.progress = [](double f) { printProgress("rendering", f); };
    MethodRenderStats stats;
    const Image image = renderMethod(scene.view(), spec, settings, &stats);
    writePng(o->output, toImage8(image, o->alpha));
    if (!o->floatOutput.empty()) writeFloatImage(o->floatOutput, image);
    const double total = std::chrono::duration<double>(Clock::now() - start).count();

    std::string label = methodName(spec.method);
    if (spec.gradientFrom) label += " (gradient from " + methodName(*spec.gradientFrom) + ")";
    if (spec.gradient == GradientMode::CentralDifference) label += ", central-difference gradient";
    if (o->json) {
      nlohmann::json j;
      j["input"] = o->input;
      j["output"] = o->output;
      j["method"] = methodName(spec.method);
      j["gradient_from"] = spec.gradientFrom ? nlohmann::json(methodName(*spec.gradientFrom))
                                             : nlohmann::json(nullptr);
      j["gradient"] = o->gradient;
      j["width"] = settings.width;
      j["height"] = settings.height;
      j["sample_distance"] = settings.sampleDistance;
      j["opacity_unit_distance"] = settings.opacityUnitDistance;
      j["shade"] = settings.shade;
      j["value_range"] = {scene.valueMin, scene.valueMax};
      j["seconds"] = {{"load", scene.loadSeconds},
                      {"encode", scene.encodeSeconds},
                      {"setup", stats.setupSeconds},
                      {"render", stats.seconds},
                      {"total", total}};
      j["rays"] = stats.rays;
      j["rays_hit"] = stats.raysHit;
      j["samples"] = stats.samples;
      j["rays_terminated_early"] = stats.terminated;
      j["samples_per_second"] = stats.seconds > 0 ? stats.samples / stats.seconds : 0.0;
      std::cout << j.dump(2) << "\n";
    } else {
      std::printf("%s: %s, %dx%d, step %.4g, %s\n", o->output.c_str(), label.c_str(),
                  settings.width, settings.height, settings.sampleDistance,
                  settings.shade ? "shaded" : "unshaded");
      std::printf("  render %.3f s (%.1f M samples, %.1f M samples/s)", stats.seconds,
                  stats.samples / 1e6,
                  stats.seconds > 0 ? stats.samples / stats.seconds / 1e6 : 0.0);
      if (scene.encodeSeconds > 0) std::printf(", encode %.3f s", scene.encodeSeconds);
      if (stats.setupSeconds > 0.001) std::printf(", setup %.3f s", stats.setupSeconds);
      std::printf(", total %.3f s\n", total);
    }
    return 0;
  };
  return {sub, run};
}

}  // namespace mfadvr::app
