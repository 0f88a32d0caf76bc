#pragma once
// Picks the array a FieldSelection names from a VTK data set and turns its tuples into one
// scalar per point or cell. Internal to mfadvr_io, shared by the image and the mesh readers;
// VTK types are only forward-declared.
#include <string>
#include <vector>

#include "io/FieldSelection.h"

class vtkDataArray;
class vtkDataSet;

namespace mfadvr {

struct SelectedVtkField {
  vtkDataArray* array = nullptr;
  bool fromCells = false;
  int component = FieldSelection::kWholeArray;  // as chosen; kWholeArray for 1-component arrays
  std::string name;                             // of the encoded field (selectedFieldName)
};

// The array `selection` asks for. Without a name: the active scalars, else the first numeric
// array that can be used (one component, or any when a component was chosen), from the point
// data, then (unless the selection says points) from the cell data. Throws mfadvr::Error
// naming `path` and listing the arrays there are when none fits: no arrays, a missing name, an
// array of another association, a multi-component array without --component, a component out
// of range, a non-numeric array.
SelectedVtkField selectVtkField(const std::string& path, vtkDataSet* data,
                                const FieldSelection& selection);

// One value per tuple of the selected array: the value, the chosen component, or the
// magnitude of the components; float for grids (the samples' precision), double for points.
template <typename Out>
std::vector<Out> selectedValues(const SelectedVtkField& field);

}  // namespace mfadvr
