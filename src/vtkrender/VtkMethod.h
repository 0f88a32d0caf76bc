#pragma once
// VTK 9.1's own volume renderers, offered as timed baselines next to our ray caster's methods:
// their names on the command line, the VTK class behind each, and what each does with our
// RenderSettings. docs/rendering.md ("VTK baselines") describes them.
#include <optional>
#include <string>
#include <vector>

namespace mfadvr {

enum class VtkMethod {
  FixedPoint,          // vtkFixedPointVolumeRayCastMapper: regular grids only
  Bunyk,               // vtkUnstructuredGridVolumeRayCastMapper (Bunyk ray casting): tetrahedra
  ZSweep,              // vtkUnstructuredGridVolumeZSweepMapper: tetrahedra
  ProjectedTetrahedra  // vtkProjectedTetrahedraMapper (OpenGL): tetrahedra
};

// vtk-fixedpoint, vtk-bunyk, vtk-zsweep, vtk-pt.
std::vector<std::string> vtkMethodNames();
std::string vtkMethodName(VtkMethod m);
// The method of a name, or nothing when `name` is not one of vtkMethodNames().
std::optional<VtkMethod> findVtkMethod(const std::string& name);
// The VTK class that renders it, e.g. "vtkUnstructuredGridVolumeRayCastMapper".
std::string vtkMapperClassName(VtkMethod m);
// Whether the mapper renders tetrahedral meshes (a grid is tetrahedralized first) rather than
// a regular grid.
bool vtkMethodNeedsTetrahedra(VtkMethod m);
// Whether the mapper applies RenderSettings::shade (only the fixed-point ray caster does).
bool vtkMethodShades(VtkMethod m);
// Whether the mapper samples rays at RenderSettings::sampleDistance (only the fixed-point ray
// caster; the others integrate exactly across each cell).
bool vtkMethodUsesSampleDistance(VtkMethod m);

}  // namespace mfadvr
