#include "core/model/TimeAxis.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/spline/BasisFunctions.h"
#include "core/util/Error.h"

namespace mfadvr {

double TimeAxis::toParameter(double t) const {
  const double u = (t - begin) / (end - begin);
  return std::clamp(u, 0.0, 1.0);
}

TimeWeights timeWeights(const TimeAxis& axis, double t) {
  TimeWeights w;
  const int p = axis.degree();
  const double u = axis.toParameter(t);
  const int span = axis.knots.findSpan(u);
  double ders[2 * (kMaxDegree + 1)];
  basisDerivatives(axis.knots, p, span, u, 1, ders);
  w.first = span - p;
  w.count = p + 1;
  // Outside the range the model holds the end instant: its rate of change there is zero.
  const double inverseLength = axis.contains(t) ? 1.0 / (axis.end - axis.begin) : 0.0;
  for (int r = 0; r <= p; ++r) {
    w.value[static_cast<size_t>(r)] = ders[r];
    w.rate[static_cast<size_t>(r)] = ders[p + 1 + r] * inverseLength;
  }
  return w;
}

void validateTimeAxis(const TimeAxis& axis, const char* what) {
  const std::string prefix = std::string(what) + ": ";
  if (!(std::isfinite(axis.begin) && std::isfinite(axis.end) && axis.end > axis.begin))
    throw Error(prefix + "the time range must be finite with end > begin");
  if (axis.steps.size() < 2) throw Error(prefix + "needs at least two time steps");
  for (size_t i = 0; i < axis.steps.size(); ++i) {
    if (!std::isfinite(axis.steps[i])) throw Error(prefix + "a time is not finite");
    if (i > 0 && !(axis.steps[i] > axis.steps[i - 1]))
      throw Error(prefix + "the times must increase strictly (time " + std::to_string(i) +
                  " is not after time " + std::to_string(i - 1) + ")");
  }
  if (axis.steps.front() != axis.begin || axis.steps.back() != axis.end)
    throw Error(prefix + "the time range must run from the first step to the last");
  if (axis.controlCount() < axis.degree() + 1 ||
      axis.controlCount() > static_cast<int>(axis.steps.size()))
    throw Error(prefix +
                "the number of time control points must lie between degree + 1 and the "
                "number of steps");
}

}  // namespace mfadvr
