#pragma once
// Conversions from VTK data objects already in memory (a pipeline's output) to the encoders'
// inputs, with the same field selection and errors as the file readers. Unlike the other io
// headers this one names VTK types; it serves the VTK module.
#include <string>

#include "core/grid/GridSamples.h"
#include "core/grid/StructuredGrid.h"
#include "core/mesh/ScatteredData.h"

class vtkDataSet;
class vtkImageData;

namespace mfadvr {

// The point-data array `field` (empty: the active scalars, else the first array) of an
// axis-aligned image, as a grid. `source` names the data in error messages and provenance.
// Throws mfadvr::Error as readVtkVolume does. With `inPlace`, a plain scalar array (one
// component, contiguous) is not copied: *inPlace views it (valid while the image's array lives)
// and the grid's values stay empty; otherwise *inPlace is left empty and the values are copied.
StructuredGrid gridFromVtkImage(vtkImageData* image, const std::string& field,
                                const std::string& source, GridSamples* inPlace = nullptr);

// Any data set as scattered data, as loadScatteredData reads a mesh file: cells of dimension 3
// become tetrahedra, a cell-data field is averaged to the points, a data set without 3-D cells
// is a point cloud. Returns validated data; throws mfadvr::Error naming `source`.
ScatteredData scatteredFromVtkDataSet(vtkDataSet* data, const std::string& field,
                                      const std::string& source);

}  // namespace mfadvr
