#include "core/model/TimeVaryingModel.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

std::int64_t spatialCount(const Model& m) {
  return static_cast<std::int64_t>(m.spline().controlPoints().size());
}

Model withControls(const Model& shape, TensorBSpline spline) {
  Model out(std::move(spline), shape.domain(), shape.valueMin(), shape.valueMax(),
            shape.provenance());
  out.setMask(shape.mask());
  return out;
}

}  // namespace

TimeVaryingModel::TimeVaryingModel(Model model) : first_(std::move(model)) {}

TimeVaryingModel::TimeVaryingModel(const Model& shape, TimeAxis axis, std::vector<float> controls) {
  validateTimeAxis(axis);
  const std::int64_t m = spatialCount(shape);
  if (static_cast<std::int64_t>(controls.size()) != m * axis.controlCount())
    throw Error("a time-varying model needs " + std::to_string(axis.controlCount()) + " slabs of " +
                std::to_string(m) + " control points, not " + std::to_string(controls.size()) +
                " points");
  controls_ = std::make_shared<const std::vector<float>>(std::move(controls));
  time_ = std::move(axis);
  first_ = shape;  // at() takes the shape (knots, box, range, mask) from first_
  first_ = at(time_->steps.front());
}

std::span<const float> TimeVaryingModel::controlPoints() const {
  if (controls_) return *controls_;
  return first_.spline().controlPoints();
}

Model TimeVaryingModel::slab(std::int64_t l) const {
  const std::int64_t m = spatialCount(first_);
  return withControls(
      first_, TensorBSpline(first_.spline().allKnots(), controls_,
                            std::span<const float>(*controls_)
                                .subspan(static_cast<size_t>(l * m), static_cast<size_t>(m))));
}

Model TimeVaryingModel::at(double t) const {
  if (!time_) return first_;
  const TimeWeights w = timeWeights(*time_, t);
  const std::int64_t m = static_cast<std::int64_t>(controls_->size()) / time_->controlCount();
  std::vector<float> ctrl(static_cast<size_t>(m));
  const float* all = controls_->data();
  // p_t + 1 multiply-adds per control point, in double as every fit sums.
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, m, 1 << 14), [&](const auto& range) {
    for (std::int64_t i = range.begin(); i < range.end(); ++i) {
      double sum = 0.0;
      for (int r = 0; r < w.count; ++r)
        sum += w.value[static_cast<size_t>(r)] * all[(w.first + r) * m + i];
      ctrl[static_cast<size_t>(i)] = static_cast<float>(sum);
    }
  });
  Model out = withControls(first_, TensorBSpline(first_.spline().allKnots(), std::move(ctrl)));
  out.setControlEnvelope(controlEnvelope());
  return out;
}

std::shared_ptr<const ControlEnvelope> TimeVaryingModel::controlEnvelope() const {
  if (!time_) return nullptr;
  std::call_once(envelope_->once, [&] {
    const std::int64_t m = static_cast<std::int64_t>(controls_->size()) / time_->controlCount();
    const std::int64_t nt = time_->controlCount();
    std::vector<float> lower(static_cast<size_t>(m)), upper(static_cast<size_t>(m));
    const float* all = controls_->data();
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, m, 1 << 14), [&](const auto& range) {
      for (std::int64_t i = range.begin(); i < range.end(); ++i) {
        float lo = all[i], hi = all[i];
        for (std::int64_t l = 1; l < nt; ++l) {
          const float v = all[l * m + i];
          // NaN reaches both ends (a cell with one is never skipped).
          lo = v < lo || std::isnan(v) ? v : lo;
          hi = v > hi || std::isnan(v) ? v : hi;
        }
        lower[static_cast<size_t>(i)] = lo;
        upper[static_cast<size_t>(i)] = hi;
      }
    });
    const auto& knots = first_.spline().allKnots();
    envelope_->value = std::make_shared<const ControlEnvelope>(ControlEnvelope{
        TensorBSpline(knots, std::move(lower)), TensorBSpline(knots, std::move(upper))});
  });
  return envelope_->value;
}

void TimeVaryingModel::evaluate(std::span<const Vec3d> points, std::span<const double> times,
                                std::span<float> values, std::span<Vec3f> gradients,
                                std::span<float> rates) const {
  const size_t n = points.size();
  if (values.size() != n || times.size() != n || (!gradients.empty() && gradients.size() != n) ||
      (!rates.empty() && rates.size() != n))
    throw Error("query spans must match the number of points");
  if (!time_) {
    first_.evaluate(points, values, gradients);
    std::fill(rates.begin(), rates.end(), 0.0f);
    return;
  }
  std::vector<Model> slabs;
  slabs.reserve(static_cast<size_t>(time_->controlCount()));
  for (int l = 0; l < time_->controlCount(); ++l) slabs.push_back(slab(l));
  const bool wantGradient = !gradients.empty();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const auto& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const TimeWeights w = timeWeights(*time_, times[i]);
      double v = 0.0, dt = 0.0;
      Vec3d g = Vec3d::Zero();
      for (int r = 0; r < w.count; ++r) {
        const Model& s = slabs[static_cast<size_t>(w.first + r)];
        const double wv = w.value[static_cast<size_t>(r)];
        if (wantGradient) {
          const ValueGradient vg = s.valueGradient(points[i]);
          v += wv * vg.value;
          dt += w.rate[static_cast<size_t>(r)] * vg.value;
          g += wv * vg.gradient.cast<double>();
        } else {
          const double sv = s.value(points[i]);
          v += wv * sv;
          dt += w.rate[static_cast<size_t>(r)] * sv;
        }
      }
      values[i] = static_cast<float>(v);
      if (wantGradient) gradients[i] = g.cast<float>();
      if (!rates.empty()) rates[i] = static_cast<float>(dt);
    }
  });
}

const ControlCoding& TimeVaryingModel::controlCoding() const {
  return time_ ? coding_ : first_.controlCoding();
}

const std::string* TimeVaryingModel::codedControlPoints() const {
  return time_ ? coded_.get() : first_.codedControlPoints();
}

void TimeVaryingModel::setControlCoding(ControlCoding coding,
                                        std::shared_ptr<const std::string> coded) {
  if (!time_) {
    first_.setControlCoding(coding, std::move(coded));
    return;
  }
  coding_ = coding;
  coded_ = std::move(coded);
}

void TimeVaryingModel::setValueRange(double lo, double hi) {
  first_.setValueRange(lo, hi);
}

TimeVaryingModel timeVaryingModelOfSlabs(const std::vector<Model>& slabs, TimeAxis axis) {
  if (slabs.empty()) throw Error("a time-varying model needs at least one slab");
  std::vector<float> controls;
  const Index3 counts = slabs.front().spline().counts();
  for (const Model& s : slabs) {
    if (s.spline().counts() != counts)
      throw Error("the slabs of a time-varying model must share one control grid");
    controls.insert(controls.end(), s.spline().controlPoints().begin(),
                    s.spline().controlPoints().end());
  }
  return TimeVaryingModel(slabs.front(), std::move(axis), std::move(controls));
}

}  // namespace mfadvr
