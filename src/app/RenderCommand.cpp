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
#include "core/render/BlendMode.h"
#include "core/render/kernel/EmptySpaceProfile.h"
#include "core/util/Error.h"
#include "device/RenderDevice.h"
#include "io/ScatteredLoader.h"
#include "io/VolumeLoader.h"
#include "vtkrender/VtkBaselineRenderer.h"

#if MFADVR_EMPTY_SPACE_PROFILE
#include <tbb/info.h>
#endif

namespace mfadvr::app {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<std::string> allMethodNames() {
  std::vector<std::string> names = reconstructionMethodNames();
  for (const auto& n : vtkMethodNames()) names.push_back(n);
  return names;
}

std::string methodList(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : "|") + n;
  return list;
}

struct Options {
  std::string input, output, floatOutput, depthOutput, method, gradientFrom, gradient = "analytic";
  std::string device = "auto";
  std::string spacing, origin;
  FieldOptionTexts field;
  EncodeCliOptions encode;
  bool json = false, quiet = false, alpha = false;
  int frames = 0;  // 0: 1 for our methods, 3 for VTK's
  RenderOptions render;
};

// Load and settings, shared by both kinds of method.
SceneLoadOptions loadOptions(const Options& o, bool progress) {
  SceneLoadOptions load;
  load.encode = o.encode.parse();
  load.volume = parseVolumeLoadOptions(o.spacing, o.origin, o.field);
  load.progress = progress;
  const auto blend = parseBlendMode(o.render.blend);
  load.extremeBounds = blend == BlendMode::Maximum || blend == BlendMode::Minimum;
  return load;
}

// --method vtk-*: VTK's own renderer on the input's grid or mesh.
int renderWithVtk(const Options& o, VtkMethod method, Clock::time_point start) {
  const std::string name = vtkMethodName(method);
  if (!o.gradientFrom.empty())
    throw CLI::ValidationError("--gradient-from",
                               "the gradient test runs on our ray caster, not on " + name);
  if (o.gradient != "analytic")
    throw CLI::ValidationError("--gradient", name + " computes its own gradients");
  if (o.alpha || !o.floatOutput.empty() || !o.depthOutput.empty())
    throw CLI::ValidationError(o.alpha                 ? "--alpha"
                               : o.floatOutput.empty() ? "--depth"
                                                       : "--float",
                               name + " gives an 8-bit RGB image only (read back from VTK)");
  if (method == VtkMethod::FixedPoint && !isModelFile(o.input) && isScatteredInput(o.input))
    throw Error(name + " (" + vtkMapperClassName(method) + ") renders regular grids; " + o.input +
                " holds a mesh or points: use vtk-bunyk, vtk-zsweep or vtk-pt (meshes with "
                "tetrahedra), or --method mfa");

  const bool progress = wantProgress(o.quiet || o.json);
  SceneNeeds needs;
  needs.grid = method == VtkMethod::FixedPoint;
  needs.cells = vtkMethodNeedsTetrahedra(method);
  const LoadedScene scene = loadScene(o.input, needs, loadOptions(o, progress));
  std::string tfWarning;
  const RenderSettings settings = o.render.settingsFor(scene, &tfWarning);
  const int frames = o.frames > 0 ? o.frames : 3;

  if (!o.quiet && !o.json) {
    if (!tfWarning.empty()) std::cerr << "mfadvr render: warning: " << tfWarning << "\n";
    if (settings.shade && !vtkMethodShades(method))
      std::cerr << "mfadvr render: warning: " << name << " does not shade; --shade is ignored\n";
    if (o.render.step && !vtkMethodUsesSampleDistance(method))
      std::cerr << "mfadvr render: warning: " << name
                << " integrates across each cell; --step is ignored\n";
  }

  VtkBaselineInput input;
  input.grid = scene.grid ? &*scene.grid : nullptr;
  input.mesh = scene.scattered ? &*scene.scattered : nullptr;
  VtkBaselineRenderer renderer(method, input, settings);
  if (progress) std::cerr << "rendering " << frames << " frame(s) with " << name << "\n";
  const VtkFrameTimes times = renderer.renderFrames(frames);
  writePng(o.output, renderer.readBack());
  const double total = secondsSince(start);

  const bool shaded = settings.shade && vtkMethodShades(method);
  const std::string cells = renderer.tetrahedralized() ? "tetrahedra (from the grid's voxels)"
                            : method == VtkMethod::FixedPoint ? "voxels"
                                                              : "tetrahedra";
  if (o.json) {
    nlohmann::json j;
    j["input"] = o.input;
    j["output"] = o.output;
    j["method"] = name;
    j["mapper"] = vtkMapperClassName(method);
    j["width"] = settings.width;
    j["height"] = settings.height;
    j["sample_distance"] = vtkMethodUsesSampleDistance(method)
                               ? nlohmann::json(settings.sampleDistance)
                               : nlohmann::json(nullptr);
    j["opacity_unit_distance"] = settings.opacityUnitDistance;
    j["shade"] = shaded;
    j["shade_requested"] = settings.shade;
    j["value_range"] = {scene.valueMin, scene.valueMax};
    j["points"] = renderer.pointCount();
    j["cells"] = renderer.cellCount();
    j["tetrahedralized"] = renderer.tetrahedralized();
    j["frames"] = frames;
    j["frame_seconds"] = times.seconds;
    j["seconds"] = {{"load", scene.loadSeconds},
                    {"encode", scene.encodeSeconds},
                    {"setup", renderer.preparationSeconds()},
                    {"first_frame", times.firstSeconds},
                    {"render", times.medianSeconds},
                    {"total", total}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("%s: %s (%s), %dx%d, %lld %s, ", o.output.c_str(), name.c_str(),
                vtkMapperClassName(method).c_str(), settings.width, settings.height,
                static_cast<long long>(renderer.cellCount()), cells.c_str());
    if (vtkMethodUsesSampleDistance(method)) std::printf("step %.4g, ", settings.sampleDistance);
    std::printf("%s\n", shaded ? "shaded" : "unshaded");
    if (frames > 1)
      std::printf("  render %.3f s (median of %d frames after the first), first frame %.3f s",
                  times.medianSeconds, frames - 1, times.firstSeconds);
    else
      std::printf("  render %.3f s (one frame, building VTK's structures included)",
                  times.firstSeconds);
    std::printf(", setup %.3f s, total %.3f s\n", renderer.preparationSeconds(), total);
  }
  return 0;
}

}  // namespace

Command addRenderCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "render",
      "Ray-cast a volume image of an MFA model, a grid filter or the analytic truth, or render "
      "the data with one of VTK's volume renderers");
  sub->add_option("input", o->input,
                  "A model (.mfa, one model or multi-block), a volume, mesh or point file, or "
                  "builtin:NAME[:N|:NXxNYxNZ]\n" +
                      supportedVolumeFormats() + "\n" + supportedScatteredFormats())
      ->required();
  sub->add_option("-o,--output", o->output, "PNG to write (8-bit RGB; RGBA with --alpha)")
      ->required();
  sub->add_option("--method", o->method,
                  "Reconstruction: " + methodList(reconstructionMethodNames()) +
                      " [default: mfa; a non-model input is encoded first with the encoding "
                      "options]; or a VTK baseline: vtk-fixedpoint (grids), vtk-bunyk, "
                      "vtk-zsweep, vtk-pt (tetrahedral meshes; a grid is tetrahedralized)")
      ->check(CLI::IsMember(allMethodNames()));
  sub->add_option("--gradient-from", o->gradientFrom,
                  "Gradient test (paper Table 1): value from the truth, gradient from this method")
      ->check(CLI::IsMember(reconstructionMethodNames()));
  sub->add_option("--gradient", o->gradient,
                  "analytic (derivative of the reconstruction) or central (central differences "
                  "one data spacing apart)")
      ->check(CLI::IsMember({"analytic", "central"}))
      ->capture_default_str();
  sub->add_option("--frames", o->frames,
                  "Frames to render and time: the first is reported apart (it builds VTK's "
                  "mapper structures, or the MFA model's empty-space flags), the frame time is "
                  "the median of the others "
                  "[default: 3 for vtk-*, 1 otherwise]")
      ->check(CLI::Range(1, 1000));
  addDeviceOption(sub, o->device);
  sub->add_flag("--alpha", o->alpha, "Write RGBA (alpha = accumulated opacity)");
  sub->add_option("--float", o->floatOutput,
                  "Also write the linear float RGBA image as NRRD (for analysis)");
  sub->add_option("--depth", o->depthOutput,
                  "Also write a float32 NRRD of ray distances from the camera position: where "
                  "the opacity first reaches 0.5 (composite), to the extreme sample (max, min), "
                  "to the first sample that counts (average, additive); NaN where none");
  o->render.addTo(sub);
  o->encode.addTo(sub, "Encoding (non-model inputs rendered with mfa)");
  const char* in = "Input";
  sub->add_option("--spacing", o->spacing, "Sample spacing S or SX,SY,SZ (overrides the file's)")
      ->group(in);
  sub->add_option("--origin", o->origin, "Position of the first sample X,Y,Z")->group(in);
  o->field.addTo(sub, in);
  sub->add_flag("--json", o->json, "Print timings and counts as JSON");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  auto run = [o]() -> int {
    const auto start = Clock::now();
    if (const auto vtk = findVtkMethod(o->method)) {
      if (o->device == "cuda")
        throw Error("device 'cuda': " + o->method +
                    " is VTK's own renderer and runs where VTK runs it; use --device auto or cpu");
      return renderWithVtk(*o, *vtk, start);
    }
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

    const RenderDevice device = openRenderDevice(o->device, spec);
    spec.device = device.renderer.get();
    const bool progress = wantProgress(o->quiet || o->json);
    const int frames = o->frames > 0 ? o->frames : 1;
    SceneLoadOptions load = loadOptions(*o, progress);
    // One frame reads every block once either way; one at a time, it holds one.
    load.streamBlocks = frames == 1;
    const LoadedScene scene = loadScene(o->input, needs, load);
    std::string tfWarning;
    RenderSettings settings = o->render.settingsFor(scene, &tfWarning);
    settings.depth = !o->depthOutput.empty();
    if (!o->quiet && !o->json && !tfWarning.empty())
      std::cerr << "mfadvr render: warning: " << tfWarning << "\n";
    if (progress) settings.progress = [](double f) { printProgress("rendering", f); };
    MethodRenderStats stats;
    Image image;
    std::vector<double> frameSeconds;
#if MFADVR_EMPTY_SPACE_PROFILE
    // The frames after the first (all of them when there is one): cycles of the rays, and the
    // time-stamp counter's rate measured over the same frames.
    EmptySpaceCycles profile;
    std::int64_t profileTicks = 0;
#endif
    for (int i = 0; i < frames; ++i) {
#if MFADVR_EMPTY_SPACE_PROFILE
      const std::int64_t ticks = cycleCount();
      EmptySpaceProfile::take();
#endif
      image = renderMethod(scene.view(), spec, settings, &stats);
      frameSeconds.push_back(stats.seconds);
#if MFADVR_EMPTY_SPACE_PROFILE
      if (frames == 1 || i > 0) {
        profile += EmptySpaceProfile::take();
        profileTicks += cycleCount() - ticks;
      }
#endif
    }
    const double firstFrame = frameSeconds.front();
    const double frameTime =
        frames == 1
            ? firstFrame
            : medianSeconds(std::vector<double>(frameSeconds.begin() + 1, frameSeconds.end()));
    writePng(o->output, toImage8(image, o->alpha));
    if (!o->floatOutput.empty()) writeFloatImage(o->floatOutput, image);
    if (!o->depthOutput.empty()) writeDepthImage(o->depthOutput, image, depthRule(settings.blend));
    const double total = secondsSince(start);

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
      j["device"] = device.name;
      j["device_description"] = device.description;
      j["value_range"] = {scene.valueMin, scene.valueMax};
      j["frames"] = frames;
      j["frame_seconds"] = frameSeconds;
      j["seconds"] = {{"load", scene.loadSeconds},   {"encode", scene.encodeSeconds},
                      {"setup", stats.setupSeconds}, {"first_frame", firstFrame},
                      {"render", frameTime},         {"total", total}};
      j["rays"] = stats.rays;
      j["rays_hit"] = stats.raysHit;
      j["samples"] = stats.samples;
      j["rays_terminated_early"] = stats.terminated;
      j["samples_skipped"] = stats.skipped;
      j["samples_per_second"] = frameTime > 0 ? stats.samples / frameTime : 0.0;
#if MFADVR_EMPTY_SPACE_PROFILE
      j["profile_cycles"] = {{"rays", profile.ray},
                             {"marching", profile.marching},
                             {"marching_ahead", profile.ahead},
                             {"transparent_samples", profile.transparent},
                             {"jumps", profile.jumps},
                             {"checks", profile.checks},
                             {"frames", frames == 1 ? 1 : frames - 1}};
#endif
      std::cout << j.dump(2) << "\n";
    } else {
      std::printf("%s: %s, %dx%d, step %.4g, %s\n", o->output.c_str(), label.c_str(),
                  settings.width, settings.height, settings.sampleDistance,
                  settings.shade ? "shaded" : "unshaded");
      std::printf("  render %.3f s (%.1f M samples, %.1f M samples/s)", frameTime,
                  stats.samples / 1e6, frameTime > 0 ? stats.samples / frameTime / 1e6 : 0.0);
      if (stats.skipped > 0) std::printf(", %.1f M empty samples skipped", stats.skipped / 1e6);
      if (frames > 1)
        std::printf(", median of %d frames after the first, first frame %.3f s", frames - 1,
                    firstFrame);
      if (scene.encodeSeconds > 0) std::printf(", encode %.3f s", scene.encodeSeconds);
      if (stats.setupSeconds > 0.001) std::printf(", setup %.3f s", stats.setupSeconds);
      std::printf(", total %.3f s\n  on the %s\n", total, device.description.c_str());
#if MFADVR_EMPTY_SPACE_PROFILE
      if (profile.ray > 0) {
        // Thread time of the frames: their ticks (wall time at the counter's rate) per thread.
        const double threadTicks =
            static_cast<double>(profileTicks) *
            (settings.threads > 0 ? settings.threads : tbb::info::default_concurrency());
        const double ray = static_cast<double>(profile.ray);
        std::printf(
            "  profile of the rays: marching (steps, empty-space checks, jumps) %.1f %%, "
            "evaluating transparent samples %.1f %%, together %.1f %% of the rays' time; the "
            "rays %.1f %% of the frames' thread time\n",
            100.0 * profile.marching / ray, 100.0 * profile.transparent / ray,
            100.0 * (profile.marching + profile.transparent) / ray, 100.0 * ray / threadTicks);
        const double measured = frames == 1 ? 1.0 : frames - 1.0;
        std::printf("  %.1f M jumps over empty space per frame, %.2f per ray that hits the box\n",
                    static_cast<double>(profile.jumps) / measured / 1e6,
                    static_cast<double>(profile.jumps) / measured /
                        static_cast<double>(std::max<std::int64_t>(stats.raysHit, 1)));
        // A check that finds a cell that is not empty locates a sample that is then evaluated
        // (without skipping, the evaluation locates it): marching, but not empty space.
        std::printf(
            "  %.2f M empty-space checks per frame, %.2f M of them in cells that are not empty; "
            "the march ahead of the integration %.1f %% of the rays' time; %lld of %lld rays "
            "that hit the box terminated\n",
            static_cast<double>(profile.checks) / measured / 1e6,
            static_cast<double>(profile.checks - profile.jumps) / measured / 1e6,
            100.0 * profile.ahead / ray, static_cast<long long>(stats.terminated),
            static_cast<long long>(stats.raysHit));
      }
#endif
    }
    return 0;
  };
  return {sub, run};
}

}  // namespace mfadvr::app
