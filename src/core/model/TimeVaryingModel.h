#pragma once
// A model that may vary in time: a 3-D Model, or a 4-D one whose fourth tensor axis is time
// (TimeAxis.h). Everything that renders or decodes takes the model at one instant (at(t)): a
// 3-D Model, the weighted sum of p_t + 1 control slabs, which the 3-D renderers and decoders take
// unchanged. Queries at points with their own times evaluate the 4-D spline directly.
//
// The control points of a 4-D model are nt slabs one after the other, each a spatial grid x
// fastest: point (i, j, k, l) is number i + nx (j + ny (k + nz l)).
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/model/Model.h"
#include "core/model/TimeAxis.h"

namespace mfadvr {

class TimeVaryingModel {
 public:
  TimeVaryingModel() = default;
  // A model without a time axis.
  explicit TimeVaryingModel(Model model);
  // `shape`: the spatial knots, box, value range, provenance and mask (its control points are
  // ignored and replaced); `controls`: nt slabs of shape's control count each. Throws
  // mfadvr::Error when the sizes disagree or the axis is invalid (validateTimeAxis).
  TimeVaryingModel(const Model& shape, TimeAxis axis, std::vector<float> controls);

  bool hasTime() const { return time_.has_value(); }
  // Only with hasTime().
  const TimeAxis& timeAxis() const { return *time_; }
  // The instant rendered when none is asked for: the first step.
  double defaultTime() const { return time_ ? time_->steps.front() : 0.0; }

  // The model at time t (clamped onto the time range); without a time axis, the model itself.
  Model at(double t) const;
  // The model at the default time (its spatial shape, range, provenance and mask are those of
  // every instant).
  const Model& first() const { return first_; }

  // The envelope of the slabs (ControlEnvelope.h), computed on the first call (two 3-D control
  // grids); every model at() returns carries it. Null without a time axis.
  std::shared_ptr<const ControlEnvelope> controlEnvelope() const;

  // Every control point: nt slabs (one without a time axis).
  std::span<const float> controlPoints() const;
  std::int64_t slabCount() const { return time_ ? time_->controlCount() : 1; }

  // Value, physical gradient and (with rates non-empty) the derivative by time at points with
  // their own times; spans as Model::evaluate, times.size() == points.size(). Over all cores.
  void evaluate(std::span<const Vec3d> points, std::span<const double> times,
                std::span<float> values, std::span<Vec3f> gradients = {},
                std::span<float> rates = {}) const;

  // How the file stores the control points; the coded bytes of all slabs, when kept (as
  // Model::setControlCoding: they decode to controlPoints() exactly).
  const ControlCoding& controlCoding() const;
  const std::string* codedControlPoints() const;
  void setControlCoding(ControlCoding coding, std::shared_ptr<const std::string> coded = nullptr);

  Provenance& provenance() { return first_.provenance(); }
  const Provenance& provenance() const { return first_.provenance(); }
  void setValueRange(double lo, double hi);

 private:
  // Slab l as a 3-D model viewing the shared control points (no copy).
  Model slab(std::int64_t l) const;

  Model first_;
  std::optional<TimeAxis> time_;
  std::shared_ptr<const std::vector<float>> controls_;  // 4-D only
  ControlCoding coding_;
  std::shared_ptr<const std::string> coded_;
  struct LazyEnvelope {
    std::once_flag once;
    std::shared_ptr<const ControlEnvelope> value;
  };
  std::shared_ptr<LazyEnvelope> envelope_ = std::make_shared<LazyEnvelope>();
};

// `models` (the codings of the models are ignored) with one time axis: nt = models.size() slabs
// of one spatial shape. For tests and for building a model slab by slab.
TimeVaryingModel timeVaryingModelOfSlabs(const std::vector<Model>& slabs, TimeAxis axis);

}  // namespace mfadvr
