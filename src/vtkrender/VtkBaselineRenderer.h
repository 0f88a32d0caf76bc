#pragma once
// Renders a scene with one of VTK 9.1's volume mappers, off screen, and times its frames: the
// baselines our ray caster is compared with (docs/architecture.md, Baselines). The scene is the one
// our ray caster renders from the same RenderSettings: camera, transfer function, opacity unit
// distance, shading, lights, background, image size and (for the fixed-point ray caster) the
// sample distance. docs/rendering.md ("VTK baselines") says what each mapper does with them.
//
// Debian's VTK needs an X display even off screen: construction throws mfadvr::Error when none
// can be opened (run under `xvfb-run -a`). The header is free of VTK types.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/grid/StructuredGrid.h"
#include "core/image/Image.h"
#include "core/mesh/ScatteredData.h"
#include "core/render/RenderSettings.h"
#include "vtkrender/VtkMethod.h"

namespace mfadvr {

// What to render; pointers are borrowed and must outlive the constructor only (VTK copies the
// data). vtk-fixedpoint needs the grid. The tetrahedral mappers take the mesh when there is one,
// else the grid, tetrahedralized.
struct VtkBaselineInput {
  const StructuredGrid* grid = nullptr;
  const ScatteredData* mesh = nullptr;
};

struct VtkFrameTimes {
  // Wall time of each vtkRenderWindow::Render() + WaitForCompletion(), first frame first.
  std::vector<double> seconds;
  // The first frame builds VTK's internal structures (tables, gradients, cell connectivity,
  // sorting structures): reported on its own.
  double firstSeconds = 0.0;
  // Median of the frames after the first; the first frame's time when only one was rendered.
  double medianSeconds = 0.0;
};

class VtkBaselineRenderer {
 public:
  // Builds the VTK pipeline: data set (tetrahedralizing a grid for the tetrahedral mappers),
  // mapper, volume property, lights, camera and off-screen window. Renders nothing yet.
  // Throws mfadvr::Error for a missing input, vtk-fixedpoint without a grid, a point cloud
  // without cells, invalid settings, or no display.
  VtkBaselineRenderer(VtkMethod method, const VtkBaselineInput& input,
                      const RenderSettings& settings);
  ~VtkBaselineRenderer();
  VtkBaselineRenderer(const VtkBaselineRenderer&) = delete;
  VtkBaselineRenderer& operator=(const VtkBaselineRenderer&) = delete;

  VtkMethod method() const;
  // Shading on or off for the following frames (only vtk-fixedpoint applies it).
  void setShade(bool shade);

  // Renders one full frame (the camera is marked modified so that VTK really re-renders) and
  // returns its wall time, WaitForCompletion included. Throws mfadvr::Error when VTK reports an
  // error while rendering.
  double renderFrame();
  // Renders `frames` >= 1 frames and summarizes their times.
  VtkFrameTimes renderFrames(int frames);
  // The last frame as 8-bit RGB, row 0 at the top.
  Image8 readBack();

  std::int64_t pointCount() const;
  std::int64_t cellCount() const;     // voxels for vtk-fixedpoint, tetrahedra otherwise
  bool tetrahedralized() const;       // a grid was split into tetrahedra for this mapper
  double preparationSeconds() const;  // building the VTK data set (and tetrahedralizing)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Median of `v` (the mean of the middle two for an even count); 0 for an empty list.
double medianSeconds(std::vector<double> v);

}  // namespace mfadvr
