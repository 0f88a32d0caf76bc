#pragma once
// Volume files whose samples can be read a box at a time, without loading the whole file:
// headerless .raw files, and NRRD (raw or gzip encoding), MetaImage (uncompressed), NIfTI
// (.nii, .nii.gz, .hdr/.img) and legacy VTK structured points (binary) whose single-component
// samples lie in one file from a known byte on. The header is checked as for the in-memory read
// (DeclaredSizeCheck.h); the grid's dims and placement come from mfadvr's own NRRD reader
// (NrrdVolumeReader.h), or from VTK's reader of the other formats reading the header only, so
// that a streamed volume is the same grid, sample for sample, as loadStructuredVolume reads
// (tested).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/InflatedPayload.h"
#include "io/RawVolumeSource.h"
#include "io/VolumeLoader.h"

namespace mfadvr {

// What to do with samples stored as one gzip stream (NRRD's gzip encoding, .nii.gz).
enum class GzipPayloads {
  kLeaveToVtk,              // nullptr: the in-memory read inflates them (NRRD: mfadvr's own
                            // reader; NIfTI: VTK's)
  kInflateToTemporaryFile,  // inflated once to a temporary file (InflatedPayload.h), then read
                            // box by box: for volumes that do not fit in memory
};

// A source for `path`, or nullptr when its samples are stored otherwise (text data, several
// components, rotated axes, a NIfTI image that its header reorders, a chosen field): such
// files are read whole by loadStructuredVolume, which also gives their errors. Throws
// mfadvr::Error as loadStructuredVolume does for a header that does not match its data.
// --spacing / --origin in `options` replace the file's placement. `inflating`, when set, hears
// how far the inflation of gzip samples is (it may throw to stop it).
std::unique_ptr<RawVolumeSource> openStreamedVolume(const std::string& path,
                                                    const VolumeLoadOptions& options = {},
                                                    GzipPayloads gzip = GzipPayloads::kLeaveToVtk,
                                                    const InflateProgress& inflating = {});

// A file whose samples are one gzip stream (NRRD's gzip encoding, .nii.gz), its header read and
// checked: the grid is known, the samples are not inflated yet (that takes seconds per
// gigabyte), so that a reader can give the grid at once and inflate when samples are asked for.
struct GzipVolume {
  StructuredGrid layout;  // dims, placement, names, notes; no values
  RawSampleLayout file;   // the compressed file; `offset` counts bytes of the inflated stream
  std::int64_t gzipAt;    // where the gzip stream starts in file.path

  // Inflates the samples once to a temporary file (InflatedPayload.h) and opens them box by
  // box; `inflating` hears how far it is and may throw to stop it.
  std::unique_ptr<RawVolumeSource> open(const InflateProgress& inflating = {}) const;
  // The same for the z planes `z0` .. `z1` alone (a piece of a parallel pipeline): the stream
  // is inflated up to the last of them, and the temporary file holds only them. The source's
  // grid is those planes (its origin at plane z0).
  std::unique_ptr<RawVolumeSource> openPlanes(std::int64_t z0, std::int64_t z1,
                                              const InflateProgress& inflating = {}) const;
};

// The gzip file at `path` as openStreamedVolume would stream it, before inflating; nullopt for
// every other file (then openStreamedVolume or loadStructuredVolume). Throws as they do for a
// header that does not match its data.
std::optional<GzipVolume> describeGzipVolume(const std::string& path,
                                             const VolumeLoadOptions& options = {});

// A volume file that holds a time series, one whole volume per step: a NRRD with a time axis
// (the last axis) or a NIfTI image with time points (dim[4] > 1; times toffset + pixdim[4] x
// step, in the file's units). Its first step is the grid openStreamedVolume reads of it.
struct TimeStepsInFile {
  StructuredGrid layout;     // of one step: dims, placement, names, notes (the time unit)
  RawSampleLayout file;      // step 0; step s lies `stepBytes` x s further on
  std::int64_t gzipAt = -1;  // >= 0: the steps are one gzip stream from this byte of file.path
  std::int64_t stepBytes = 0;
  std::vector<double> times;  // one per step, increasing
};

// nullopt for a file of one volume (or of one time step) and for other formats. Throws
// mfadvr::Error for a damaged header, as openStreamedVolume does, and with the reason for a time
// series that cannot be read step by step (ascii values, a NIfTI image whose header reorders
// its samples).
std::optional<TimeStepsInFile> describeTimeStepsInFile(const std::string& path);

}  // namespace mfadvr
