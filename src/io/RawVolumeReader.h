#pragma once
// Headerless raw volumes named after the Open SciVis convention `name_XxYxZ_dtype.raw`
// (e.g. fuel_64x64x64_uint8.raw): x fastest, little-endian. The name is the only metadata,
// so it is parsed strictly and the file size must match it exactly.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/grid/StructuredGrid.h"
#include "core/util/Vec.h"
#include "io/RawVolumeSource.h"

namespace mfadvr {

struct RawVolumeName {
  std::string name;  // the part before _XxYxZ_
  Index3 dims{0, 0, 0};
  std::string dtype;  // as written in the name: uint8, int16, float32, ...
};

// Sample types a raw name may carry, in the order the documentation lists them.
const std::vector<std::string>& rawSampleTypes();

// Bytes per sample of a type from rawSampleTypes(); 0 for any other string.
int rawSampleSize(const std::string& dtype);

// Splits a file name (directories are ignored) into name, dims and dtype; nullopt when it does
// not have the shape NAME_XxYxZ_DTYPE.raw. The dtype is not checked here, so that the caller
// can tell "unknown type" apart from "not the convention".
std::optional<RawVolumeName> parseRawVolumeName(const std::string& path);

// A raw volume read box by box (out-of-core encoding). Throws as readRawVolume does, before
// any sample is read.
std::unique_ptr<RawVolumeSource> openRawVolume(const std::string& path);

// Reads a raw volume. Throws mfadvr::Error when the name does not follow the convention, the
// dtype is unknown, the file cannot be opened, or its size differs from X*Y*Z*sizeof(dtype).
// The grid has origin 0 and spacing 1 and is not validated (the caller overrides and validates).
StructuredGrid readRawVolume(const std::string& path);

}  // namespace mfadvr
