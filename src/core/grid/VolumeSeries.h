#pragma once
// A time series of volumes on one grid, read one step at a time: what the time-series encoder
// streams over (core/encode/TimeSeriesEncoder.h), so that a series is never held whole. The
// readers of files (io/VolumeSeriesReader.h) and the time-varying built-in functions
// (core/analytic/BuiltinSeries.h) implement it.
#include <string>

#include "core/grid/StructuredGrid.h"

namespace mfadvr {

class VolumeSeries {
 public:
  virtual ~VolumeSeries() = default;
  virtual int size() const = 0;
  // The physical time of each step, increasing.
  virtual double time(int step) const = 0;
  // Names the step in messages (a file name, "step 3 of name.nrrd").
  virtual std::string stepName(int step) const = 0;
  // Step `step`'s samples; throws mfadvr::Error for a bad file.
  virtual StructuredGrid load(int step) const = 0;
  // The whole series, for the model's provenance.
  virtual std::string source() const = 0;
};

}  // namespace mfadvr
