#include "io/VtkFieldSelection.h"

#include <cmath>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkSetGet.h>
#include <vtkType.h>

#include "core/util/Error.h"
#include "io/VtkSupport.h"

namespace mfadvr {
namespace {

std::string nameOf(vtkDataArray* a) {
  return a->GetName() ? a->GetName() : "";
}

std::string listArrays(vtkDataSet* data) {
  return "point data: " + describeVtkArrays(data->GetPointData()) +
         "; cell data: " + describeVtkArrays(data->GetCellData());
}

template <typename T, typename Out>
void copyValues(const T* in, size_t count, Out* out) {
  for (size_t n = 0; n < count; ++n) out[n] = static_cast<Out>(in[n]);
}

bool numeric(vtkDataArray* a) {
  return a && !vtkSampleTypeName(a).empty();
}

bool usable(vtkDataArray* a, int component) {
  return numeric(a) &&
         (a->GetNumberOfComponents() == 1 ||
          (component != FieldSelection::kWholeArray && component < a->GetNumberOfComponents()));
}

// The active scalars, else the first usable array, of one attribute set; null when none fits.
vtkDataArray* defaultArray(vtkDataSetAttributes* set, int component) {
  if (vtkDataArray* active = set->GetScalars(); usable(active, component)) return active;
  for (int i = 0; i < set->GetNumberOfArrays(); ++i)
    if (vtkDataArray* a = set->GetArray(i); usable(a, component)) return a;
  return nullptr;
}

// The first multi-component numeric array of the sets searched, for the advice in an error.
vtkDataArray* firstVectorArray(vtkDataSet* data, FieldAssociation association) {
  for (vtkDataSetAttributes* set : {static_cast<vtkDataSetAttributes*>(data->GetPointData()),
                                    static_cast<vtkDataSetAttributes*>(data->GetCellData())}) {
    const bool cells = set == data->GetCellData();
    if ((cells && association == FieldAssociation::kPoints) ||
        (!cells && association == FieldAssociation::kCells))
      continue;
    for (int i = 0; i < set->GetNumberOfArrays(); ++i)
      if (vtkDataArray* a = set->GetArray(i); numeric(a) && a->GetNumberOfComponents() > 1)
        return a;
  }
  return nullptr;
}

std::string componentAdvice(vtkDataArray* a) {
  return "choose one with --component N (0.." + std::to_string(a->GetNumberOfComponents() - 1) +
         ") or --component magnitude";
}

}  // namespace

SelectedVtkField selectVtkField(const std::string& path, vtkDataSet* data,
                                const FieldSelection& selection) {
  vtkPointData* points = data->GetPointData();
  vtkCellData* cells = data->GetCellData();
  const bool wantPoints = selection.association != FieldAssociation::kCells;
  const bool wantCells = selection.association != FieldAssociation::kPoints;
  const int component = selection.component;
  SelectedVtkField out;

  if (selection.name.empty()) {
    if (wantPoints) out.array = defaultArray(points, component);
    if (!out.array && wantCells) {
      out.array = defaultArray(cells, component);
      out.fromCells = out.array != nullptr;
    }
    if (!out.array) {
      const std::string where = associationName(selection.association);
      if (points->GetNumberOfArrays() == 0 && cells->GetNumberOfArrays() == 0)
        throw Error(path +
                    ": the file holds no point-data or cell-data arrays; a scalar field "
                    "(one value per point or cell) is needed");
      if (vtkDataArray* v = firstVectorArray(data, selection.association);
          v && component == FieldSelection::kWholeArray)
        throw Error(path + ": no one-component numeric array in the " + where + "; array '" +
                    nameOf(v) + "' has " + std::to_string(v->GetNumberOfComponents()) +
                    " components per sample: " + componentAdvice(v) + "; " + listArrays(data));
      throw Error(path + ": no numeric array in the " + where + " to use as the scalar field" +
                  (component >= 0 ? " with component " + std::to_string(component) : "") + "; " +
                  listArrays(data));
    }
  } else {
    const char* name = selection.name.c_str();
    if (wantPoints) out.array = points->GetArray(name);
    if (!out.array && wantCells) {
      out.array = cells->GetArray(name);
      out.fromCells = out.array != nullptr;
    }
    if (!out.array) {
      std::string why = "no " + std::string(associationName(selection.association)) +
                        " array named '" + selection.name + "'";
      if (!wantCells && cells->GetAbstractArray(name))
        why += " (there is a cell-data array of that name: --association cell reads it)";
      else if (!wantPoints && points->GetAbstractArray(name))
        why += " (there is a point-data array of that name: --association point reads it)";
      else if (points->GetAbstractArray(name) || cells->GetAbstractArray(name))
        why = "the array '" + selection.name + "' is not numeric";
      throw Error(path + ": " + why + "; " + listArrays(data));
    }
  }

  vtkDataArray* a = out.array;
  const std::string label = "array '" + nameOf(a) + "'";
  if (!numeric(a)) {
    throw Error(path + ": " + label + " has sample type " + a->GetDataTypeAsString() +
                "; expected an integer or floating-point type");
  }
  const int components = a->GetNumberOfComponents();
  if (components > 1 && component == FieldSelection::kWholeArray) {
    throw Error(path + ": " + label + " has " + std::to_string(components) +
                " components per sample, but a scalar field (1 component) is needed: " +
                componentAdvice(a) + "; " + listArrays(data));
  }
  if (component >= components && !(components == 1 && component == 0)) {
    throw Error(path + ": --component " + std::to_string(component) + " is out of range: " + label +
                " has " + std::to_string(components) +
                (components == 1 ? " component"
                                 : " components (0.." + std::to_string(components - 1) + ")"));
  }
  out.component = components == 1 ? FieldSelection::kWholeArray : component;
  out.name = selectedFieldName(nameOf(a), components, out.component);
  return out;
}

template <typename Out>
std::vector<Out> selectedValues(const SelectedVtkField& field) {
  vtkDataArray* a = field.array;
  const vtkIdType n = a->GetNumberOfTuples();
  const int components = a->GetNumberOfComponents();
  std::vector<Out> out(static_cast<size_t>(n));
  if (components == 1 && a->HasStandardMemoryLayout()) {
    // The common case, a plain scalar array: a typed copy rather than a virtual call per value.
    switch (a->GetDataType()) {
      vtkTemplateMacro(
          copyValues(static_cast<const VTK_TT*>(a->GetVoidPointer(0)), out.size(), out.data()));
      default:
        break;
    }
    if (vtkSampleTypeName(a).size()) return out;
  }
  if (field.component == FieldSelection::kMagnitude) {
    for (vtkIdType i = 0; i < n; ++i) {
      double sum = 0.0;
      for (int c = 0; c < components; ++c) {
        const double v = a->GetComponent(i, c);
        sum += v * v;
      }
      out[static_cast<size_t>(i)] = static_cast<Out>(std::sqrt(sum));
    }
  } else {
    const int c = field.component == FieldSelection::kWholeArray ? 0 : field.component;
    for (vtkIdType i = 0; i < n; ++i)
      out[static_cast<size_t>(i)] = static_cast<Out>(a->GetComponent(i, c));
  }
  return out;
}

template std::vector<float> selectedValues<float>(const SelectedVtkField&);
template std::vector<double> selectedValues<double>(const SelectedVtkField&);

}  // namespace mfadvr
