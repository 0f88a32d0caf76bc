#include "io/NrrdVolumeReader.h"

#include "core/grid/SampleRange.h"
#include "core/util/Error.h"
#include "io/RawVolumeReader.h"
#include "io/StreamedVolumeReader.h"

namespace mfadvr {

NrrdVolume describeNrrdVolume(const std::string& path, bool timeSeries) {
  NrrdFile file = checkNrrdDeclaredSize(path);
  if (file.grid.timeSteps > 1 && !timeSeries)
    throw Error("cannot read " + path + " as NRRD: axis " + std::to_string(file.grid.timeAxis) +
                " is a time axis of " + std::to_string(file.grid.timeSteps) +
                " samples: a time series, which `mfadvr encode` makes one 4-D model of; where "
                "one volume is read, take one time step first (e.g. unu slice -a " +
                std::to_string(file.grid.timeAxis) + " -p 0)");
  NrrdVolume volume;
  volume.timeSteps = file.grid.timeSteps;
  volume.timeStart = file.grid.timeStart;
  volume.timeStep = file.grid.timeStep;
  StructuredGrid& layout = volume.layout;
  for (int a = 0; a < 3; ++a) {
    layout.dims[a] = file.grid.dims[a];
    layout.spacing[a] = file.grid.spacing[a];
    layout.origin[a] = file.grid.origin[a];
  }
  // The names VTK's reader gave these samples, so that models and pipelines keep their arrays'
  // names; a header's label comes first.
  layout.fieldName = !file.grid.label.empty()                              ? file.grid.label
                     : file.payload.gzipAt >= 0 || !file.asciiFile.empty() ? "ImageScalars"
                                                                           : "ImageFile";
  layout.fieldAssociation = "point data";
  layout.sampleType = file.grid.sampleType;
  layout.inputBytes = layout.sampleCount() * rawSampleSize(layout.sampleType);
  layout.notes = file.grid.notes;
  layout.source = path;
  volume.payload = std::move(file.payload);
  volume.asciiFile = std::move(file.asciiFile);
  volume.asciiOffset = file.asciiOffset;
  return volume;
}

namespace {

// A NRRD file holds one field at the points: a selection may name it, nothing else.
void requireSelectable(const std::string& path, const StructuredGrid& layout,
                       const FieldSelection& field) {
  if (!field.name.empty() && field.name != layout.fieldName)
    throw Error(path + ": a NRRD file holds one field, '" + layout.fieldName + "', not '" +
                field.name + "'");
  if (field.association == FieldAssociation::kCells)
    throw Error(path + ": a NRRD file holds samples at the grid points, not cell data");
  if (field.component != FieldSelection::kWholeArray)
    throw Error(path +
                ": a NRRD file read by mfadvr holds one scalar per sample, so "
                "--component does not apply to it");
}

}  // namespace

StructuredGrid readNrrdVolume(const std::string& path, const FieldSelection& field) {
  NrrdVolume volume = describeNrrdVolume(path);
  requireSelectable(path, volume.layout, field);
  StructuredGrid grid;
  if (!volume.asciiFile.empty()) {
    grid = volume.layout;
    const std::vector<double> values =
        readAsciiValues(volume.asciiFile, volume.asciiOffset, grid.sampleCount());
    grid.values.assign(values.begin(), values.end());
  } else {
    const RawSampleLayout file{volume.payload.file, volume.payload.offset, volume.payload.dtype,
                               volume.payload.bigEndian};
    std::unique_ptr<RawVolumeSource> source =
        volume.payload.gzipAt < 0 ? std::make_unique<RawVolumeSource>(file, volume.layout)
                                  : GzipVolume{volume.layout, file, volume.payload.gzipAt}.open();
    grid = source->readUnchecked(wholeRange(volume.layout.dims));
    grid.notes = volume.layout.notes;
  }
  grid.source = path;
  return grid;
}

}  // namespace mfadvr
