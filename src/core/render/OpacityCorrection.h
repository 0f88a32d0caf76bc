#pragma once
// VTK's opacity correction a' = 1 - (1 - a)^(dt / unit), for steps of the full sample distance
// and for shorter ones (the last step of a ray). The renderer bakes full() into its transfer
// function table, so pow runs once per table entry and once per ray, not at every sample.
#include "core/render/kernel/OpacityCorrectionKernel.h"

namespace mfadvr {

class OpacityCorrection {
 public:
  explicit OpacityCorrection(double exponent) : exponent_(exponent) {}

  float full(float a) const { return partial(a, 1.0); }

  // For a step whose length is `fraction` of the full one.
  float partial(float a, double fraction) const { return correctOpacity(a, exponent_ * fraction); }
  double exponent() const { return exponent_; }

 private:
  double exponent_;
};

}  // namespace mfadvr
