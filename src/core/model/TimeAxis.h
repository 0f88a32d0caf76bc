#pragma once
// The time axis of a time-varying model: a fourth tensor axis (docs/time-varying.md).
//
// A 4-D model is f(x, t) = sum_l N_l(u(t)) S_l(x): nt spatial control grids ("slabs") S_l, each a
// 3-D grid of the model's spatial shape, weighted by the 1-D B-spline basis N_l of the time
// knots at the time parameter u(t) = (t - begin) / (end - begin), clamped onto [0, 1]. At any
// instant at most p_t + 1 basis functions are non-zero, so the model at time t is one 3-D control
// grid, the weighted sum of p_t + 1 slabs (contraction): the renderers stay 3-D.
#include <array>
#include <vector>

#include "core/spline/KnotVector.h"

namespace mfadvr {

struct TimeAxis {
  KnotVector knots;           // clamped on [0, 1]; degree p_t, nt = knots.controlCount()
  double begin = 0.0;         // the physical time of parameter 0 (the first step)
  double end = 1.0;           // ... and of parameter 1 (the last step); end > begin
  std::vector<double> steps;  // the input's times, increasing, begin and end included

  int degree() const { return knots.degree(); }
  int controlCount() const { return knots.controlCount(); }
  // Clamped onto [0, 1].
  double toParameter(double t) const;
  bool contains(double t) const { return t >= begin && t <= end; }
};

// The slabs first .. first + count - 1 that are non-zero at time t, with their basis values and
// their derivatives by physical time (per unit of t).
struct TimeWeights {
  int first = 0;
  int count = 0;
  std::array<double, kMaxDegree + 1> value{};
  std::array<double, kMaxDegree + 1> rate{};
};
TimeWeights timeWeights(const TimeAxis& axis, double t);

// Throws mfadvr::Error (prefixed by `what`) unless the range is finite with end > begin, the
// steps (at least two) increase strictly from begin to end, and the time control count lies
// between degree + 1 and the number of steps. The encoder and the file reader both check it.
void validateTimeAxis(const TimeAxis& axis, const char* what = "time axis");

}  // namespace mfadvr
