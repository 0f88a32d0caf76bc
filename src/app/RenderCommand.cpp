// mfadvr render INPUT -o OUT.png [--method M] [--gradient-from M] [scene options] [--json]
#include <nlohmann/json.hpp>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "app/Commands.h"
#include "app/EncodeCliOptions.h"
#include "app/OptionParsing.h"
#include "app/RenderOptions.h"
#include "app/SceneLoader.h"
#include "app/VideoWriter.h"
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
  std::string spacing, origin, time, times, video;
  double fps = 24.0;
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
  if (!o.time.empty()) load.time = parseNumberList("--time", o.time, 1, 1)[0];
  return load;
}

// --times T0:T1:N: N instants from T0 to T1.
std::vector<double> parseTimes(const std::string& text) {
  const auto colon1 = text.find(':'), colon2 = text.rfind(':');
  if (colon1 == std::string::npos || colon1 == colon2)
    throw CLI::ValidationError("--times", "expected T0:T1:N, got '" + text + "'");
  const double t0 = parseNumberList("--times", text.substr(0, colon1), 1, 1)[0];
  const double t1 =
      parseNumberList("--times", text.substr(colon1 + 1, colon2 - colon1 - 1), 1, 1)[0];
  const double n = parseNumberList("--times", text.substr(colon2 + 1), 1, 1)[0];
  if (!(n >= 1 && n <= 100000 && n == std::floor(n)))
    throw CLI::ValidationError("--times", "N must be a whole number of frames in 1..100000");
  std::vector<double> out;
  for (int i = 0; i < static_cast<int>(n); ++i)
    out.push_back(n == 1 ? t0 : t0 + (t1 - t0) * i / (n - 1));
  return out;
}

// The file of frame i of an animation: the output's printf pattern (%d, %03d, ...) applied.
std::string frameFileName(const std::string& pattern, int i) {
  const int size = std::snprintf(nullptr, 0, pattern.c_str(), i);
  std::string out(static_cast<size_t>(std::max(size, 0)), '\0');
  std::snprintf(out.data(), out.size() + 1, pattern.c_str(), i);
  return out;
}

// Whether `pattern` holds exactly one integer conversion (%d, %Nd, %0Nd) and no other %.
bool isFramePattern(const std::string& pattern) {
  int conversions = 0;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    size_t j = i + 1;
    if (j < pattern.size() && pattern[j] == '%') {
      i = j;
      continue;
    }
    while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
    if (j >= pattern.size() || pattern[j] != 'd' || j - i > 4) return false;
    ++conversions;
    i = j;
  }
  return conversions == 1;
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
  sub->add_option("-o,--output", o->output,
                  "PNG to write (8-bit RGB; RGBA with --alpha); required unless --video is given");
  sub->add_option(
         "--method", o->method,
         "Reconstruction: " + methodList(reconstructionMethodNames()) +
             " [default: mfa; a non-model input is encoded first with the encoding "
             "options; mesh: a tetrahedral mesh's own field, linear in each tetrahedron, sampled "
             "by our ray caster]; or a VTK baseline: vtk-fixedpoint (grids), vtk-bunyk, "
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
  sub->add_option("--time", o->time,
                  "Time-varying models: the instant T to render (any time in the model's range, "
                  "not only its steps; default: the first step)")
      ->group("Time (docs/time-varying.md)");
  sub->add_option("--times", o->times,
                  "Time-varying models: an animation of N frames from T0 to T1 (T0:T1:N), "
                  "written to the output pattern (e.g. -o frame_%03d.png)")
      ->group("Time (docs/time-varying.md)");
  sub->add_option("--video", o->video,
                  "With --times: also (or, without -o, only) code the frames into a video file "
                  "(.mp4, .mov, .mkv: H.264; .webm: VP9; .avi: MPEG-4; .gif) with ffmpeg, which "
                  "must be installed (Debian: ffmpeg; or $MFADVR_FFMPEG)")
      ->group("Time (docs/time-varying.md)");
  sub->add_option("--fps", o->fps, "With --video: frames per second")
      ->check(CLI::Range(0.1, 1000.0))
      ->capture_default_str()
      ->group("Time (docs/time-varying.md)");
  sub->add_flag("--json", o->json, "Print timings and counts as JSON");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  auto run = [o]() -> int {
    const auto start = Clock::now();
    if (o->output.empty() && o->video.empty())
      throw CLI::ValidationError("--output", "is required (or --video with --times)");
    if (!o->video.empty() && o->times.empty())
      throw CLI::ValidationError("--video", "codes an animation: give --times T0:T1:N too");
    if ((!o->time.empty() || !o->times.empty()) && findVtkMethod(o->method))
      throw CLI::ValidationError("--time", "applies to models rendered with our ray caster");
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
      needs.mesh |= *m == ReconstructionMethod::Mesh;
    }

    const RenderDevice device = openRenderDevice(o->device, spec);
    spec.device = device.renderer.get();
    const bool progress = wantProgress(o->quiet || o->json);
    const int frames = o->frames > 0 ? o->frames : 1;
    SceneLoadOptions load = loadOptions(*o, progress);
    // One frame reads every block once either way; one at a time, it holds one.
    load.streamBlocks = frames == 1;
    std::vector<double> animation;
    if (!o->times.empty()) {
      if (!o->time.empty())
        throw CLI::ValidationError("--times", "renders several instants; --time renders one");
      if (!(o->output.empty() && !o->video.empty()) && !isFramePattern(o->output))
        throw CLI::ValidationError("--times",
                                   "needs an output pattern with one %d (e.g. frame_%03d.png), "
                                   "got '" +
                                       o->output + "'");
      if (!o->floatOutput.empty() || !o->depthOutput.empty())
        throw CLI::ValidationError("--times", "writes PNG frames only (no --float or --depth)");
      animation = parseTimes(o->times);
      load.time = animation.front();
    }
    LoadedScene scene = loadScene(o->input, needs, load);
    if (needs.mesh && !scene.mesh)
      throw Error("method 'mesh' renders a tetrahedral mesh's own field; " + o->input +
                  " holds points without cells: render it with --method mfa");
    std::string tfWarning;
    RenderSettings settings = o->render.settingsFor(scene, &tfWarning);
    settings.depth = !o->depthOutput.empty();
    if (!animation.empty()) {
      if (!scene.timeVarying)
        throw Error("--times animates a time-varying model; " + o->input + " has no time axis");
      const TimeAxis& axis = scene.timeVarying->timeAxis();
      for (double t : animation)
        if (!axis.contains(t)) {
          std::ostringstream m;
          m << "--times: t = " << t << " lies outside the model's time range (" << axis.begin
            << " .. " << axis.end << ")";
          throw Error(m.str());
        }
      if (!o->quiet && !o->json && !tfWarning.empty())
        std::cerr << "mfadvr render: warning: " << tfWarning << "\n";
      // The video is started first, so that a missing ffmpeg is said before any rendering.
      std::unique_ptr<VideoWriter> video;
      if (!o->video.empty())
        video = std::make_unique<VideoWriter>(o->video, settings.width, settings.height, o->fps);
      nlohmann::json list = nlohmann::json::array();
      double renderSum = 0.0, contractSum = 0.0;
      for (size_t i = 0; i < animation.size(); ++i) {
        const auto contractStart = Clock::now();
        if (i > 0) scene.setTime(animation[i]);
        const double contract = i > 0 ? secondsSince(contractStart) : 0.0;
        MethodRenderStats stats;
        const Image image = renderMethod(scene.view(), spec, settings, &stats);
        const Image8 pixels = toImage8(image, o->alpha);
        nlohmann::json frame = {
            {"time", animation[i]}, {"render", stats.seconds}, {"contract", contract}};
        if (!o->output.empty()) {
          frame["file"] = frameFileName(o->output, static_cast<int>(i));
          writePng(frame["file"].get<std::string>(), pixels);
        }
        if (video) video->add(pixels);
        renderSum += stats.seconds;
        contractSum += contract;
        list.push_back(std::move(frame));
        if (progress) printProgress("frames", double(i + 1) / double(animation.size()));
      }
      if (video) video->finish();
      const double n = static_cast<double>(animation.size());
      if (o->json) {
        nlohmann::json j;
        j["input"] = o->input;
        j["output"] = o->output;
        if (video) j["video"] = o->video;
        j["method"] = methodName(spec.method);
        j["device"] = device.name;
        j["width"] = settings.width;
        j["height"] = settings.height;
        j["frames"] = list;
        j["seconds"] = {{"load", scene.loadSeconds},
                        {"mean_render", renderSum / n},
                        {"mean_contract", animation.size() > 1 ? contractSum / (n - 1) : 0.0},
                        {"total", secondsSince(start)}};
        std::cout << j.dump(2) << "\n";
      } else {
        const std::string written =
            (o->output.empty() ? std::string()
                               : list.front()["file"].get<std::string>() + " .. " +
                                     list.back()["file"].get<std::string>()) +
            (o->output.empty() || !video ? "" : ", ") + (video ? o->video : std::string());
        std::printf(
            "%s: %zu frames, t = %g .. %g, %dx%d, mean render %.3f s, mean time "
            "contraction %.4f s, total %.3f s\n  on the %s\n",
            written.c_str(), animation.size(), animation.front(), animation.back(), settings.width,
            settings.height, renderSum / n, animation.size() > 1 ? contractSum / (n - 1) : 0.0,
            secondsSince(start), device.description.c_str());
      }
      return 0;
    }
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
      j["time"] = scene.timeVarying ? nlohmann::json(scene.time) : nlohmann::json(nullptr);
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
      std::printf("%s: %s, %dx%d, step %.4g, %s", o->output.c_str(), label.c_str(), settings.width,
                  settings.height, settings.sampleDistance, settings.shade ? "shaded" : "unshaded");
      if (scene.timeVarying) std::printf(", t = %g", scene.time);
      std::printf("\n");
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
