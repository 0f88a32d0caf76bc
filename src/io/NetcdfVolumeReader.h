#pragma once
// NetCDF volumes (.nc, .nc4, .cdf, .netcdf: classic, 64-bit offset and netCDF-4 files), read
// with Debian's libnetcdf. What is read follows the CF conventions as far as a regular grid
// needs them:
//   - the variable: --field NAME, else the only data variable (not a coordinate variable) with
//     three dimensions of more than one value besides an optional time dimension;
//   - time: the dimension whose coordinate variable has axis = "T", standard_name = "time" or
//     units "... since ..." (else an unlimited dimension or one named time or t), which must be
//     the variable's slowest dimension of more than one value; its coordinate values are the
//     times (in the file's units, named in a note);
//   - placement: each spatial dimension's coordinate variable (evenly spaced and increasing:
//     origin and spacing; else the samples are placed by index, with a note saying why);
//     x is the fastest dimension, z the slowest;
//   - values: packed integers unpacked (scale_factor, add_offset); a sample equal to
//     _FillValue or missing_value (for float data also netCDF's default fill) is missing data,
//     which an error reports (mfadvr needs a value at every sample).
// Any other layout, and every libnetcdf error, is an mfadvr::Error naming the file.
#include <string>
#include <vector>

#include "core/grid/StructuredGrid.h"
#include "io/FieldSelection.h"

namespace mfadvr {

bool isNetcdfPath(const std::string& path);

struct NetcdfVolume {
  std::string path, variable;
  StructuredGrid layout;      // one step: dims, placement, names, sample type, notes; no values
  std::vector<double> times;  // the time coordinate's values; empty without a time dimension
};

// The header of `path`: which variable, its grid and its times; nothing of the samples is read.
NetcdfVolume describeNetcdfVolume(const std::string& path, const FieldSelection& field = {});

// The samples of time step `step` (0 for a variable without a time dimension).
StructuredGrid readNetcdfStep(const NetcdfVolume& volume, int step);

// One volume: the variable's first time step (a note says how many there are).
StructuredGrid readNetcdfVolume(const std::string& path, const FieldSelection& field = {});

}  // namespace mfadvr
