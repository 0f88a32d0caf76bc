#pragma once
// Time-varying analytic fields on [-1,1]^3 x [0,1] with exact value, gradient and time derivative:
// the ground truth of `mfadvr eval time` and time series that need no files.
//
// Spec syntax: builtin:NAME (its default grid and steps), builtin:NAME:N (N^3 samples),
// builtin:NAME:NXxNYxNZ or builtin:NAME:NXxNYxNZxNT (NT steps at t = s / (NT - 1)).
// Names: orbiting-blobs (default 64^3 x 16 steps): three Gaussian blobs circling the z axis once
// per unit time while they bob up and down and breathe (docs/builtins.md states the formula).
#include <memory>
#include <string>
#include <vector>

#include "core/analytic/BuiltinFunction.h"
#include "core/grid/VolumeSeries.h"
#include "core/util/Vec.h"

namespace mfadvr {

class BuiltinSeriesFunction {
 public:
  virtual ~BuiltinSeriesFunction() = default;
  virtual std::string name() const = 0;
  // Value at (x, t); with the pointers, the physical gradient and the derivative by t.
  virtual double value(const Vec3d& x, double t, Vec3d* gradient = nullptr,
                       double* rate = nullptr) const = 0;
  virtual Index3 defaultDims() const = 0;
  virtual int defaultSteps() const = 0;
};

// The names of the time-varying built-ins.
std::vector<std::string> builtinSeriesNames();
bool isBuiltinSeriesSpec(const std::string& spec);
// Throws mfadvr::Error for an unknown name.
std::unique_ptr<BuiltinSeriesFunction> makeBuiltinSeries(const std::string& name);

// The field at one instant, as a 3-D built-in (the truth a render or an evaluation compares with).
std::unique_ptr<BuiltinFunction> builtinAtTime(std::shared_ptr<const BuiltinSeriesFunction> f,
                                               double t, const Index3& dims);

// A time-varying built-in sampled on dims points per axis spanning [-1,1]^3 at `steps` equally
// spaced times over [0, 1] (or at the given times).
class BuiltinVolumeSeries final : public VolumeSeries {
 public:
  // Parses builtin:NAME[:N | :NXxNYxNZ | :NXxNYxNZxNT]; throws mfadvr::Error for a bad spec.
  explicit BuiltinVolumeSeries(const std::string& spec);
  BuiltinVolumeSeries(std::shared_ptr<const BuiltinSeriesFunction> f, const Index3& dims,
                      std::vector<double> times);
  int size() const override { return static_cast<int>(times_.size()); }
  double time(int step) const override { return times_[static_cast<size_t>(step)]; }
  std::string stepName(int step) const override;
  StructuredGrid load(int step) const override;
  std::string source() const override;
  // The field at any time (for truths between the steps).
  StructuredGrid sampleAt(double t) const;
  const BuiltinSeriesFunction& function() const { return *f_; }
  std::shared_ptr<const BuiltinSeriesFunction> sharedFunction() const { return f_; }
  const Index3& dims() const { return dims_; }

 private:
  std::shared_ptr<const BuiltinSeriesFunction> f_;
  Index3 dims_{};
  std::vector<double> times_;
};

}  // namespace mfadvr
