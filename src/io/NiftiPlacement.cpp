#include "io/NiftiPlacement.h"

#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>

#include <cmath>
#include <cstdio>

#include "core/grid/GridOrientation.h"

namespace mfadvr {
namespace {

std::string formatNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace

std::optional<NiftiCalibration> niftiCalibration(vtkNIFTIImageReader& reader) {
  const double slope = reader.GetRescaleSlope();
  const double intercept = reader.GetRescaleIntercept();
  if (slope == 0.0 || !std::isfinite(slope) || !std::isfinite(intercept) ||
      (slope == 1.0 && intercept == 0.0))
    return std::nullopt;
  return NiftiCalibration{slope, intercept,
                          "values calibrated as stored * " + formatNumber(slope) + " + " +
                              formatNumber(intercept) + " (the header's scl_slope, scl_inter)"};
}

void placeNiftiGrid(vtkNIFTIImageReader& reader, StructuredGrid& grid) {
  if (vtkNIFTIImageHeader* header = reader.GetNIFTIHeader();
      header && header->GetDim(0) > 3 && header->GetDim(4) > 1) {
    grid.notes.push_back("the file holds " + std::to_string(header->GetDim(4)) +
                         " time points (4th dimension); only the first is read");
  }
  vtkMatrix4x4* matrix = reader.GetSFormMatrix();
  const char* which = "sform";
  if (!matrix) {
    matrix = reader.GetQFormMatrix();
    which = "qform";
  }
  if (!matrix) {
    grid.notes.push_back(
        "no qform or sform orientation in the header: the volume is placed in its voxel axes "
        "with the header's spacing and its first voxel at the origin");
    return;
  }
  GridToWorld toWorld;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) toWorld.linear[r][c] = matrix->GetElement(r, c);
    toWorld.offset[r] = matrix->GetElement(r, 3);
  }
  const OrientationResult placed = orientToWorld(grid, toWorld);
  if (placed.applied) {
    grid.notes.push_back(std::string("placed in world (RAS) coordinates by the header's ") + which +
                         " matrix; voxel axes run along " + placed.axes);
  } else {
    grid.notes.push_back(std::string("the header's ") + which + ": " + placed.note);
  }
}

void applyNiftiHeader(vtkNIFTIImageReader& reader, StructuredGrid& grid) {
  if (const auto calibration = niftiCalibration(reader)) {
    for (float& v : grid.values)
      v = static_cast<float>(v * calibration->slope + calibration->intercept);
    grid.notes.push_back(calibration->note);
  }
  placeNiftiGrid(reader, grid);
}

}  // namespace mfadvr
