#pragma once
// One entry point for scattered inputs: unstructured and curvilinear meshes and point clouds,
// read through VTK's readers (the text formats directly). The header stays free of VTK types.
// docs/input-formats.md ("Scattered points and meshes") describes the formats and the errors.
#include <string>

#include "core/mesh/ScatteredData.h"
#include "io/FieldSelection.h"

namespace mfadvr {

struct ScatteredLoadOptions {
  // Array to read (name, point or cell data, component; selectVtkField). Default: the active
  // scalars, else the first one-component point-data array, else the same from the cell data.
  // A cell-data array is averaged to the points. Text files have one value column; a name must
  // match its header.
  FieldSelection field;
};

// Reads a mesh or point cloud by extension: .vtu, .vts, .vtp, legacy .vtk (DATASET
// UNSTRUCTURED_GRID, STRUCTURED_GRID or POLYDATA), .csv/.txt/.xyz ("x y z v" rows). Cells of
// dimension 3 are split into tetrahedra; 2-D, 1-D and vertex cells are ignored (such inputs are
// point clouds). Returns validated data. Throws mfadvr::Error naming the file: missing or
// unreadable file, VTK's read errors, no points, a missing or multi-component field (listing
// the arrays there are), NaN/Inf values, a box without volume.
ScatteredData loadScatteredData(const std::string& path, const ScatteredLoadOptions& options = {});

// Whether `path` names a scattered input (by extension; for legacy .vtk by the DATASET line of
// its header) rather than a volume. A .vtk file that cannot be read or holds STRUCTURED_POINTS
// is not (the volume loader reads or reports it).
bool isScatteredInput(const std::string& path);

// Human-readable list of supported scattered formats for --help text, one per line.
std::string supportedScatteredFormats();

}  // namespace mfadvr
