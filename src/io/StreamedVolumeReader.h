#pragma once
// Volume files whose samples can be read a box at a time, without loading the whole file:
// headerless .raw files, and NRRD (raw encoding), MetaImage (uncompressed), NIfTI (.nii and
// .hdr/.img, uncompressed) and legacy VTK structured points (binary) whose single-component
// samples lie in one file from a known byte on. The header is checked as for the in-memory read
// (DeclaredSizeCheck.h); the grid's dims and placement come from VTK's reader of the format
// reading the header only, so that a streamed volume is the same grid, sample for sample, as
// loadStructuredVolume reads (tested).
#include <memory>
#include <string>

#include "io/RawVolumeSource.h"
#include "io/VolumeLoader.h"

namespace mfadvr {

// A source for `path`, or nullptr when its samples are stored otherwise (compressed or text
// data, several components, rotated axes, a NIfTI image that its header reorders, a chosen
// field): such files are read whole by loadStructuredVolume, which also gives their errors.
// Throws mfadvr::Error as loadStructuredVolume does for a header that does not match its data.
// --spacing / --origin in `options` replace the file's placement.
std::unique_ptr<RawVolumeSource> openStreamedVolume(const std::string& path,
                                                    const VolumeLoadOptions& options = {});

}  // namespace mfadvr
