#pragma once
// One entry point for every volume input: built-in analytic fields and the supported files.
// docs/input-formats.md describes the formats, the raw naming rule and the errors.
#include <optional>
#include <string>

#include "core/grid/StructuredGrid.h"
#include "core/util/Vec.h"
#include "io/FieldSelection.h"

namespace mfadvr {

struct VolumeLoadOptions {
  std::optional<Vec3d> spacing;  // override (raw files: default 1,1,1)
  std::optional<Vec3d> origin;   // override (raw files: default 0,0,0)
  // The array to encode (name, point or cell data, component); only formats with named arrays
  // (.vti, .vtk, .nrrd, .mha, ...) have a choice. Default: the active scalars, else the first
  // one-component point-data array, else the same from the cell data.
  FieldSelection field;
};

// input: "builtin:..." (sampled by sampleBuiltinSpec; the options do not apply to it), or a
// file path whose extension picks the reader. Returns a validated StructuredGrid (NaN/Inf
// samples, non-positive spacing are errors). Throws mfadvr::Error naming the input.
StructuredGrid loadStructuredVolume(const std::string& input,
                                    const VolumeLoadOptions& options = {});

// Human-readable list of supported formats for --help text, one per line.
std::string supportedVolumeFormats();

}  // namespace mfadvr
