#include "io/StreamedVolumeReader.h"

#include <vtkDataObject.h>
#include <vtkDataSetAttributes.h>
#include <vtkInformation.h>
#include <vtkMetaImageReader.h>
#include <vtkNIFTIImageHeader.h>
#include <vtkNIFTIImageReader.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStructuredPointsReader.h>

#include <cmath>
#include <filesystem>
#include <optional>

#include "core/analytic/BuiltinFunction.h"
#include "core/grid/SampleRange.h"
#include "core/util/Error.h"
#include "io/DeclaredSizeCheck.h"
#include "io/InflatedPayload.h"
#include "io/InputFile.h"
#include "io/NiftiPlacement.h"
#include "io/NrrdVolumeReader.h"
#include "io/RawVolumeReader.h"
#include "io/VtkSupport.h"

namespace mfadvr {
namespace {

// The grid VTK's reader would produce, from its header-only pass (RequestInformation): dims,
// spacing and origin of the first sample; nullopt when the image is not one a RawVolumeSource
// can stand for (rotated axes, several components, dims that differ from the payload's).
std::optional<StructuredGrid> layoutFromHeader(vtkAlgorithm& reader, const DeclaredPayload& payload,
                                               size_t axes) {
  VtkMessageCapture capture;
  reader.UpdateInformation();
  if (capture.hasErrors()) return std::nullopt;
  vtkInformation* info = reader.GetOutputInformation(0);
  if (!info || !info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT())) return std::nullopt;
  int extent[6];
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  double spacing[3] = {1, 1, 1}, origin[3] = {0, 0, 0};
  if (info->Has(vtkDataObject::SPACING())) info->Get(vtkDataObject::SPACING(), spacing);
  if (info->Has(vtkDataObject::ORIGIN())) info->Get(vtkDataObject::ORIGIN(), origin);
  if (info->Has(vtkDataObject::DIRECTION())) {
    double d[9];
    info->Get(vtkDataObject::DIRECTION(), d);
    for (int i = 0; i < 9; ++i)
      if (d[i] != (i % 4 == 0 ? 1.0 : 0.0)) return std::nullopt;
  }
  if (vtkInformation* scalars = vtkDataObject::GetActiveFieldInformation(
          info, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
      scalars && scalars->Has(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS()) &&
      scalars->Get(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS()) != 1)
    return std::nullopt;
  if (payload.sizes.size() < 3 || payload.sizes.size() > axes) return std::nullopt;
  StructuredGrid grid;
  for (int a = 0; a < 3; ++a) {
    grid.dims[a] = extent[2 * a + 1] - extent[2 * a] + 1;
    if (grid.dims[a] < 2 || grid.dims[a] != payload.sizes[static_cast<size_t>(a)])
      return std::nullopt;
    grid.spacing[a] = spacing[a];
    // VTK's origin is the position of index 0, which need not be the first sample.
    grid.origin[a] = origin[a] + extent[2 * a] * spacing[a];
  }
  grid.fieldAssociation = "point data";
  return grid;
}

// A NIfTI placement that keeps the stored sample order: the header's matrix applied to a 2^3
// grid of distinct values leaves them in place. Origin, spacing and notes carry over to the
// whole grid (they do not depend on its size when nothing is flipped).
bool placeUnreordered(vtkNIFTIImageReader& reader, StructuredGrid& layout) {
  StructuredGrid probe;
  probe.dims = {2, 2, 2};
  probe.origin = layout.origin;
  probe.spacing = layout.spacing;
  probe.values = {0, 1, 2, 3, 4, 5, 6, 7};
  const std::vector<float> stored = probe.values;
  placeNiftiGrid(reader, probe);
  if (probe.dims != Index3{2, 2, 2} || probe.values != stored) return false;
  layout.origin = probe.origin;
  layout.spacing = probe.spacing;
  layout.notes.insert(layout.notes.end(), probe.notes.begin(), probe.notes.end());
  return true;
}

// A header format's file whose samples can be streamed: the grid and where its samples lie.
struct HeaderVolume {
  StructuredGrid layout;     // dims, placement, names, notes; no values
  RawSampleLayout file;      // for gzip samples: offset counted in the inflated stream
  std::int64_t gzipAt = -1;  // where the gzip stream starts in file.path, or -1
  // The volumes stored one after another (time steps), this one the first, and their times.
  std::int64_t steps = 1;
  double timeStart = 0.0, timeStep = 1.0;
  std::string timeNote;
};

// The checks every streamed read starts with; false for inputs that are never streamed.
bool mayStream(const std::string& path, const VolumeLoadOptions& options) {
  if (options.field.chosen() || isBuiltinSpec(path)) return false;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return false;
  requireReadableFile(path, "a volume file or a directory of DICOM slices");
  return true;
}

// NRRD, MetaImage, NIfTI or legacy structured points, read up to its samples; nullopt when its
// samples cannot be streamed or the format is none of these.
std::optional<HeaderVolume> readHeaderVolume(const std::string& path, bool timeSeries = false) {
  const std::string ext = lowerExtension(path);
  requireNonEmptyFile(path, "a volume file or a directory of DICOM slices");
  DeclaredPayload payload;
  vtkSmartPointer<vtkAlgorithm> reader;
  size_t axes = 3;        // the payload's axes VTK reads as one volume
  std::string arrayName;  // the name VTK's reader gives the samples (tested)
  if (ext == ".nrrd" || ext == ".nhdr") {
    // Read by mfadvr alone (NrrdVolumeReader.h): the header gives the whole layout.
    NrrdVolume nrrd = describeNrrdVolume(path, timeSeries);
    if (nrrd.payload.file.empty()) return std::nullopt;  // ascii values
    HeaderVolume volume;
    volume.layout = std::move(nrrd.layout);
    volume.file = {nrrd.payload.file, nrrd.payload.offset, nrrd.payload.dtype,
                   nrrd.payload.bigEndian};
    volume.gzipAt = nrrd.payload.gzipAt;
    volume.steps = nrrd.timeSteps;
    volume.timeStart = nrrd.timeStart;
    volume.timeStep = nrrd.timeStep;
    return volume;
  }
  if (ext == ".mha" || ext == ".mhd") {
    payload = checkMetaImageDeclaredSize(path);
    arrayName = "MetaImage";
    auto r = vtkSmartPointer<vtkMetaImageReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  } else if (isNiftiPath(path)) {
    payload = checkNiftiDeclaredSize(path);
    arrayName = "NIFTI";
    auto r = vtkSmartPointer<vtkNIFTIImageReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
    axes = 7;  // time points and more: the first volume comes first
  } else if (ext == ".vtk") {
    payload = checkLegacyVtkDeclaredSize(path);
    auto r = vtkSmartPointer<vtkStructuredPointsReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  if (!reader || payload.file.empty() || payload.components != 1) return std::nullopt;
  std::optional<StructuredGrid> layout = layoutFromHeader(*reader, payload, axes);
  if (!layout) return std::nullopt;
  // VTK decodes %xx escapes in legacy names; such names are left to the in-memory read.
  if (payload.arrayName.find('%') != std::string::npos) return std::nullopt;
  layout->fieldName = payload.arrayName.empty() ? arrayName : payload.arrayName;
  HeaderVolume volume;
  volume.layout = *layout;
  volume.file = {payload.file, payload.offset, payload.dtype, payload.bigEndian};
  volume.gzipAt = payload.gzipAt;
  if (auto* nifti = vtkNIFTIImageReader::SafeDownCast(reader)) {
    // VTK's reader flips the slice order of a left-handed qform (qfac -1) while reading.
    if (nifti->GetQFac() < 0) return std::nullopt;
    if (const auto calibration = niftiCalibration(*nifti)) {
      volume.file.scale = calibration->slope;
      volume.file.shift = calibration->intercept;
      volume.layout.notes.push_back(calibration->note);
    }
    if (!placeUnreordered(*nifti, volume.layout)) return std::nullopt;
    // dim[4]: time points, each a whole volume after the previous one.
    if (payload.sizes.size() >= 4) {
      volume.steps = payload.sizes[3];
      vtkNIFTIImageHeader* header = nifti->GetNIFTIHeader();
      const double step = nifti->GetTimeSpacing();
      volume.timeStep = std::isfinite(step) && step > 0.0 ? step : 1.0;
      const double offset = header ? header->GetTOffset() : 0.0;
      volume.timeStart = std::isfinite(offset) ? offset : 0.0;
      static const std::pair<int, const char*> kUnits[] = {{8, "s"},   {16, "ms"},  {24, "us"},
                                                           {32, "Hz"}, {40, "ppm"}, {48, "rad/s"}};
      const int unit = header ? (header->GetXYZTUnits() & 0x38) : 0;
      for (const auto& [code, name] : kUnits)
        if (code == unit) volume.timeNote = std::string("times in ") + name + " (xyzt_units)";
      if (!(std::isfinite(step) && step > 0.0))
        volume.timeNote += std::string(volume.timeNote.empty() ? "" : "; ") +
                           "pixdim[4] gives no time step: steps 1 apart";
    }
  }
  volume.layout.source = path;
  volume.layout.sampleType = payload.dtype;  // as the source opened on the samples says
  volume.layout.inputBytes = volume.layout.sampleCount() * rawSampleSize(payload.dtype);
  return volume;
}

}  // namespace

std::optional<TimeStepsInFile> describeTimeStepsInFile(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".nrrd" && ext != ".nhdr" && !isNiftiPath(path)) return std::nullopt;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::optional<HeaderVolume> header = readHeaderVolume(path, true);
  if (!header) {
    // A NRRD of ascii values or a NIfTI image stored in another order than it is placed: read
    // as one volume only; a time series of them is refused with the reason.
    const DeclaredPayload nifti =
        isNiftiPath(path) ? checkNiftiDeclaredSize(path) : DeclaredPayload{};
    if (isNiftiPath(path) && nifti.sizes.size() >= 4 && nifti.sizes[3] > 1)
      throw Error("cannot read " + path + " as a time series of " + std::to_string(nifti.sizes[3]) +
                  " steps: its header places the samples in another order than they are stored "
                  "(flipped or rotated axes, several values per sample), which mfadvr reads as "
                  "one volume only; resample it to stored order first");
    if (!isNiftiPath(path) && describeNrrdVolume(path, true).timeSteps > 1)
      throw Error("cannot read " + path +
                  " as a time series: its values are ascii text; store them as raw or gzip");
    return std::nullopt;
  }
  if (header->steps < 2) return std::nullopt;
  TimeStepsInFile steps;
  steps.layout = std::move(header->layout);
  steps.file = std::move(header->file);
  steps.gzipAt = header->gzipAt;
  steps.stepBytes = steps.layout.sampleCount() * rawSampleSize(steps.file.dtype);
  for (std::int64_t s = 0; s < header->steps; ++s)
    steps.times.push_back(header->timeStart + header->timeStep * static_cast<double>(s));
  if (!header->timeNote.empty()) steps.layout.notes.push_back(header->timeNote);
  return steps;
}

std::unique_ptr<RawVolumeSource> GzipVolume::open(const InflateProgress& inflating) const {
  return openPlanes(0, layout.dims[2] - 1, inflating);
}

std::unique_ptr<RawVolumeSource> GzipVolume::openPlanes(std::int64_t z0, std::int64_t z1,
                                                        const InflateProgress& inflating) const {
  const SampleRange planes{{0, 0, z0}, {layout.dims[0] - 1, layout.dims[1] - 1, z1}};
  requireRangeInside(planes, layout.dims);
  const std::int64_t planeBytes = layout.dims[0] * layout.dims[1] * rawSampleSize(file.dtype);
  // Only these planes of the first volume (a NIfTI file may hold time points after it).
  const TemporaryFile inflated =
      inflateToTemporaryFile(file.path, gzipAt, file.offset + z0 * planeBytes,
                             (z1 - z0 + 1) * planeBytes, layout.source, inflating);
  RawSampleLayout plain = file;
  plain.path = inflated.path();
  plain.offset = 0;
  // Opened here: the inflated file stays readable once its name is removed at the end of this
  // scope.
  StructuredGrid part = subGridLayout(layout, planes);
  part.notes = layout.notes;
  return std::make_unique<RawVolumeSource>(plain, part);
}

std::optional<GzipVolume> describeGzipVolume(const std::string& path,
                                             const VolumeLoadOptions& options) {
  if (!mayStream(path, options) || lowerExtension(path) == ".raw") return std::nullopt;
  std::optional<HeaderVolume> header = readHeaderVolume(path);
  if (!header || header->gzipAt < 0) return std::nullopt;
  GzipVolume volume{std::move(header->layout), std::move(header->file), header->gzipAt};
  volume.layout.origin = options.origin.value_or(volume.layout.origin);
  volume.layout.spacing = options.spacing.value_or(volume.layout.spacing);
  return volume;
}

std::unique_ptr<RawVolumeSource> openStreamedVolume(const std::string& path,
                                                    const VolumeLoadOptions& options,
                                                    GzipPayloads gzip,
                                                    const InflateProgress& inflating) {
  if (!mayStream(path, options)) return nullptr;
  std::unique_ptr<RawVolumeSource> source;
  if (lowerExtension(path) == ".raw") {
    source = openRawVolume(path);
  } else {
    std::optional<HeaderVolume> header = readHeaderVolume(path);
    if (!header) return nullptr;
    if (header->gzipAt < 0) {
      source = std::make_unique<RawVolumeSource>(header->file, header->layout);
    } else if (gzip == GzipPayloads::kLeaveToVtk) {
      return nullptr;
    } else {
      source = GzipVolume{std::move(header->layout), std::move(header->file), header->gzipAt}.open(
          inflating);
    }
  }
  const StructuredGrid& layout = source->layout();
  source->setPlacement(options.origin.value_or(layout.origin),
                       options.spacing.value_or(layout.spacing));
  return source;
}

}  // namespace mfadvr
