#include "io/VtkVolumeReader.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include <vtkAlgorithm.h>
#include <vtkCellData.h>
#include <vtkDICOMImageReader.h>
#include <vtkDataArray.h>
#include <vtkDataObjectTypes.h>
#include <vtkDataSetReader.h>
#include <vtkErrorCode.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkMetaImageReader.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStructuredPoints.h>
#include <vtkStructuredPointsReader.h>
#include <vtkType.h>
#include <vtkXMLImageDataReader.h>

#include "core/grid/GridOrientation.h"
#include "core/util/Error.h"
#include "io/DeclaredSizeCheck.h"
#include "io/InputFile.h"
#include "io/NiftiPlacement.h"
#include "io/VtkDataConversion.h"
#include "io/VtkFieldSelection.h"
#include "io/VtkSupport.h"

namespace mfadvr {
namespace {

const char* formatName(VtkVolumeFormat format) {
  switch (format) {
    case VtkVolumeFormat::kXmlImageData:
      return "VTK XML image data (.vti)";
    case VtkVolumeFormat::kLegacyStructuredPoints:
      return "legacy VTK structured points";
    case VtkVolumeFormat::kMetaImage:
      return "MetaImage";
    case VtkVolumeFormat::kNifti:
      return "NIfTI";
    case VtkVolumeFormat::kDicomSeries:
      return "a DICOM series";
  }
  return "volume";
}

// What a readable file of each format looks like, for the end of a read error.
const char* formatExpectation(VtkVolumeFormat format) {
  switch (format) {
    case VtkVolumeFormat::kXmlImageData:
      return "a VTK XML file <VTKFile type=\"ImageData\"> with point data";
    case VtkVolumeFormat::kLegacyStructuredPoints:
      return "a legacy VTK file ('# vtk DataFile Version') with DATASET STRUCTURED_POINTS";
    case VtkVolumeFormat::kMetaImage:
      return "a MetaImage header (ObjectType = Image, NDims, DimSize, ElementType, "
             "ElementDataFile) and its data";
    case VtkVolumeFormat::kNifti:
      return "a NIfTI-1/-2 or Analyze 7.5 image (.nii, .nii.gz, or .hdr with its .img)";
    case VtkVolumeFormat::kDicomSeries:
      return "a directory of uncompressed single-frame DICOM slices of one series";
  }
  return "a volume file";
}

[[noreturn]] void throwReadFailure(const std::string& path, VtkVolumeFormat format,
                                   const VtkMessageCapture& capture, vtkAlgorithm* reader,
                                   const std::string& fallback) {
  std::string why = capture.errorText();
  if (why.empty() && reader && reader->GetErrorCode() != vtkErrorCode::NoError)
    why = "the reader failed (VTK error code " + std::to_string(reader->GetErrorCode()) + ")";
  if (why.empty()) why = fallback;
  throw Error("cannot read " + path + " as " + formatName(format) + ": " + why + " (expected " +
              formatExpectation(format) + ")");
}

// Whether a legacy file's first keyword after ASCII/BINARY is FIELD (a vtkDataObject).
bool legacyHoldsFieldDataOnly(const std::string& path) {
  const auto words = legacyVtkHeaderWords(path, 2);
  return words.size() == 2 && words[1] == "FIELD";
}

// Legacy files name their dataset type in the header; say which one it is instead of VTK's
// "Cannot read dataset type".
void requireStructuredPoints(const std::string& path, const VtkMessageCapture& capture) {
  vtkNew<vtkDataSetReader> probe;
  probe->SetFileName(path.c_str());
  const int type = probe->ReadOutputType();
  if (type < 0 && legacyHoldsFieldDataOnly(path)) {
    throw Error(path +
                ": the legacy VTK file holds field data only (FIELD, no DATASET), not a data "
                "set: there are no points or grid to encode");
  }
  if (type < 0) {
    throwReadFailure(path, VtkVolumeFormat::kLegacyStructuredPoints, capture, nullptr,
                     "not a legacy VTK data file (expected a '# vtk DataFile Version' header)");
  }
  if (type != VTK_STRUCTURED_POINTS && type != VTK_IMAGE_DATA) {
    const char* found = vtkDataObjectTypes::GetClassNameFromTypeId(type);
    throw Error(path +
                ": this input needs a regular grid, i.e. a legacy VTK file with DATASET "
                "STRUCTURED_POINTS, but the file holds a " +
                std::string(found ? found : "dataset of unknown type") +
                "; resample it onto a regular grid first (e.g. vtkResampleToImage in ParaView)");
  }
}

vtkSmartPointer<vtkImageData> runReader(const std::string& path, VtkVolumeFormat format,
                                        const VtkMessageCapture& capture,
                                        vtkSmartPointer<vtkAlgorithm>& reader) {
  int dicomFiles = 0;
  switch (format) {
    case VtkVolumeFormat::kXmlImageData: {
      checkXmlVtkDeclaredSize(path);
      auto r = vtkSmartPointer<vtkXMLImageDataReader>::New();
      r->SetFileName(path.c_str());
      reader = r;
      break;
    }
    case VtkVolumeFormat::kLegacyStructuredPoints: {
      requireStructuredPoints(path, capture);
      checkLegacyVtkDeclaredSize(path);
      auto r = vtkSmartPointer<vtkStructuredPointsReader>::New();
      r->SetFileName(path.c_str());
      readAllLegacyArrays(r);
      reader = r;
      break;
    }
    case VtkVolumeFormat::kMetaImage: {
      // Also refuses a missing data file, on which MetaIO leaks and says little.
      checkMetaImageDeclaredSize(path);
      auto r = vtkSmartPointer<vtkMetaImageReader>::New();
      r->SetFileName(path.c_str());
      reader = r;
      break;
    }
    case VtkVolumeFormat::kNifti: {
      checkNiftiDeclaredSize(path);
      auto r = vtkSmartPointer<vtkNIFTIImageReader>::New();
      r->SetFileName(path.c_str());
      reader = r;
      break;
    }
    case VtkVolumeFormat::kDicomSeries: {
      dicomFiles = checkDicomSeries(path);
      auto r = vtkSmartPointer<vtkDICOMImageReader>::New();
      r->SetDirectoryName(path.c_str());
      reader = r;
      break;
    }
  }
  reader->Update();
  auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  if (capture.hasErrors() || reader->GetErrorCode() != vtkErrorCode::NoError || !image)
    throwReadFailure(path, format, capture, reader, "the reader produced no image");
  if (image->GetNumberOfPoints() == 0)
    throwReadFailure(path, format, capture, reader, "the file holds no samples");
  // VTK's DICOM reader leaves out files it cannot parse, without a word.
  if (format == VtkVolumeFormat::kDicomSeries && image->GetDimensions()[2] != dicomFiles) {
    throw Error("cannot read " + path + " as a DICOM series: it holds " +
                std::to_string(dicomFiles) + " DICOM files, but VTK's reader assembled " +
                std::to_string(image->GetDimensions()[2]) +
                " slices from them (files it cannot parse are left out)");
  }
  return image;
}

std::string axesText(const Index3& dims) {
  return std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
         std::to_string(dims[2]);
}

// A view of a plain scalar array where it is (one component, contiguous, a numeric type), or
// an empty view.
GridSamples viewOf(vtkDataArray* a, const Index3& dims) {
  if (a->GetNumberOfComponents() != 1 || !a->HasStandardMemoryLayout() ||
      vtkSampleTypeName(a).empty())
    return {};
  switch (a->GetDataType()) {
    vtkTemplateMacro(
        return GridSamples::of(static_cast<const VTK_TT*>(a->GetVoidPointer(0)), dims));
    default:
      return {};
  }
}

// With `inPlace`, a plain scalar array is not copied: *inPlace views it and grid.values stays
// empty (a copy is made, and *inPlace left empty, for components and magnitudes).
StructuredGrid toGrid(const std::string& path, vtkImageData* image, const FieldSelection& field,
                      GridSamples* inPlace = nullptr) {
  if (vtkMatrix3x3* direction = image->GetDirectionMatrix(); direction && !direction->IsIdentity())
    throw Error(path +
                ": the grid axes are rotated or flipped (direction matrix is not the "
                "identity); only axis-aligned grids are supported");
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2) {
    throw Error(path + ": the image spans " + axesText({dims[0], dims[1], dims[2]}) +
                " points: 2-D data (a volume needs at least 2 samples along every axis)");
  }
  const SelectedVtkField selected = selectVtkField(path, image, field);
  vtkDataArray* array = selected.array;

  StructuredGrid grid;
  int extent[6];
  double origin[3];
  double spacing[3];
  image->GetExtent(extent);
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  for (int a = 0; a < 3; ++a) {
    // VTK's origin is the position of index 0, which need not be the first sample.
    grid.origin[a] = origin[a] + extent[2 * a] * spacing[a];
    grid.spacing[a] = spacing[a];
    grid.dims[a] = dims[a];
    // Cell data: one sample at the centre of each cell (an axis of one point has one cell).
    if (selected.fromCells && dims[a] > 1) {
      grid.dims[a] = dims[a] - 1;
      grid.origin[a] += 0.5 * spacing[a];
    }
  }
  const char* association = selected.fromCells ? "cell data" : "point data";
  if (grid.dims[0] < 2 || grid.dims[1] < 2 || grid.dims[2] < 2) {
    throw Error(path + ": the " + association + " of '" + selected.name + "' spans " +
                axesText(grid.dims) +
                " samples: 2-D data (a volume needs at least 2 samples along every axis)");
  }
  if (array->GetNumberOfTuples() != grid.sampleCount()) {
    throw Error(path + ": array '" + std::string(array->GetName() ? array->GetName() : "") +
                "' has " + std::to_string(array->GetNumberOfTuples()) + " values for " +
                std::to_string(grid.sampleCount()) + (selected.fromCells ? " cells" : " points"));
  }
  grid.source = path;
  grid.fieldName = selected.name;
  grid.fieldAssociation = association;
  if (selected.fromCells)
    grid.notes.push_back("'" + selected.name +
                         "' is cell data: encoded with one sample at each "
                         "cell centre (a " +
                         axesText(grid.dims) +
                         " grid, half a cell inside "
                         "the image's bounds)");
  grid.sampleType = vtkSampleTypeName(array);
  grid.inputBytes =
      grid.sampleCount() * array->GetDataTypeSize() *
      (selected.component == FieldSelection::kWholeArray ? 1 : array->GetNumberOfComponents());
  // VTK's point and cell order is x fastest, like StructuredGrid's.
  if (inPlace) {
    *inPlace = viewOf(array, grid.dims);
    if (!inPlace->empty()) return grid;
  }
  grid.values = selectedValues<float>(selected);
  return grid;
}

// VTK's DICOM reader gives no placement in patient coordinates: say what the grid is. It also
// takes Pixel Spacing's first value (the distance between rows) for x; DICOM defines the pair
// as (row spacing, column spacing), so x, along a row, gets the second.
void fixDicomSeries(StructuredGrid& grid) {
  std::swap(grid.spacing[0], grid.spacing[1]);
  grid.notes.push_back(
      "DICOM series of " + std::to_string(grid.dims[2]) +
      " slices: the volume is in voxel axes (x along the rows, y from the image's last row "
      "up, z from the slice farthest along the slice normal back), spaced by Pixel Spacing "
      "and the slice distance, first voxel at the origin; the patient position and "
      "orientation are not applied");
}

}  // namespace

StructuredGrid readVtkVolume(const std::string& path, VtkVolumeFormat format,
                             const FieldSelection& field) {
  vtkSmartPointer<vtkImageData> image;
  vtkSmartPointer<vtkAlgorithm> reader;
  {
    VtkMessageCapture capture;
    image = runReader(path, format, capture, reader);
  }
  StructuredGrid grid = toGrid(path, image, field);
  if (auto* nifti = vtkNIFTIImageReader::SafeDownCast(reader)) applyNiftiHeader(*nifti, grid);
  if (format == VtkVolumeFormat::kDicomSeries) fixDicomSeries(grid);
  return grid;
}

StructuredGrid gridFromVtkImage(vtkImageData* image, const std::string& field,
                                const std::string& source, GridSamples* inPlace) {
  if (inPlace) *inPlace = GridSamples();
  if (!image || image->GetNumberOfPoints() == 0)
    throw Error(source + ": the image data holds no samples");
  FieldSelection selection;
  selection.name = field;
  StructuredGrid grid = toGrid(source, image, selection, inPlace);
  grid.source = source;
  return grid;
}

}  // namespace mfadvr
