#include "eval/EvalRendering.h"

#include <algorithm>

#include "core/util/Error.h"
#include "vtkrender/VtkBaselineRenderer.h"

namespace mfadvr::eval {

TimedImage renderOurs(const SceneData& scene, const MethodSpec& spec,
                      const RenderSettings& settings, int repeats) {
  if (repeats < 1) throw Error("renderOurs: repeats must be >= 1");
  TimedImage out;
  std::vector<double> seconds;
  for (int r = 0; r < repeats; ++r) {
    MethodRenderStats stats;
    Image image = renderMethod(scene, spec, settings, &stats);
    if (r == 0) {
      out.image = toImage8(image);
      out.firstSeconds = stats.setupSeconds + stats.seconds;
    }
    seconds.push_back(stats.seconds);
  }
  out.seconds = medianSeconds(seconds);
  return out;
}

TimedImage renderVtk(VtkMethod method, const StructuredGrid* grid, const ScatteredData* mesh,
                     const RenderSettings& settings, int frames) {
  VtkBaselineInput input;
  input.grid = grid;
  input.mesh = mesh;
  VtkBaselineRenderer renderer(method, input, settings);
  const VtkFrameTimes times = renderer.renderFrames(frames);
  TimedImage out;
  out.image = renderer.readBack();
  out.firstSeconds = times.firstSeconds;
  out.seconds = times.medianSeconds;
  return out;
}

RenderSettings sceneSettings(int width, int height, const Vec3d& boxMin, const Vec3d& boxMax,
                             double azimuth, double elevation, const std::string& opacity,
                             const std::string& colormap, double vmin, double vmax,
                             const Vec3d& spacing, double stepFraction, int threads) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.camera.resetToBounds(boxMin, boxMax);
  if (azimuth != 0.0) s.camera.azimuth(azimuth);
  if (elevation != 0.0) s.camera.elevation(elevation);
  s.transferFunction = parseTransferFunction(opacity, colormap).resolved(vmin, vmax);
  s.opacityUnitDistance = spacing.minCoeff();
  s.sampleDistance = stepFraction * spacing.minCoeff();
  s.threads = threads;
  s.validate();
  return s;
}

}  // namespace mfadvr::eval
