// mfadvr view INPUT [--method M] [scene options] [--screenshot OUT.png]
//
// An interactive VTK window on a scene: the model rendered by vtkMFAVolumeMapper inside an
// ordinary vtkRenderer, with a trackball camera. Keys switch the reconstruction method (every
// method goes through the same ray caster), the colour map and the opacity preset, and toggle
// shading. --screenshot renders one frame off screen to a PNG instead (how it is tested, under
// xvfb-run). docs/vtk-module.md describes the keys.
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkContourValues.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPlane.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/Commands.h"
#include "app/EncodeCliOptions.h"
#include "app/OptionParsing.h"
#include "app/RenderOptions.h"
#include "app/SceneLoader.h"
#include "core/image/Image.h"
#include "core/image/PngFile.h"
#include "core/render/ReconstructionMethod.h"
#include "core/render/TransferFunction.h"
#include "core/util/Error.h"
#include "device/RenderDevice.h"
#include "io/ScatteredLoader.h"
#include "io/VolumeLoader.h"
#include "vtkMFAModelData.h"
#include "vtkMFAVolumeMapper.h"
#include "vtkrender/DisplayCheck.h"
#include "vtkrender/LeakCheckPause.h"
#include "vtkrender/VtkSceneSetup.h"

namespace mfadvr::app {
namespace {

const std::vector<std::string> kOpacityCycle = {"ramp", "step:0.3", "step:0.5", "step:0.7",
                                                "tent:0.5:0.2"};

// What the keys change, and the VTK objects they change.
struct Viewer {
  LoadedScene* scene = nullptr;
  RenderOptions options;
  std::vector<ReconstructionMethod> methods;
  size_t method = 0;
  // The GPU renderer of the grid methods it renders (trilinear); the model's is the mapper's own.
  std::shared_ptr<DeviceRenderer> gpu;
  vtkNew<vtkMFAModelData> data;
  vtkNew<vtkMFAVolumeMapper> mapper;
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkVolume> volume;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;

  bool clipFacingCamera = false;  // key c: a plane through the focal point, facing the camera
  // A time-varying model: space plays (one pass through the range in kPlaySeconds, looping),
  // '.' and ',' go to the next and previous step.
  bool playing = false;
  static constexpr double kPlaySeconds = 8.0;
  static constexpr int kPlayTickMs = 40;
  double lastContractSeconds = 0.0;
  std::string savedAverageRange;  // --average-range while key b shows another blend

  // The blend mode, isovalues, clipping planes and cropping of `s` on the mapper and property.
  void applyBlendAndClipping(const RenderSettings& s) {
    switch (s.blend) {
      case BlendMode::Maximum:
        mapper->SetBlendModeToMaximumIntensity();
        break;
      case BlendMode::Minimum:
        mapper->SetBlendModeToMinimumIntensity();
        break;
      case BlendMode::Average:
        mapper->SetBlendModeToAverageIntensity();
        if (s.averageRange)
          mapper->SetAverageIPScalarRange(s.averageRange->first, s.averageRange->second);
        break;
      case BlendMode::Additive:
        mapper->SetBlendModeToAdditive();
        break;
      case BlendMode::Iso:
        mapper->SetBlendModeToIsoSurface();
        break;
      default:
        mapper->SetBlendModeToComposite();
    }
    vtkContourValues* iso = property->GetIsoSurfaceValues();
    iso->SetNumberOfContours(static_cast<int>(s.isoSurfaces.size()));
    for (size_t i = 0; i < s.isoSurfaces.size(); ++i)
      iso->SetValue(static_cast<int>(i), s.isoSurfaces[i].value);
    mapper->RemoveAllClippingPlanes();
    for (const ClipPlane& c : s.clipPlanes) {
      vtkNew<vtkPlane> plane;
      plane->SetOrigin(c.point.data());
      plane->SetNormal(c.normal.data());
      mapper->AddClippingPlane(plane);
    }
    if (clipFacingCamera) {
      vtkCamera* camera = renderer->GetActiveCamera();
      vtkNew<vtkPlane> plane;
      plane->SetOrigin(camera->GetFocalPoint());
      plane->SetNormal(camera->GetDirectionOfProjection());  // keeps the half behind the focus
      mapper->AddClippingPlane(plane);
    }
    mapper->SetCropping(s.crop ? 1 : 0);
    if (s.crop) {
      mapper->SetCroppingRegionPlanes(s.crop->min[0], s.crop->max[0], s.crop->min[1],
                                      s.crop->max[1], s.crop->min[2], s.crop->max[2]);
      mapper->SetCroppingRegionFlagsToSubVolume();
    }
  }

  // Re-derives the transfer function and shading from the options; keeps the live camera.
  void applyOptions() {
    const RenderSettings s = options.settingsFor(*scene);
    applyBlendAndClipping(s);
    applyTransferFunction(s, property);
    applyLighting(s.lighting, renderer);
    mapper->SetSampleDistance(s.sampleDistance);
    const ReconstructionMethod m = methods[method];
    if (m == ReconstructionMethod::Mfa) {
      mapper->SetFieldRenderer({});
    } else {
      const SceneData view = scene->view();
      mapper->SetFieldRenderer([view, m, gpu = gpu](const RenderSettings& settings) {
        MethodSpec spec;
        spec.method = m;
        if (gpu && deviceRendersMethod(spec)) spec.device = gpu.get();
        return renderMethod(view, spec, settings);
      });
    }
    updateStatus();
  }

  // Shows the instant t (clamped onto the range): the model contracted at t, handed to the
  // mapper; grid methods (a time-varying built-in's truth and samples) follow.
  void setTime(double t) {
    const auto start = std::chrono::steady_clock::now();
    scene->setTime(t);
    lastContractSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    data->SetModel(std::make_shared<const Model>(*scene->model));
    applyOptions();
  }

  // The next (dir 1) or previous (-1) stored step from the time shown.
  void stepTime(int dir) {
    const std::vector<double>& steps = scene->timeVarying->timeAxis().steps;
    double t = scene->time;
    if (dir > 0) {
      const auto it = std::upper_bound(steps.begin(), steps.end(), scene->time + 1e-12);
      t = it == steps.end() ? steps.front() : *it;
    } else {
      auto it = std::lower_bound(steps.begin(), steps.end(), scene->time - 1e-12);
      t = it == steps.begin() ? steps.back() : *std::prev(it);
    }
    setTime(t);
  }

  // One tick of playback.
  void tick() {
    if (!playing || !scene->timeVarying) return;
    const TimeAxis& axis = scene->timeVarying->timeAxis();
    const double advance = (axis.end - axis.begin) * kPlayTickMs / (1000.0 * kPlaySeconds);
    const double t = scene->time + advance > axis.end + 1e-12 ? axis.begin : scene->time + advance;
    setTime(std::min(t, axis.end));
    window->Render();
  }

  void updateStatus() {
    char text[512];
    char instant[64] = "";
    if (scene->timeVarying)
      std::snprintf(instant, sizeof(instant), " | t = %.4g%s", scene->time,
                    playing ? " (playing)" : "");
    std::snprintf(text, sizeof(text), "mfadvr view: %s | colours %s | opacity %s | %s | %.0f ms%s",
                  methodName(methods[method]).c_str(),
                  options.colormap.empty() ? "cool-to-warm" : options.colormap.c_str(),
                  options.tf.empty() ? "ramp" : options.tf.c_str(),
                  (std::string(options.shade ? "shaded " : "unshaded ") + options.blend +
                   (clipFacingCamera ? ", clipped" : ""))
                      .c_str(),
                  1000.0 * mapper->GetTimeToDraw(), instant);
    // The window title: a text actor would need VTK's FreeType module, whose CMake package
    // drags in MPI on Debian.
    window->SetWindowName(text);
  }

  void onKey(const std::string& key) {
    if (key == "m") {
      method = (method + 1) % methods.size();
    } else if (key == "t") {
      const auto names = colorMapPresetNames();
      size_t i = 0;
      while (i < names.size() && names[i] != options.colormap) ++i;
      options.colormap = names[(i + 1) % names.size()];
    } else if (key == "o") {
      size_t i = 0;
      while (i < kOpacityCycle.size() && kOpacityCycle[i] != options.tf) ++i;
      options.tf = kOpacityCycle[(i + 1) % kOpacityCycle.size()];
    } else if (key == "s") {
      options.shade = !options.shade;
    } else if (key == "b" && (!options.gradientOpacity.empty() || !options.tf2d.empty())) {
      std::fprintf(stderr,
                   "mfadvr view: --gradient-opacity and --tf2d classify composite renders "
                   "only; the blend stays composite\n");
      return;
    } else if (key == "b") {
      // Composite, max, min, average, additive, and iso where isovalues were given.
      std::vector<std::string> modes{"composite", "max", "min", "average", "additive"};
      if (!options.isoValues.empty()) modes.push_back("iso");
      size_t i = 0;
      while (i < modes.size() && modes[i] != options.blend) ++i;
      options.blend = modes[(i + 1) % modes.size()];
      // The average range belongs to the average blend only.
      if (options.blend != "average") savedAverageRange.swap(options.averageRange);
      if (options.blend == "average") options.averageRange.swap(savedAverageRange);
    } else if (key == "c") {
      clipFacingCamera = !clipFacingCamera;
    } else if ((key == "period" || key == "comma") && scene->timeVarying) {
      playing = false;
      stepTime(key == "period" ? 1 : -1);
    } else if (key == "space" && scene->timeVarying) {
      playing = !playing;
      updateStatus();
      return;
    } else {
      return;
    }
    applyOptions();
    window->Render();
    updateStatus();  // with this frame's time
    window->Render();
  }
};

// The trackball camera, with the viewer's keys taking precedence over the style's own.
class ViewerStyle : public vtkInteractorStyleTrackballCamera {
 public:
  static ViewerStyle* New();
  vtkTypeMacro(ViewerStyle, vtkInteractorStyleTrackballCamera);
  Viewer* viewer = nullptr;

  void OnChar() override {
    const std::string key = this->Interactor->GetKeySym() ? this->Interactor->GetKeySym() : "";
    if (key == "m" || key == "t" || key == "o" || key == "s" || key == "b" || key == "c" ||
        key == "period" || key == "comma" || key == "space") {
      viewer->onKey(key);
      return;
    }
    if (key == "h") {
      std::cout << kKeyHelp;
      return;
    }
    vtkInteractorStyleTrackballCamera::OnChar();
  }

  static constexpr const char* kKeyHelp =
      "keys: m method, t colour map, o opacity preset, s shading on/off, b blend mode, "
      "c clipping plane through the focal point (on/off), r reset camera, "
      "h help, q quit; time-varying models: space play/pause, . next step, , previous step; "
      "drag to rotate, shift-drag to pan, wheel to zoom\n";
};
vtkStandardNewMacro(ViewerStyle);

// What an interactive session does, timed off screen: frames at the interactive update rate
// while the camera turns (3 degrees a frame), then one frame at VTK's still rate.
int runViewBenchmark(Viewer& viewer, int frames, double fps) {
  using Clock = std::chrono::steady_clock;
  viewer.window->SetOffScreenRendering(1);
  vtkCamera* camera = viewer.renderer->GetActiveCamera();
  std::vector<double> seconds, distances;
  {
    const LeakCheckPause pause;  // Mesa's process-lifetime allocations (LeakCheckPause.h)
    viewer.window->SetDesiredUpdateRate(fps);
    for (int i = 0; i < frames; ++i) {
      camera->Azimuth(3.0);
      viewer.renderer->ResetCameraClippingRange();
      const auto start = Clock::now();
      viewer.window->Render();
      seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
      distances.push_back(viewer.mapper->GetLastImageSampleDistance());
      std::printf("moving frame %3d: %.1f ms, image sample distance %.2f\n", i + 1,
                  1000.0 * seconds.back(), distances.back());
    }
    viewer.window->SetDesiredUpdateRate(0.0001);  // vtkRenderWindowInteractor's still rate
    const auto start = Clock::now();
    viewer.window->Render();
    const double still = std::chrono::duration<double>(Clock::now() - start).count();
    // The first frames calibrate the sample distance; the rate is the median of the rest.
    const size_t skip = seconds.size() > 4 ? 2 : 0;
    std::vector<double> settled(seconds.begin() + static_cast<std::ptrdiff_t>(skip), seconds.end());
    std::sort(settled.begin(), settled.end());
    const double median = settled[settled.size() / 2];
    std::printf("moving: %.1f frames/s (median frame %.1f ms over %zu frames, target %.1f/s)\n",
                1.0 / median, 1000.0 * median, settled.size(), fps);
    std::printf("still frame (full quality): %.1f ms, image sample distance %.2f\n", 1000.0 * still,
                viewer.mapper->GetLastImageSampleDistance());
    std::printf("device: %s\n", viewer.mapper->GetLastDeviceDescription());
    if (viewer.scene->timeVarying) {
      // Changing the time: the contraction of the time axis, then the still frame it brings.
      const TimeAxis& axis = viewer.scene->timeVarying->timeAxis();
      std::vector<double> contract, frame;
      for (int i = 1; i <= 8; ++i) {
        viewer.setTime(axis.begin + (axis.end - axis.begin) * i / 9.0);
        contract.push_back(viewer.lastContractSeconds);
        const auto at = Clock::now();
        viewer.window->Render();
        frame.push_back(std::chrono::duration<double>(Clock::now() - at).count());
      }
      std::sort(contract.begin(), contract.end());
      std::sort(frame.begin(), frame.end());
      std::printf(
          "changing the time: %.1f ms to contract the time axis (median of %zu), then a "
          "%.1f ms still frame\n",
          1000.0 * contract[contract.size() / 2], contract.size(),
          1000.0 * frame[frame.size() / 2]);
    }
    viewer.window->Finalize();
  }
  return 0;
}

}  // namespace

Command addViewCommand(CLI::App& app) {
  struct Options {
    std::string input, method = "mfa", screenshot, spacing, origin, device = "auto", time;
    FieldOptionTexts field;
    EncodeCliOptions encode;
    RenderOptions render;
    bool quiet = false;
    double interactiveFps = 15.0;  // vtkRenderWindowInteractor's default desired update rate
    int benchmarkFrames = 0;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "view", "Interactive VTK window on a model, volume or mesh (vtkMFAVolumeMapper)");
  sub->add_option("input", o->input,
                  "A model (.mfa), a volume, mesh or point file, or builtin:NAME[:N|:NXxNYxNZ]")
      ->required();
  sub->add_option("--method", o->method,
                  "Reconstruction shown first; key m cycles through those the input allows")
      ->check(CLI::IsMember(reconstructionMethodNames()))
      ->capture_default_str();
  sub->add_option("--screenshot", o->screenshot,
                  "Render one frame off screen to this PNG and exit (no window)");
  sub->add_option("--interactive-fps", o->interactiveFps,
                  "Frames per second to keep while the camera moves: coarser frames (fewer rays, "
                  "magnified smoothly) are drawn while dragging, the full frame when it stops")
      ->check(CLI::Range(0.5, 240.0))
      ->capture_default_str();
  sub->add_option("--benchmark", o->benchmarkFrames,
                  "Off screen, no window: render N frames while turning the camera (as a drag "
                  "does), then the full-quality frame; print frames per second and times")
      ->check(CLI::Range(1, 100000));
  sub->add_option("--time", o->time,
                  "Time-varying models: the instant shown first (default: the first step); "
                  "space plays the series, '.' and ',' step through it");
  o->render.addTo(sub);
  addDeviceOption(sub, o->device);
  o->encode.addTo(sub, "Encoding (non-model inputs)");
  const char* in = "Input";
  sub->add_option("--spacing", o->spacing, "Sample spacing S or SX,SY,SZ (overrides the file's)")
      ->group(in);
  sub->add_option("--origin", o->origin, "Position of the first sample X,Y,Z")->group(in);
  o->field.addTo(sub, in);
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  auto run = [o]() -> int {
    if (isBlockModelInput(o->input))
      throw Error(o->input +
                  " is a multi-block model; `view` shows single models: render it with "
                  "`mfadvr render`, or open it in ParaView (docs/paraview.md)");
    requireRenderDisplay();
    // Grid methods need the samples: volumes and built-in functions have them; model files
    // and scattered inputs do not (a model of a built-in function has its truth). A mesh
    // renders as itself too (method mesh).
    SceneNeeds needs;
    needs.model = true;
    needs.grid = !isModelFile(o->input) && !isScatteredInput(o->input);
    needs.mesh = !isModelFile(o->input) && isScatteredInput(o->input);
    SceneLoadOptions load;
    load.encode = o->encode.parse();
    load.volume = parseVolumeLoadOptions(o->spacing, o->origin, o->field);
    load.progress = wantProgress(o->quiet);
    if (!o->time.empty()) load.time = parseNumberList("--time", o->time, 1, 1)[0];
    LoadedScene scene = loadScene(o->input, needs, load);

    auto viewer = std::make_unique<Viewer>();
    viewer->scene = &scene;
    viewer->options = o->render;
    viewer->methods.push_back(ReconstructionMethod::Mfa);
    if (scene.grid)
      for (auto m : {ReconstructionMethod::Trilinear, ReconstructionMethod::Tricubic,
                     ReconstructionMethod::CatmullRom, ReconstructionMethod::BSpline})
        viewer->methods.push_back(m);
    if (scene.truth) viewer->methods.push_back(ReconstructionMethod::Truth);
    if (scene.mesh) viewer->methods.push_back(ReconstructionMethod::Mesh);
    const ReconstructionMethod first = parseReconstructionMethod(o->method);
    viewer->method = 0;
    while (viewer->method < viewer->methods.size() && viewer->methods[viewer->method] != first)
      ++viewer->method;
    if (viewer->method == viewer->methods.size())
      throw Error("--method " + o->method + " needs data that " + o->input +
                  " does not provide; available: " + [&] {
                    std::string list;
                    for (auto m : viewer->methods)
                      list += (list.empty() ? "" : ", ") + methodName(m);
                    return list;
                  }());

    // The device, checked before a window opens: --device cuda fails here without a GPU.
    MethodSpec firstSpec;
    firstSpec.method = first;
    RenderDevice device = openRenderDevice(o->device, firstSpec);
    viewer->gpu = std::move(device.renderer);
    viewer->mapper->SetDevice(o->device == "cpu"    ? vtkMFAVolumeMapper::DeviceCPU
                              : o->device == "cuda" ? vtkMFAVolumeMapper::DeviceCUDA
                                                    : vtkMFAVolumeMapper::DeviceAuto);

    // The scene as the render command would draw it, set up in VTK.
    std::string tfWarning;
    const RenderSettings settings = o->render.settingsFor(scene, &tfWarning);
    if (!o->quiet && !tfWarning.empty()) std::cerr << "mfadvr view: warning: " << tfWarning << "\n";
    viewer->data->SetModel(std::make_shared<const Model>(*scene.model));
    viewer->mapper->SetInputData(viewer->data.GetPointer());
    viewer->mapper->SetEarlyRayTerminationOpacity(settings.earlyTerminationOpacity);
    viewer->mapper->SetNumberOfThreads(settings.threads);
    // Curvature classification (composite and iso blends): the mapper reads the specification
    // itself, as a VTK program passes it.
    if (!o->render.curvatureTf.empty())
      viewer->mapper->SetCurvatureTransferFunction(o->render.curvatureTf.c_str());
    viewer->mapper->SetContourWidth(settings.contourPixels);
    viewer->mapper->SetContourColor(settings.contourColor[0], settings.contourColor[1],
                                    settings.contourColor[2]);
    viewer->property->SetScalarOpacityUnitDistance(settings.opacityUnitDistance);
    viewer->volume->SetMapper(viewer->mapper);
    viewer->volume->SetProperty(viewer->property);
    viewer->renderer->AddVolume(viewer->volume);
    applyBackground(settings.background, viewer->renderer);
    viewer->window->AddRenderer(viewer->renderer);
    viewer->window->SetSize(settings.width, settings.height);
    viewer->window->SetMultiSamples(0);
    applyCamera(settings.camera, viewer->renderer);
    viewer->applyOptions();

    if (o->benchmarkFrames > 0) {
      return runViewBenchmark(*viewer, o->benchmarkFrames, o->interactiveFps);
    }
    if (!o->screenshot.empty()) {
      viewer->window->SetOffScreenRendering(1);
      {
        const LeakCheckPause pause;  // Mesa's process-lifetime allocations (LeakCheckPause.h)
        viewer->window->Render();
      }
      const Image8 shot = readWindowRgb(viewer->window);
      {
        const LeakCheckPause pause;
        viewer->window->Finalize();
      }
      writePng(o->screenshot, shot);
      std::printf("%s: %s, %dx%d, frame %.3f s, on the %s\n", o->screenshot.c_str(),
                  methodName(viewer->methods[viewer->method]).c_str(), settings.width,
                  settings.height, viewer->mapper->GetTimeToDraw(), device.description.c_str());
      return 0;
    }

    vtkNew<vtkRenderWindowInteractor> interactor;
    vtkNew<ViewerStyle> style;
    style->viewer = viewer.get();
    interactor->SetInteractorStyle(style);
    interactor->SetRenderWindow(viewer->window);
    // Still frames at full resolution; while dragging the mapper lowers the image sample
    // distance to keep about this many frames per second.
    interactor->SetDesiredUpdateRate(o->interactiveFps);
    // Playback of a time-varying model: a repeating timer, a tick per kPlayTickMs.
    vtkNew<vtkCallbackCommand> playback;
    if (scene.timeVarying) {
      playback->SetClientData(viewer.get());
      playback->SetCallback([](vtkObject*, unsigned long, void* client, void*) {
        static_cast<Viewer*>(client)->tick();
      });
      interactor->AddObserver(vtkCommand::TimerEvent, playback);
      interactor->Initialize();
      interactor->CreateRepeatingTimer(Viewer::kPlayTickMs);
    }
    std::cout << ViewerStyle::kKeyHelp;
    viewer->window->Render();
    viewer->updateStatus();
    interactor->Start();
    return 0;
  };
  return {sub, run};
}

}  // namespace mfadvr::app
