#include "core/analytic/BuiltinSeries.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <numbers>
#include <regex>
#include <sstream>

#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr {
namespace {

constexpr double kPi = std::numbers::pi;

// Three Gaussian blobs of width sigma_k(t) = 0.2 (1 + 0.25 sin(2 pi t + k)) at
// c_k(t) = (0.5 cos a_k, 0.5 sin a_k, 0.3 sin a_k), a_k = 2 pi (t + k / 3), each of height 1:
// a blob moves 0.2 (its half width at half maximum is 0.24) between two of 16 steps.
class OrbitingBlobs final : public BuiltinSeriesFunction {
 public:
  std::string name() const override { return "orbiting-blobs"; }
  Index3 defaultDims() const override { return {64, 64, 64}; }
  int defaultSteps() const override { return 16; }
  double value(const Vec3d& x, double t, Vec3d* gradient, double* rate) const override {
    double v = 0.0, dt = 0.0;
    Vec3d g = Vec3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const double a = 2.0 * kPi * (t + k / 3.0), da = 2.0 * kPi;
      const Vec3d c(0.5 * std::cos(a), 0.5 * std::sin(a), 0.3 * std::sin(a));
      const Vec3d dc(-0.5 * std::sin(a) * da, 0.5 * std::cos(a) * da, 0.3 * std::cos(a) * da);
      const double sigma = 0.2 * (1.0 + 0.25 * std::sin(2.0 * kPi * t + k));
      const double dsigma = 0.2 * 0.25 * 2.0 * kPi * std::cos(2.0 * kPi * t + k);
      const Vec3d d = x - c;
      const double r2 = d.squaredNorm(), s2 = sigma * sigma;
      const double e = std::exp(-r2 / (2.0 * s2));
      v += e;
      g += -e / s2 * d;
      // d/dt of -r^2 / (2 sigma^2) = d . c' / sigma^2 + r^2 sigma' / sigma^3
      dt += e * (d.dot(dc) / s2 + r2 * dsigma / (s2 * sigma));
    }
    if (gradient) *gradient = g;
    if (rate) *rate = dt;
    return v;
  }
};

std::vector<double> equallySpaced(int steps) {
  if (steps < 2) throw Error("a built-in series needs at least 2 steps");
  std::vector<double> t(static_cast<size_t>(steps));
  for (int s = 0; s < steps; ++s) t[static_cast<size_t>(s)] = static_cast<double>(s) / (steps - 1);
  return t;
}

class BuiltinAtTime final : public BuiltinFunction {
 public:
  BuiltinAtTime(std::shared_ptr<const BuiltinSeriesFunction> f, double t, const Index3& dims)
      : f_(std::move(f)), t_(t), dims_(dims) {}
  std::string name() const override { return f_->name(); }
  double value(const Vec3d& x) const override { return f_->value(x, t_); }
  double valueGradient(const Vec3d& x, Vec3d& gradient) const override {
    return f_->value(x, t_, &gradient);
  }
  Index3 defaultDims() const override { return dims_; }

 private:
  std::shared_ptr<const BuiltinSeriesFunction> f_;
  double t_;
  Index3 dims_;
};

}  // namespace

std::unique_ptr<BuiltinFunction> builtinAtTime(std::shared_ptr<const BuiltinSeriesFunction> f,
                                               double t, const Index3& dims) {
  return std::make_unique<BuiltinAtTime>(std::move(f), t, dims);
}

std::vector<std::string> builtinSeriesNames() {
  return {"orbiting-blobs"};
}

std::unique_ptr<BuiltinSeriesFunction> makeBuiltinSeries(const std::string& name) {
  if (name == "orbiting-blobs") return std::make_unique<OrbitingBlobs>();
  std::string known;
  for (const auto& n : builtinSeriesNames()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown time-varying built-in '" + name + "' (known: " + known + ")");
}

bool isBuiltinSeriesSpec(const std::string& spec) {
  if (spec.rfind("builtin:", 0) != 0) return false;
  const std::string rest = spec.substr(8);
  const std::string name = rest.substr(0, rest.find(':'));
  for (const auto& n : builtinSeriesNames())
    if (n == name) return true;
  return false;
}

BuiltinVolumeSeries::BuiltinVolumeSeries(const std::string& spec) {
  static const std::regex re(R"(builtin:([a-z\-]+)(?::(\d+)(?:x(\d+)x(\d+)(?:x(\d+))?)?)?)");
  std::smatch m;
  if (!std::regex_match(spec, m, re))
    throw Error("malformed built-in spec '" + spec +
                "': expected builtin:NAME, builtin:NAME:N, builtin:NAME:NXxNYxNZ or "
                "builtin:NAME:NXxNYxNZxNT");
  f_ = makeBuiltinSeries(m[1]);
  auto parse = [&](const std::string& s) -> std::int64_t {
    if (s.size() > 6) throw Error("a size in '" + spec + "' is too large");
    const long v = std::stol(s);
    if (v < 2) throw Error("the sizes in '" + spec + "' must be at least 2");
    return v;
  };
  dims_ = f_->defaultDims();
  int steps = f_->defaultSteps();
  if (m[2].matched) {
    const std::int64_t nx = parse(m[2]);
    dims_ = m[3].matched ? Index3{nx, parse(m[3]), parse(m[4])} : Index3{nx, nx, nx};
    if (m[5].matched) steps = static_cast<int>(parse(m[5]));
  }
  times_ = equallySpaced(steps);
}

BuiltinVolumeSeries::BuiltinVolumeSeries(std::shared_ptr<const BuiltinSeriesFunction> f,
                                         const Index3& dims, std::vector<double> times)
    : f_(std::move(f)), dims_(dims), times_(std::move(times)) {}

std::string BuiltinVolumeSeries::source() const {
  return "builtin:" + f_->name() + ":" + std::to_string(dims_[0]) + "x" + std::to_string(dims_[1]) +
         "x" + std::to_string(dims_[2]) + "x" + std::to_string(times_.size());
}

std::string BuiltinVolumeSeries::stepName(int step) const {
  std::ostringstream s;
  s << "step " << step << " (t = " << time(step) << ") of " << source();
  return s.str();
}

StructuredGrid BuiltinVolumeSeries::sampleAt(double t) const {
  StructuredGrid g;
  g.dims = dims_;
  for (int a = 0; a < 3; ++a)
    if (dims_[a] < 2) throw Error("a built-in series is sampled with at least 2 samples per axis");
  g.origin = Vec3d::Constant(-1.0);
  for (int a = 0; a < 3; ++a) g.spacing[a] = 2.0 / static_cast<double>(dims_[a] - 1);
  g.source = source();
  g.fieldName = f_->name();
  g.sampleType = "float64";
  g.inputBytes = g.sampleCount() * static_cast<std::int64_t>(sizeof(double));
  requireMemory(4 * g.sampleCount(), "sampling " + source());
  g.values.resize(static_cast<size_t>(g.sampleCount()));
  tbb::parallel_for(std::int64_t(0), dims_[2], [&](std::int64_t k) {
    for (std::int64_t j = 0; j < dims_[1]; ++j)
      for (std::int64_t i = 0; i < dims_[0]; ++i)
        g.at(i, j, k) = static_cast<float>(f_->value(g.position(i, j, k), t));
  });
  return g;
}

StructuredGrid BuiltinVolumeSeries::load(int step) const {
  return sampleAt(time(step));
}

}  // namespace mfadvr
