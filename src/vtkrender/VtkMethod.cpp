#include "vtkrender/VtkMethod.h"

#include "core/util/Error.h"

namespace mfadvr {

namespace {

constexpr VtkMethod kAll[] = {VtkMethod::FixedPoint, VtkMethod::Bunyk, VtkMethod::ZSweep,
                              VtkMethod::ProjectedTetrahedra};

}  // namespace

std::vector<std::string> vtkMethodNames() {
  std::vector<std::string> names;
  for (const VtkMethod m : kAll) names.push_back(vtkMethodName(m));
  return names;
}

std::string vtkMethodName(VtkMethod m) {
  switch (m) {
    case VtkMethod::FixedPoint:
      return "vtk-fixedpoint";
    case VtkMethod::Bunyk:
      return "vtk-bunyk";
    case VtkMethod::ZSweep:
      return "vtk-zsweep";
    case VtkMethod::ProjectedTetrahedra:
      return "vtk-pt";
  }
  throw Error("unknown VTK method");
}

std::optional<VtkMethod> findVtkMethod(const std::string& name) {
  for (const VtkMethod m : kAll)
    if (vtkMethodName(m) == name) return m;
  return std::nullopt;
}

std::string vtkMapperClassName(VtkMethod m) {
  switch (m) {
    case VtkMethod::FixedPoint:
      return "vtkFixedPointVolumeRayCastMapper";
    case VtkMethod::Bunyk:
      return "vtkUnstructuredGridVolumeRayCastMapper";
    case VtkMethod::ZSweep:
      return "vtkUnstructuredGridVolumeZSweepMapper";
    case VtkMethod::ProjectedTetrahedra:
      return "vtkProjectedTetrahedraMapper";
  }
  throw Error("unknown VTK method");
}

bool vtkMethodNeedsTetrahedra(VtkMethod m) {
  return m != VtkMethod::FixedPoint;
}

bool vtkMethodShades(VtkMethod m) {
  return m == VtkMethod::FixedPoint;
}

bool vtkMethodUsesSampleDistance(VtkMethod m) {
  return m == VtkMethod::FixedPoint;
}

}  // namespace mfadvr
