#include "io/VolumeLoader.h"

#include <filesystem>

#include "core/analytic/BuiltinFunction.h"
#include "core/util/Error.h"
#include "io/InputFile.h"
#include "io/NetcdfVolumeReader.h"
#include "io/NrrdVolumeReader.h"
#include "io/RawVolumeReader.h"
#include "io/StreamedVolumeReader.h"
#include "io/VtkVolumeReader.h"

namespace mfadvr {
namespace {

StructuredGrid readFile(const std::string& path, const FieldSelection& field) {
  const std::string ext = lowerExtension(path);
  if (ext != ".raw") requireNonEmptyFile(path, "a volume file or a directory of DICOM slices");
  if (isNiftiPath(path)) return readVtkVolume(path, VtkVolumeFormat::kNifti, field);
  if (ext == ".dcm") {
    throw Error(path +
                ": a DICOM file holds one slice; pass the directory that holds the series' "
                "slices (and nothing else) to read them as a volume");
  }
  if (ext == ".raw") {
    if (field.chosen())
      throw Error(path + ": a raw file holds one unnamed scalar field on the grid points, so " +
                  (field.name.empty() ? std::string("--association and --component do")
                                      : "a field name ('" + field.name + "') does") +
                  " not apply to it");
    return readRawVolume(path);
  }
  if (ext == ".nrrd" || ext == ".nhdr") return readNrrdVolume(path, field);
  if (isNetcdfPath(path)) return readNetcdfVolume(path, field);
  if (ext == ".vti") return readVtkVolume(path, VtkVolumeFormat::kXmlImageData, field);
  if (ext == ".vtk") return readVtkVolume(path, VtkVolumeFormat::kLegacyStructuredPoints, field);
  if (ext == ".mha" || ext == ".mhd")
    return readVtkVolume(path, VtkVolumeFormat::kMetaImage, field);
  if (ext == ".vtu" || ext == ".vtp" || ext == ".vts" || ext == ".vtr") {
    throw Error(path + ": '" + ext +
                "' files hold VTK unstructured, polygonal, curvilinear or rectilinear grids, "
                "but this input needs samples on a regular grid; supported inputs:\n" +
                supportedVolumeFormats());
  }
  throw Error(path + ": unknown volume format '" +
              (ext.empty() ? std::string("(no extension)") : ext) + "'; supported inputs:\n" +
              supportedVolumeFormats());
}

}  // namespace

StructuredGrid loadStructuredVolume(const std::string& input, const VolumeLoadOptions& options) {
  if (isBuiltinSpec(input)) {
    // A built-in is defined on [-1,1]^3; moving its samples would detach it from its truth.
    if (options.spacing || options.origin || options.field.chosen())
      throw Error(input +
                  ": --spacing, --origin, --field, --association and --component apply to "
                  "files, not to built-in functions (choose the grid with builtin:NAME:NXxNYxNZ)");
    return sampleBuiltinSpec(input);
  }

  std::error_code ec;
  StructuredGrid grid;
  // Samples stored plainly in one file are read directly into float32, without VTK's copy in
  // the file's type; gzip data too, inflated once.
  if (auto streamed = openStreamedVolume(input, options, GzipPayloads::kInflateToTemporaryFile)) {
    grid = streamed->readUnchecked(wholeRange(streamed->layout().dims));
    grid.notes = streamed->layout().notes;
  } else if (std::filesystem::is_directory(input, ec)) {
    grid = readVtkVolume(input, VtkVolumeFormat::kDicomSeries, options.field);
  } else {
    requireReadableFile(input, "a volume file or a directory of DICOM slices");
    grid = readFile(input, options.field);
  }
  if (options.spacing) grid.spacing = *options.spacing;
  if (options.origin) grid.origin = *options.origin;
  grid.source = input;
  grid.validate();
  return grid;
}

std::string supportedVolumeFormats() {
  return "  NAME_XxYxZ_TYPE.raw  headerless raw, x fastest, little-endian; TYPE: uint8, int8,\n"
         "                       uint16, int16, uint32, int32, float32, float64\n"
         "                       (e.g. fuel_64x64x64_uint8.raw)\n"
         "  .nrrd, .nhdr         NRRD (raw, ascii or gzip encoding; 3 spatial axes, one scalar)\n"
         "  .vti                 VTK XML image data\n"
         "  .vtk                 legacy VTK, DATASET STRUCTURED_POINTS only\n"
         "  .mha, .mhd           MetaImage\n"
         "  .nii, .nii.gz        NIfTI-1/-2 (also Analyze .hdr + .img); sform/qform placement\n"
         "  .nc, .nc4, .cdf      NetCDF (classic, 64-bit offset, netCDF-4): a variable of 3\n"
         "                       dimensions (its first time step; encode: every step), CF\n"
         "                       coordinates place it\n"
         "  DIRECTORY            a DICOM series: uncompressed single-frame slices\n"
         "  builtin:NAME[:N|:NXxNYxNZ]  analytic field sampled on [-1,1]^3\n";
}

}  // namespace mfadvr
