#pragma once
// VTK's opacity correction a' = 1 - (1 - a)^(dt / unit) for the full step length, read from a
// table over a instead of calling pow at every sample (pow was a quarter of a trilinear render).
//
// The table holds the exact value at 2^16 + 1 evenly spaced a and interpolates linearly. The
// function is smooth except near a = 1 when dt < unit, so the interpolation error is below 1e-9
// for a < 0.99 and stays under 4e-3 in the last interval (a > 1 - 2^-16), where a sample is
// opaque anyway. Steps of another length (the last, shorter step of a ray) use pow directly.
#include <cmath>
#include <vector>

namespace mfadvr {

class OpacityCorrection {
 public:
  static constexpr int kIntervals = 1 << 16;

  explicit OpacityCorrection(double exponent) : exponent_(exponent), table_(kIntervals + 1) {
    for (int i = 0; i <= kIntervals; ++i)
      table_[i] = static_cast<float>(1.0 - std::pow(1.0 - double(i) / kIntervals, exponent));
  }

  // a in [0, 1]; values outside are clamped.
  float full(float a) const {
    if (!(a > 0.0f)) return 0.0f;
    if (a >= 1.0f) return 1.0f;
    const float x = a * kIntervals;
    const int i = static_cast<int>(x);
    const float t = x - static_cast<float>(i);
    return table_[i] + t * (table_[i + 1] - table_[i]);
  }

  // For a step whose length is `fraction` of the full one.
  float partial(float a, double fraction) const {
    if (!(a > 0.0f)) return 0.0f;
    if (a >= 1.0f) return 1.0f;
    return static_cast<float>(1.0 - std::pow(1.0 - double(a), exponent_ * fraction));
  }

 private:
  double exponent_;
  std::vector<float> table_;
};

}  // namespace mfadvr
