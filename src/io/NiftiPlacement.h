#pragma once
// What a NIfTI header adds to the samples VTK's reader (vtkNIFTIImageReader) reads: the
// scl_slope / scl_inter calibration and the placement in world (RAS) coordinates by the sform,
// else the qform. Shared by the in-memory read and the streamed read (StreamedVolumeReader.h).
#include <optional>
#include <string>

#include "core/grid/StructuredGrid.h"

class vtkNIFTIImageReader;

namespace mfadvr {

// value = stored * slope + intercept, when the header's calibration changes values (scl_slope
// 0 means none in NIfTI).
struct NiftiCalibration {
  double slope = 1.0;
  double intercept = 0.0;
  std::string note;  // for grid.notes
};
std::optional<NiftiCalibration> niftiCalibration(vtkNIFTIImageReader& reader);

// Notes on time points, and the sform / qform placement (GridOrientation.h: samples reordered
// into world axes when the matrix allows, else the grid keeps its voxel axes with a note).
void placeNiftiGrid(vtkNIFTIImageReader& reader, StructuredGrid& grid);

// Both, on a grid read whole.
void applyNiftiHeader(vtkNIFTIImageReader& reader, StructuredGrid& grid);

}  // namespace mfadvr
