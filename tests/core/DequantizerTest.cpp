// encode --dequantize (core/encode/Dequantizer.h): the smoothest model within half a
// quantization step of every sample; it rounds back to every sample, keeps what needs no
// smoothing, and refuses steps that do not describe the data.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "core/encode/Dequantizer.h"
#include "core/encode/Encoder.h"
#include "core/encode/StructuredEncoder.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// A grid of `dims` samples of f(x, y, z) (integer coordinates), rounded to multiples of `step`.
template <class F>
StructuredGrid quantizedGrid(const Index3& dims, double step, const F& f,
                             const std::string& type = "uint8") {
  StructuredGrid g;
  g.dims = dims;
  g.sampleType = type;
  g.source = "test";
  g.values.resize(static_cast<size_t>(dims[0] * dims[1] * dims[2]));
  size_t i = 0;
  for (std::int64_t z = 0; z < dims[2]; ++z)
    for (std::int64_t y = 0; y < dims[1]; ++y)
      for (std::int64_t x = 0; x < dims[0]; ++x, ++i)
        g.values[i] = static_cast<float>(step * std::nearbyint(f(double(x), double(y), double(z)) / step));
  g.inputBytes = static_cast<std::int64_t>(g.values.size());
  return g;
}

// The largest |model - sample| over the grid, and whether rounding the model to the step gives
// every sample back.
struct RoundTrip {
  double maxError = 0.0;
  bool roundsBack = true;
};
RoundTrip roundTrip(const Model& m, const StructuredGrid& g, double step) {
  const std::vector<double> v = splineOnGrid(m.spline(), g.dims);
  RoundTrip r;
  for (size_t i = 0; i < v.size(); ++i) {
    r.maxError = std::max(r.maxError, std::abs(v[i] - g.values[i]));
    r.roundsBack = r.roundsBack && step * std::nearbyint(v[i] / step) == g.values[i];
  }
  return r;
}

EncodeOptions dequantizing(double step, std::optional<ControlCoder> coder = {}) {
  EncodeOptions o;
  o.dequantizeStep = step;
  o.coding.coder = coder;
  return o;
}

TEST(Dequantize, RandomQuantizedGridsRoundBackWithEveryCoding) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> phase(0.0, 6.28), noise(-0.7, 0.7);
  for (int trial = 0; trial < 2; ++trial) {
    const double p0 = phase(rng), p1 = phase(rng);
    const StructuredGrid g = quantizedGrid({13, 11, 9}, 1.0, [&](double x, double y, double z) {
      return 120.0 + 40.0 * std::sin(0.3 * x + p0) * std::cos(0.25 * y + p1) + 3.0 * z +
             noise(rng);
    });
    for (const ControlCoder coder : {ControlCoder::kFloat32, ControlCoder::kZfp}) {
      FitReport report;
      const Model m = encodeStructured(g, dequantizing(0.0, coder), &report);
      const RoundTrip r = roundTrip(m, g, 1.0);
      EXPECT_LE(r.maxError, 0.5) << trial;
      EXPECT_TRUE(r.roundsBack) << trial;
      EXPECT_NEAR(report.maxError, r.maxError, 1e-5);
      EXPECT_EQ(report.dequantizeStep, 1.0);
      EXPECT_GT(report.dequantizeIterations, 1);
      EXPECT_GT(report.dequantizeEdgeShare, 0.0);
      EXPECT_EQ(m.provenance().encoder, "structured-dequantize");
    }
  }
}

// Other steps: float samples quantized to 0.25 (given), int16 samples to 1 (the default).
TEST(Dequantize, AGivenStepIsHonoured) {
  const auto f = [](double x, double y, double z) {
    return 3.0 * std::sin(0.4 * x) + 0.2 * y * z;
  };
  const StructuredGrid g = quantizedGrid({12, 12, 12}, 0.25, f, "float32");
  const Model m = encodeStructured(g, dequantizing(0.25));
  const RoundTrip r = roundTrip(m, g, 0.25);
  EXPECT_LE(r.maxError, 0.125);
  EXPECT_TRUE(r.roundsBack);
}

// Data that need no smoothing (a polynomial of the model's degree, here with integer values)
// stay as they are: the smoother keeps them, so the first iteration is the answer.
TEST(Dequantize, APolynomialStaysReproduced) {
  const auto poly = [](double x, double y, double z) { return x * x + 2.0 * y + 3.0 * z * y; };
  const StructuredGrid g = quantizedGrid({10, 9, 8}, 1.0, poly, "int16");
  FitReport report;
  const Model m = encodeStructured(g, dequantizing(0.0), &report);
  EXPECT_TRUE(report.dequantizeConverged);
  EXPECT_LE(report.dequantizeIterations, 2);
  // Everywhere, not only at the samples.
  double worst = 0.0;
  for (double x = 0.0; x <= 9.0; x += 0.7)
    for (double y = 0.0; y <= 8.0; y += 0.9)
      for (double z = 0.0; z <= 7.0; z += 1.1) {
        const Vec3d u(x / 9.0, y / 8.0, z / 7.0);
        worst = std::max(worst, std::abs(m.spline().value(u) - poly(x, y, z)));
      }
  EXPECT_LT(worst, 1e-3);
}

// What it is for: a smooth field quantized to integers has terraces; the dequantized model is
// closer to the field than the interpolating one, between the samples as at them.
TEST(Dequantize, IsCloserToASmoothFieldThanInterpolationOfItsSteps) {
  const auto f = [](double x, double y, double z) {
    return 20.0 * std::exp(-((x - 12) * (x - 12) + (y - 11) * (y - 11) + (z - 10) * (z - 10)) /
                           60.0);
  };
  const StructuredGrid g = quantizedGrid({25, 23, 21}, 1.0, f);
  const Model interpolating = encodeStructured(g, EncodeOptions{});
  const Model dequantized = encodeStructured(g, dequantizing(0.0));
  double eInterp = 0.0, eDequant = 0.0;
  int n = 0;
  for (double x = 1.0; x < 24.0; x += 0.77)
    for (double y = 1.0; y < 22.0; y += 0.83)
      for (double z = 1.0; z < 20.0; z += 0.91, ++n) {
        const Vec3d u(x / 24.0, y / 22.0, z / 20.0);
        eInterp += std::pow(interpolating.spline().value(u) - f(x, y, z), 2);
        eDequant += std::pow(dequantized.spline().value(u) - f(x, y, z), 2);
      }
  EXPECT_LT(std::sqrt(eDequant / n), 0.8 * std::sqrt(eInterp / n))
      << "rms " << std::sqrt(eDequant / n) << " against " << std::sqrt(eInterp / n);
}

TEST(Dequantize, StepsThatDoNotDescribeTheDataAreClearErrors) {
  const StructuredGrid g = quantizedGrid({8, 8, 8}, 1.0, [](double x, double, double) { return x; });
  for (const double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_THROW(encodeStructured(g, dequantizing(bad)), Error) << bad;
  // Samples that are not multiples of the step.
  EXPECT_THROW(encodeStructured(g, dequantizing(0.3)), Error);
  // Float samples need their step.
  StructuredGrid floats = g;
  floats.sampleType = "float32";
  EXPECT_THROW(encodeStructured(floats, dequantizing(0.0)), Error);
  // Combinations it does not take.
  EncodeOptions adaptive = dequantizing(0.0);
  adaptive.adaptive = AdaptiveOptions{};
  EXPECT_THROW(encodeStructured(g, adaptive), Error);
  EncodeOptions automatic = dequantizing(0.0);
  automatic.autoSmoothing = true;
  EXPECT_THROW(encodeStructured(g, automatic), Error);
}

}  // namespace
}  // namespace mfadvr
