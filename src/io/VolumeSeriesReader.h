#pragma once
// Time series of volume files (docs/time-varying.md, Inputs):
//   NAME.pvd      ParaView's collection: <DataSet timestep="T" file="F"/> per step
//   NAME.series   ParaView's file series JSON: {"files": [{"name": F, "time": T}, ...]}
//   a pattern     name_%03d.nrrd (printf style, one %d with optional zero padding and width):
//                 the files that match, by number; a constant stride (0, 10, 20, ...) is fine,
//                 a missing number in between is an error naming it
//   a directory   its numbered volume files of one format (name_000.vti, name_001.vti, ...);
//                 a directory of DICOM slices stays one volume
//   one file      a NRRD with a time axis, a NIfTI image with time points
//                 (StreamedVolumeReader.h, TimeStepsInFile), a NetCDF variable with a time
//                 dimension (NetcdfVolumeReader.h)
// Times: the file's, else the numbers; `times` (encode --times) replaces them (as many as steps).
// Each step is read when the encoder asks for it, with loadStructuredVolume and the given options.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/grid/VolumeSeries.h"
#include "io/VolumeLoader.h"

namespace mfadvr {

// Whether `input` names a series (by the rules above); a plain volume file is not one.
// A file of several time steps (a 4-D NRRD or NIfTI file, a NetCDF variable with a time
// dimension: `field` chooses the variable) is one too.
bool isVolumeSeriesInput(const std::string& input, const FieldSelection& field = {});

// Throws mfadvr::Error for a malformed collection, a pattern without files, a missing step, a
// step file that does not exist, a number of `times` that differs from the steps.
std::unique_ptr<VolumeSeries> openVolumeSeries(const std::string& input,
                                               const VolumeLoadOptions& options = {},
                                               std::optional<std::vector<double>> times = {});

// The steps a collection's text lists, files relative to `path`'s folder: `json` for the .series
// format, else a .pvd. Throws mfadvr::Error naming `path` for malformed text (the fuzzed parser).
struct CollectionSteps {
  std::vector<std::string> files;
  std::vector<double> times;
};
CollectionSteps parseCollection(const std::string& text, const std::string& path, bool json);

// A list of files with their times (for collections made elsewhere).
class FileVolumeSeries final : public VolumeSeries {
 public:
  FileVolumeSeries(std::string source, std::vector<std::string> files, std::vector<double> times,
                   VolumeLoadOptions options);
  int size() const override { return static_cast<int>(files_.size()); }
  double time(int step) const override { return times_[static_cast<size_t>(step)]; }
  std::string stepName(int step) const override { return files_[static_cast<size_t>(step)]; }
  StructuredGrid load(int step) const override;
  std::string source() const override { return source_; }
  const std::vector<std::string>& files() const { return files_; }

 private:
  std::string source_;
  std::vector<std::string> files_;
  std::vector<double> times_;
  VolumeLoadOptions options_;
};

}  // namespace mfadvr
