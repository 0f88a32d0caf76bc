#pragma once
// VTK's opacity correction a' = 1 - (1 - a)^(dt / unit), for steps of the full sample distance
// and for shorter ones (the last step of a ray). The renderer bakes full() into its transfer
// function table, so pow runs once per table entry and once per ray, not at every sample.
#include <cmath>

namespace mfadvr {

class OpacityCorrection {
 public:
  explicit OpacityCorrection(double exponent) : exponent_(exponent) {}

  float full(float a) const { return partial(a, 1.0); }

  // For a step whose length is `fraction` of the full one.
  float partial(float a, double fraction) const {
    if (!(a > 0.0f)) return 0.0f;
    if (a >= 1.0f) return 1.0f;
    return static_cast<float>(1.0 - std::pow(1.0 - double(a), exponent_ * fraction));
  }

 private:
  double exponent_;
};

}  // namespace mfadvr
