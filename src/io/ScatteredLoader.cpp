#include "io/ScatteredLoader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <sstream>
#include <vector>

#include <vtkAlgorithm.h>
#include <vtkCellData.h>
#include <vtkCellDataToPointData.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkDataSetReader.h>
#include <vtkDataSetTriangleFilter.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>
#include <vtkStructuredGrid.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLRectilinearGridReader.h>
#include <vtkXMLStructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "core/util/Error.h"
#include "core/util/PointList.h"
#include "io/DeclaredSizeCheck.h"
#include "io/InputFile.h"
#include "io/VtkDataConversion.h"
#include "io/VtkFieldSelection.h"
#include "io/VtkSupport.h"

namespace mfadvr {
namespace {

bool isTextExtension(const std::string& ext) {
  return ext == ".csv" || ext == ".txt" || ext == ".xyz";
}

// The dataset type a legacy VTK file names on its DATASET line ("UNSTRUCTURED_GRID", ...), in
// upper case; "" when the file does not start like a legacy VTK data file. Only the header is
// read: version line, title line, ASCII|BINARY, DATASET TYPE.
std::string legacyDatasetType(const std::string& path) {
  const auto words = legacyVtkHeaderWords(path);
  return words.size() == 3 && words[1] == "DATASET" ? words[2] : "";
}

bool isScatteredLegacyType(const std::string& type) {
  return type == "UNSTRUCTURED_GRID" || type == "STRUCTURED_GRID" || type == "POLYDATA" ||
         type == "RECTILINEAR_GRID";
}

struct MeshFormat {
  const char* name;         // for "cannot read PATH as NAME"
  const char* expectation;  // what a readable file looks like
};

MeshFormat meshFormat(const std::string& ext) {
  if (ext == ".vtu")
    return {"VTK XML unstructured grid (.vtu)",
            "a VTK XML file <VTKFile type=\"UnstructuredGrid\"> with points, cells and data"};
  if (ext == ".vts")
    return {"VTK XML structured grid (.vts)",
            "a VTK XML file <VTKFile type=\"StructuredGrid\"> with points and data"};
  if (ext == ".vtp")
    return {"VTK XML polydata (.vtp)",
            "a VTK XML file <VTKFile type=\"PolyData\"> with points and data"};
  if (ext == ".vtr")
    return {"VTK XML rectilinear grid (.vtr)",
            "a VTK XML file <VTKFile type=\"RectilinearGrid\"> with coordinates and data"};
  return {"legacy VTK",
          "a legacy VTK file ('# vtk DataFile Version') with DATASET UNSTRUCTURED_GRID, "
          "STRUCTURED_GRID, RECTILINEAR_GRID or POLYDATA"};
}

// Runs the reader for `ext` and returns its dataset, with VTK's messages in the error.
vtkSmartPointer<vtkDataSet> readMesh(const std::string& path, const std::string& ext) {
  const MeshFormat format = meshFormat(ext);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == ".vtu" || ext == ".vts" || ext == ".vtp" || ext == ".vtr")
    checkXmlVtkDeclaredSize(path);
  else
    checkLegacyVtkDeclaredSize(path);
  if (ext == ".vtu") {
    auto r = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  } else if (ext == ".vts") {
    auto r = vtkSmartPointer<vtkXMLStructuredGridReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  } else if (ext == ".vtp") {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  } else if (ext == ".vtr") {
    auto r = vtkSmartPointer<vtkXMLRectilinearGridReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  } else {
    const std::string type = legacyDatasetType(path);
    if (type.empty()) {
      throw Error("cannot read " + path + " as " + format.name +
                  ": not a legacy VTK data file (expected " + format.expectation + ")");
    }
    if (type == "STRUCTURED_POINTS") {
      throw Error(path +
                  ": the file holds a regular grid (DATASET STRUCTURED_POINTS), which is read "
                  "as a volume, not as scattered points");
    }
    if (!isScatteredLegacyType(type)) {
      throw Error(path + ": DATASET " + type +
                  " is not supported for scattered input; expected UNSTRUCTURED_GRID, "
                  "STRUCTURED_GRID, RECTILINEAR_GRID or POLYDATA");
    }
    auto r = vtkSmartPointer<vtkDataSetReader>::New();
    r->SetFileName(path.c_str());
    readAllLegacyArrays(r);
    reader = r;
  }

  vtkSmartPointer<vtkDataSet> data;
  {
    VtkMessageCapture capture;
    reader->Update();
    data = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
    if (capture.hasErrors() || reader->GetErrorCode() != vtkErrorCode::NoError || !data) {
      std::string why = capture.errorText();
      if (why.empty() && reader->GetErrorCode() != vtkErrorCode::NoError)
        why = "the reader failed (VTK error code " + std::to_string(reader->GetErrorCode()) + ")";
      if (why.empty()) why = "the reader produced no dataset";
      throw Error("cannot read " + path + " as " + format.name + ": " + why + " (expected " +
                  format.expectation + ")");
    }
  }
  return data;
}

// Dimension (0..3) of every cell type in `data`, indexed by VTK cell type.
std::array<int, 256> cellDimensions(vtkDataSet* data) {
  std::array<int, 256> dims{};
  vtkNew<vtkCellTypes> types;
  data->GetCellTypes(types);
  vtkNew<vtkGenericCell> cell;
  for (vtkIdType i = 0; i < types->GetNumberOfTypes(); ++i) {
    const unsigned char type = types->GetCellType(static_cast<int>(i));
    cell->SetCellType(type);
    dims[type] = cell->GetCellDimension();
  }
  return dims;
}

// Whether a 3-D cell of VTK type `type` can have n points. VTK's readers take a cell's type and
// its point list from separate arrays without checking that they agree, and its filters
// (vtkDataSetTriangleFilter) then read past the list or crash (found by fuzzing: a Lagrange
// tetrahedron of 1 point). Higher-order (Lagrange, Bezier) cells have the point counts of their
// order, the same along every axis unless a "HigherOrderDegrees" cell array says otherwise.
bool pointCountFits(int type, vtkIdType n, bool anisotropicOrders) {
  auto someOrder = [&](auto count) {
    for (vtkIdType k = 1; k <= 64; ++k)
      if (count(k) == n) return true;
    return false;
  };
  switch (type) {
    case VTK_TETRA:
      return n == 4;
    case VTK_VOXEL:
    case VTK_HEXAHEDRON:
      return n == 8;
    case VTK_WEDGE:
      return n == 6;
    case VTK_PYRAMID:
      return n == 5;
    case VTK_PENTAGONAL_PRISM:
      return n == 10;
    case VTK_HEXAGONAL_PRISM:
      return n == 12;
    case VTK_QUADRATIC_TETRA:
      return n == 10;
    case VTK_QUADRATIC_HEXAHEDRON:
      return n == 20;
    case VTK_QUADRATIC_WEDGE:
      return n == 15;
    case VTK_QUADRATIC_PYRAMID:
      return n == 13;
    case VTK_TRIQUADRATIC_PYRAMID:
      return n == 19;
    case VTK_TRIQUADRATIC_HEXAHEDRON:
      return n == 27;
    case VTK_QUADRATIC_LINEAR_WEDGE:
      return n == 12;
    case VTK_BIQUADRATIC_QUADRATIC_WEDGE:
      return n == 18;
    case VTK_BIQUADRATIC_QUADRATIC_HEXAHEDRON:
      return n == 24;
    case VTK_LAGRANGE_TETRAHEDRON:
    case VTK_BEZIER_TETRAHEDRON:
      return someOrder([](vtkIdType k) { return (k + 1) * (k + 2) * (k + 3) / 6; });
    case VTK_LAGRANGE_HEXAHEDRON:
    case VTK_BEZIER_HEXAHEDRON:
      return anisotropicOrders ? n >= 8
                               : someOrder([](vtkIdType k) { return (k + 1) * (k + 1) * (k + 1); });
    case VTK_LAGRANGE_WEDGE:
    case VTK_BEZIER_WEDGE:
      return anisotropicOrders
                 ? n >= 6
                 : someOrder([](vtkIdType k) { return (k + 1) * (k + 1) * (k + 2) / 2; });
    default:
      return n >= 4;  // polyhedra, convex point sets and newer types: at least a tetrahedron
  }
}

// Every tetrahedron has its 4 points (pointCountFits, checked before).
void appendTets(vtkDataSet* data, std::vector<Tetrahedron>& tets) {
  vtkNew<vtkIdList> ids;
  const vtkIdType cells = data->GetNumberOfCells();
  tets.reserve(tets.size() + static_cast<size_t>(cells));
  for (vtkIdType c = 0; c < cells; ++c) {
    if (data->GetCellType(c) != VTK_TETRA) continue;
    data->GetCellPoints(c, ids);
    tets.push_back({ids->GetId(0), ids->GetId(1), ids->GetId(2), ids->GetId(3)});
  }
}

ScatteredData meshDataOf(vtkDataSet* input, const std::string& path, const FieldSelection& field) {
  if (!input || input->GetNumberOfPoints() == 0)
    throw Error(path + ": the data set holds no points");

  ScatteredData out;
  const SelectedVtkField selected = selectVtkField(path, input, field);
  out.fieldName = selected.name;
  out.sampleType = vtkSampleTypeName(selected.array);
  out.inputBytes =
      static_cast<std::int64_t>(selected.array->GetNumberOfTuples()) *
      selected.array->GetDataTypeSize() *
      (selected.component == FieldSelection::kWholeArray ? 1
                                                         : selected.array->GetNumberOfComponents());

  // The selected values as a one-component array of their own, on a shallow copy of the input
  // (a chosen component or magnitude becomes a scalar before any averaging).
  vtkNew<vtkDoubleArray> scalar;
  scalar->SetName(out.fieldName.c_str());
  {
    const std::vector<double> values = selectedValues<double>(selected);
    scalar->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
    std::copy(values.begin(), values.end(), scalar->GetPointer(0));
  }
  vtkSmartPointer<vtkDataSet> carrier;
  carrier.TakeReference(input->NewInstance());
  carrier->ShallowCopy(input);
  carrier->GetPointData()->Initialize();
  carrier->GetCellData()->Initialize();
  (selected.fromCells ? static_cast<vtkDataSetAttributes*>(carrier->GetCellData())
                      : static_cast<vtkDataSetAttributes*>(carrier->GetPointData()))
      ->AddArray(scalar);

  // The filters below report through VTK's output window too.
  VtkMessageCapture capture;
  vtkSmartPointer<vtkDataSet> data = carrier;
  if (selected.fromCells) {
    vtkNew<vtkCellDataToPointData> toPoints;
    toPoints->SetInputData(carrier);
    toPoints->ProcessAllArraysOff();
    toPoints->AddCellDataArray(out.fieldName.c_str());
    toPoints->PassCellDataOff();
    toPoints->Update();
    data = toPoints->GetOutput();
    out.fieldAssociation = "cell data averaged to points";
  } else {
    out.fieldAssociation = "point data";
  }

  // Count the 3-D cells; 2-D, 1-D and vertex cells do not enclose a volume and are ignored.
  std::int64_t volumeCells = 0;
  bool allTets = true;
  if (!vtkPolyData::SafeDownCast(data)) {
    const auto dims = cellDimensions(data);
    const bool anisotropicOrders = data->GetCellData()->HasArray("HigherOrderDegrees") != 0;
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < data->GetNumberOfCells(); ++c) {
      const int type = data->GetCellType(c);
      if (dims[type] != 3) continue;
      data->GetCellPoints(c, ids);
      if (!pointCountFits(type, ids->GetNumberOfIds(), anisotropicOrders))
        throw Error(path + ": cell " + std::to_string(c) + " (VTK cell type " +
                    std::to_string(type) + ") has " + std::to_string(ids->GetNumberOfIds()) +
                    " points, which no cell of its type has");
      ++volumeCells;
      allTets = allTets && type == VTK_TETRA;
    }
  }
  out.inputCells = volumeCells;

  if (volumeCells == 0) {
    out.kind = "point cloud";
  } else if (allTets && !vtkStructuredGrid::SafeDownCast(data) &&
             !vtkRectilinearGrid::SafeDownCast(data)) {
    out.kind = "tetrahedral mesh";
    appendTets(data, out.tets);
  } else {
    out.kind = vtkStructuredGrid::SafeDownCast(data)    ? "curvilinear grid"
               : vtkRectilinearGrid::SafeDownCast(data) ? "rectilinear grid"
                                                        : "mixed-cell mesh";
    // Splits every 3-D cell into tetrahedra on the cell's own points; the points and their
    // data pass through.
    vtkNew<vtkDataSetTriangleFilter> split;
    split->SetInputData(data);
    split->TetrahedraOnlyOn();
    split->Update();
    data = split->GetOutput();
    appendTets(data, out.tets);
  }
  if (capture.hasErrors())
    throw Error("cannot prepare the cells of " + path + ": " + capture.errorText());

  vtkDataArray* values = data->GetPointData()->GetArray(out.fieldName.c_str());
  if (!values || values->GetNumberOfTuples() != data->GetNumberOfPoints())
    throw Error(path + ": array '" + out.fieldName + "' has no value for every point");
  const vtkIdType n = data->GetNumberOfPoints();
  out.points.resize(static_cast<size_t>(n));
  out.values.resize(static_cast<size_t>(n));
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    data->GetPoint(i, p);
    out.points[static_cast<size_t>(i)] = Vec3d(p[0], p[1], p[2]);
    out.values[static_cast<size_t>(i)] = values->GetComponent(i, 0);
  }
  return out;
}

ScatteredData readMeshData(const std::string& path, const std::string& ext,
                           const FieldSelection& field) {
  vtkSmartPointer<vtkDataSet> input = readMesh(path, ext);
  if (input->GetNumberOfPoints() == 0) throw Error(path + ": the file holds no points");
  return meshDataOf(input, path, field);
}

ScatteredData readTextData(const std::string& path, const FieldSelection& field) {
  ScatteredData out = parsePointValueList(readTextFile(path), path);
  if (!field.name.empty() && field.name != out.fieldName) {
    throw Error(path + ": no value column named '" + field.name +
                "'; the file's value column is '" + out.fieldName +
                "' (the fourth name of a header line; 'value' when there is no header)");
  }
  if (field.association == FieldAssociation::kCells || field.component > 0)
    throw Error(path + ": a point list holds one value per point, so --association cell and " +
                "--component do not apply to it");
  return out;
}

}  // namespace

ScatteredData loadScatteredData(const std::string& path, const ScatteredLoadOptions& options) {
  const std::string ext = lowerExtension(path);
  const bool known = isTextExtension(ext) || ext == ".vtu" || ext == ".vts" || ext == ".vtp" ||
                     ext == ".vtr" || ext == ".vtk";
  if (!known) {
    throw Error(path + ": unknown mesh or point format '" +
                (ext.empty() ? std::string("(no extension)") : ext) + "'; supported inputs:\n" +
                supportedScatteredFormats());
  }
  requireReadableFile(path, "a mesh or point file");
  requireNonEmptyFile(path, "a mesh or point file");
  ScatteredData data = isTextExtension(ext) ? readTextData(path, options.field)
                                            : readMeshData(path, ext, options.field);
  data.source = path;
  data.validate();
  return data;
}

ScatteredData scatteredFromVtkDataSet(vtkDataSet* data, const std::string& field,
                                      const std::string& source) {
  FieldSelection selection;
  selection.name = field;
  ScatteredData out = meshDataOf(data, source, selection);
  out.source = source;
  out.validate();
  return out;
}

bool isScatteredInput(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (isTextExtension(ext) || ext == ".vtu" || ext == ".vts" || ext == ".vtp" || ext == ".vtr")
    return true;
  return ext == ".vtk" && isScatteredLegacyType(legacyDatasetType(path));
}

std::string supportedScatteredFormats() {
  return "  .vtu                 VTK XML unstructured grid (3-D cells split into tetrahedra)\n"
         "  .vts                 VTK XML structured (curvilinear) grid\n"
         "  .vtr                 VTK XML rectilinear grid (cells split into tetrahedra)\n"
         "  .vtp                 VTK XML polydata (the points; polygons and lines are ignored)\n"
         "  .vtk                 legacy VTK, DATASET UNSTRUCTURED_GRID, STRUCTURED_GRID,\n"
         "                       RECTILINEAR_GRID or POLYDATA\n"
         "  .csv, .txt, .xyz     text, one 'x y z value' per line (commas and/or spaces,\n"
         "                       optional header line naming the columns, # comments)\n";
}

}  // namespace mfadvr
