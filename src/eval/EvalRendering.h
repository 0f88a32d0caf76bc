#pragma once
// The rendering steps the experiments share: one of our methods or one of VTK's renderers on a
// scene, timed; image comparison against the truth; scene settings built from a few choices.
#include <string>
#include <vector>

#include "core/image/Image.h"
#include "core/image/ImageMetrics.h"
#include "core/mesh/ScatteredData.h"
#include "core/render/ReconstructionMethod.h"
#include "core/render/RenderSettings.h"
#include "vtkrender/VtkMethod.h"

namespace mfadvr::eval {

struct TimedImage {
  Image8 image;
  double seconds = 0.0;       // render time (median over the repeats)
  double firstSeconds = 0.0;  // the first render, set-up included (VTK builds its structures)
};

// Renders `spec` `repeats` times (>= 1) through our ray caster; seconds = median ray-casting
// time, firstSeconds adds the filter's set-up (padding, prefiltering) to the first.
TimedImage renderOurs(const SceneData& scene, const MethodSpec& spec,
                      const RenderSettings& settings, int repeats = 1);

// Renders with one of VTK's renderers: `frames` >= 1 frames; seconds = median of the frames
// after the first (the first when there is one), firstSeconds the first frame's.
TimedImage renderVtk(VtkMethod method, const StructuredGrid* grid, const ScatteredData* mesh,
                     const RenderSettings& settings, int frames);

// The settings the experiments start from: the image size, a camera framing the box from VTK's
// default direction turned by azimuth/elevation, a transfer function (opacity preset and colour
// map as `render --tf/--colormap` take them) over [vmin, vmax], unit distance and step from the
// data spacing (step = stepFraction x the smallest spacing), the given thread count.
RenderSettings sceneSettings(int width, int height, const Vec3d& boxMin, const Vec3d& boxMax,
                             double azimuth, double elevation, const std::string& opacity,
                             const std::string& colormap, double vmin, double vmax,
                             const Vec3d& spacing, double stepFraction, int threads);

// Per-channel |image - truth| x gain, the error images of Fig. 6.
constexpr double kErrorImageGain = 4.0;

}  // namespace mfadvr::eval
