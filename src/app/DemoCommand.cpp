// mfadvr demo [--out DIR]: the main job on a built-in default. Encodes the Marschner-Lobb
// function (41^3 samples) into an interpolating cubic MFA model, renders the analytic truth, the
// model and trilinear filtering of the same samples with one camera and transfer function,
// writes the images and a side-by-side montage (each panel labelled with its method and its
// PSNR/SSIM against the truth), and prints each method's PSNR/SSIM against the
// truth and its render time.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/Commands.h"
#include "app/OptionParsing.h"
#include "app/RenderOptions.h"
#include "app/SceneLoader.h"
#include "core/image/BitmapFont.h"
#include "core/image/ImageMetrics.h"
#include "core/image/Montage.h"
#include "core/image/PngFile.h"
#include "core/model/ModelFile.h"
#include "core/util/AtomicFile.h"
#include "core/util/Error.h"

namespace mfadvr::app {

Command addDemoCommand(CLI::App& app) {
  struct Options {
    std::string out = "out/demo", input = "builtin:marschner-lobb";
    bool json = false, quiet = false;
    RenderOptions render;
  };
  auto o = std::make_shared<Options>();
  // The paper's overall-accuracy scene (Table 2): a shaded isosurface-like view at half the range.
  o->render.tf = "step:0.5";
  o->render.colormap = "white";
  o->render.shade = true;
  o->render.azimuth = 30.0;
  o->render.elevation = 25.0;
  CLI::App* sub = app.add_subcommand(
      "demo",
      "Encode Marschner-Lobb, render truth / MFA / trilinear with one camera, write the images "
      "and a montage, and print PSNR/SSIM against the truth and render times");
  sub->add_option("--out", o->out, "Output folder")->capture_default_str();
  sub->add_option("--input", o->input,
                  "A built-in function spec to use instead (it provides the truth)")
      ->capture_default_str();
  sub->add_flag("--json", o->json, "Print the results as JSON");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");
  o->render.addTo(sub);

  auto run = [o]() -> int {
    if (!isBuiltinSpec(o->input))
      throw CLI::ValidationError("--input", "the demo needs a builtin:NAME spec (for the truth)");
    const bool progress = wantProgress(o->quiet || o->json);
    SceneLoadOptions load;
    load.progress = progress;
    const LoadedScene scene = loadScene(o->input, SceneNeeds{true, true}, load);
    std::filesystem::create_directories(o->out);
    const std::filesystem::path dir(o->out);
    const std::string modelPath = (dir / "model.mfa").string();
    saveModel(*scene.model, modelPath);

    const RenderSettings settings = o->render.settingsFor(scene);
    struct Result {
      ReconstructionMethod method;
      Image8 image;
      MethodRenderStats stats;
      ImageComparison metrics;
    };
    std::vector<Result> results;
    for (auto m : {ReconstructionMethod::Truth, ReconstructionMethod::Mfa,
                   ReconstructionMethod::Trilinear}) {
      if (progress) std::cerr << "rendering " << methodName(m) << "\n";
      Result r{m, {}, {}, {}};
      MethodSpec spec;
      spec.method = m;
      r.image = toImage8(renderMethod(scene.view(), spec, settings, &r.stats));
      writePng((dir / (methodName(m) + ".png")).string(), r.image);
      results.push_back(std::move(r));
    }
    // Each panel is labelled with its method and its metrics against the truth.
    const auto counts = scene.model->spline().counts();
    const auto degrees = scene.model->spline().degrees();
    std::vector<Image8> row;
    for (auto& r : results) {
      r.metrics = compareImages(results[0].image, r.image);
      std::vector<std::string> caption;
      char line[128];
      if (r.method == ReconstructionMethod::Truth) {
        caption = {"truth (analytic)", "the reference"};
      } else {
        if (r.method == ReconstructionMethod::Mfa)
          std::snprintf(line, sizeof line, "MFA (p=%d, %lldx%lldx%lld ctrl)", degrees[0],
                        (long long)counts[0], (long long)counts[1], (long long)counts[2]);
        else
          std::snprintf(line, sizeof line, "%s", methodName(r.method).c_str());
        caption.push_back(line);
        std::snprintf(line, sizeof line, "PSNR %.2f dB", r.metrics.psnr);
        caption.push_back(line);
        std::snprintf(line, sizeof line, "SSIM %.4f", r.metrics.ssim);
        caption.push_back(line);
      }
      row.push_back(withCaption(r.image, caption, std::max(1, r.image.width / 200)));
    }
    const std::string montagePath = (dir / "montage.png").string();
    writePng(montagePath, montageHorizontal(row));

    const auto& grid = *scene.grid;
    nlohmann::json j;
    j["input"] = o->input;
    j["samples"] = {grid.dims[0], grid.dims[1], grid.dims[2]};
    j["model"] = {{"path", modelPath},
                  {"degree", {degrees[0], degrees[1], degrees[2]}},
                  {"control_points", {counts[0], counts[1], counts[2]}},
                  {"encode_seconds", scene.encodeSeconds},
                  {"max_error", scene.model->provenance().maxError}};
    j["image"] = {{"width", settings.width},
                  {"height", settings.height},
                  {"sample_distance", settings.sampleDistance}};
    j["montage"] = montagePath;
    for (const auto& r : results) {
      nlohmann::json m;
      m["method"] = methodName(r.method);
      m["image"] = (dir / (methodName(r.method) + ".png")).string();
      m["render_seconds"] = r.stats.seconds;
      m["samples"] = r.stats.samples;
      m["psnr"] = std::isfinite(r.metrics.psnr) ? nlohmann::json(r.metrics.psnr) : nlohmann::json();
      m["ssim"] = r.metrics.ssim;
      j["methods"].push_back(m);
    }
    writeFileAtomically((dir / "summary.json").string(), j.dump(2) + "\n");
    if (o->json) {
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    std::printf(
        "%s: %lldx%lldx%lld samples -> degree %d, %lldx%lldx%lld control points, "
        "encoded in %.3f s (max error %.3g)\n",
        o->input.c_str(), (long long)grid.dims[0], (long long)grid.dims[1], (long long)grid.dims[2],
        degrees[0], (long long)counts[0], (long long)counts[1], (long long)counts[2],
        scene.encodeSeconds, scene.model->provenance().maxError);
    std::printf("%dx%d images, step %.4g, shaded; compared with the truth on 8-bit RGB:\n\n",
                settings.width, settings.height, settings.sampleDistance);
    std::printf("  %-10s %10s %10s %8s\n", "method", "render s", "PSNR dB", "SSIM");
    for (const auto& r : results) {
      if (r.method == ReconstructionMethod::Truth)
        std::printf("  %-10s %10.3f %10s %8s\n", "truth", r.stats.seconds, "-", "-");
      else
        std::printf("  %-10s %10.3f %10.2f %8.4f\n", methodName(r.method).c_str(), r.stats.seconds,
                    r.metrics.psnr, r.metrics.ssim);
    }
    std::printf("\nimages: %s/{truth,mfa,trilinear}.png, montage: %s, model: %s\n", o->out.c_str(),
                montagePath.c_str(), modelPath.c_str());
    return 0;
  };
  return {sub, run};
}

}  // namespace mfadvr::app
