// Smoothing fits of grids: the roughness penalty, the penalized separable fit and the automatic
// choice of its weight (core/spline/DerivativePenalty.h, StructuredEncoder.h, SmoothingChoice.h).
#include <gtest/gtest.h>

#include "TestSupport.h"

#include <cmath>
#include <limits>
#include <random>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/Encoder.h"
#include "core/encode/KnotPlacement.h"
#include "core/spline/DerivativePenalty.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// Control points of u^q / q! on `kv` (degree p >= q): the blossom of the monomial, the
// elementary symmetric polynomial of degree q of u_{i+1} .. u_{i+p} over C(p, q) q!.
std::vector<double> monomialControlPoints(const KnotVector& kv, int q) {
  const int p = kv.degree(), n = kv.controlCount();
  std::vector<double> c(static_cast<size_t>(n));
  double binom = 1.0, factorial = 1.0;
  for (int k = 1; k <= q; ++k) {
    binom = binom * (p - k + 1) / k;
    factorial *= k;
  }
  for (int i = 0; i < n; ++i) {
    std::vector<double> e(static_cast<size_t>(q + 1), 0.0);
    e[0] = 1.0;
    for (int j = 1; j <= p; ++j) {
      const double u = kv.knots()[static_cast<size_t>(i + j)];
      for (int k = q; k >= 1; --k) e[static_cast<size_t>(k)] += u * e[static_cast<size_t>(k - 1)];
    }
    c[static_cast<size_t>(i)] = e[static_cast<size_t>(q)] / (binom * factorial);
  }
  return c;
}

double penaltyOf(const DerivativePenalty& d, const std::vector<double>& c) {
  double sum = 0.0;
  const int w = d.order + 1;
  for (int r = 0; r < d.rows(); ++r) {
    double v = 0.0;
    for (int e = 0; e < w; ++e)
      v += d.weights[static_cast<size_t>(r * w + e)] *
           c[static_cast<size_t>(d.first[static_cast<size_t>(r)] + e)];
    sum += v * v;
  }
  return sum;
}

// Uniform knots and the fitted placement of a grid (end spans differ from the interior ones).
std::vector<KnotVector> knotVectorsToTry(int p) {
  return {KnotVector::clampedUniform(p, p + 9), knotsForSamples(p, p + 7, 40),
          knotsForSamples(p, 23, 31)};
}

TEST(DerivativePenalty, PolynomialsBelowTheOrderCarryNoPenalty) {
  for (int p = 1; p <= 5; ++p)
    for (const KnotVector& kv : knotVectorsToTry(p))
      for (int q = 1; q <= p + 1; ++q) {
        const DerivativePenalty d = derivativePenalty(kv, q);
        ASSERT_GT(d.rows(), 0);
        for (int k = 0; k < q && k <= p; ++k)
          EXPECT_LT(penaltyOf(d, monomialControlPoints(kv, k)), 1e-20)
              << "p=" << p << " q=" << q << " monomial degree " << k;
      }
}

// With s = u^q / q!, the q-th derivative is 1 everywhere: h^(2q) times the integral of 1, exactly
// (the lumped masses of a constant sum to its integral).
TEST(DerivativePenalty, MeasuresTheIntegralOfTheSquaredDerivative) {
  for (int p = 1; p <= 5; ++p)
    for (const KnotVector& kv : knotVectorsToTry(p))
      for (int q = 1; q <= p; ++q) {
        const double h = 1.0 / (kv.controlCount() - p);
        const double expected = std::pow(h, 2 * q);
        EXPECT_NEAR(penaltyOf(derivativePenalty(kv, q), monomialControlPoints(kv, q)), expected,
                    1e-9 * expected)
            << "p=" << p << " q=" << q;
      }
}

TEST(DerivativePenalty, OrderAboveTheDegreeSumsJumpsOfTheLastDerivative) {
  // s = u^3 / 6 - (u - 1/2)_+^3 / 6 on the knots 0 0 0 0 .5 1 1 1 1: its third derivative is 1,
  // then 0. The truncated power vanishes on the first span, so its control points are
  // (0, 0, 0, 0, 1/48) (the last one its value at 1).
  const KnotVector kv = KnotVector::clampedUniform(3, 5);
  std::vector<double> c = monomialControlPoints(kv, 3);
  c[4] -= 1.0 / 48.0;
  const double h = 0.5, jump = 1.0, meanSpan = 0.5;
  EXPECT_NEAR(penaltyOf(derivativePenalty(kv, 4), c), std::pow(h, 8) * jump * jump / meanSpan,
              1e-12);
  EXPECT_THROW(derivativePenalty(kv, 5), Error);
  EXPECT_THROW(derivativePenalty(kv, 0), Error);
}

double polynomial3(const Vec3d& x) {
  return 0.3 + x[0] - 0.5 * x[1] * x[1] * x[0] + 0.25 * x[2] * x[2] * x[2] -
         0.2 * x[0] * x[1] * x[2] + 0.1 * x[0] * x[0] * x[0] * x[1] * x[1];
}

StructuredGrid polynomialGrid(const Index3& dims) {
  StructuredGrid g;
  g.dims = dims;
  g.origin = Vec3d::Constant(-1.0);
  for (int a = 0; a < 3; ++a) g.spacing[a] = 2.0 / static_cast<double>(dims[a] - 1);
  g.values.resize(static_cast<size_t>(g.sampleCount()));
  for (std::int64_t k = 0; k < dims[2]; ++k)
    for (std::int64_t j = 0; j < dims[1]; ++j)
      for (std::int64_t i = 0; i < dims[0]; ++i) g.at(i, j, k) = polynomial3(g.position(i, j, k));
  g.sampleType = "float64";
  return g;
}

// Polynomials of degree <= p per axis are not biased, however strong the smoothing.
TEST(GridSmoothing, ReproducesPolynomialsOfTheModelDegree) {
  const StructuredGrid g = polynomialGrid({19, 17, 15});
  for (double lambda : {1e-3, 1.0, 1e3})
    for (const Index3& n : {Index3{19, 17, 15}, Index3{9, 8, 7}}) {
      StructuredFitOptions o;
      o.controlCounts = n;
      o.smoothing = lambda;
      FitReport r;
      const Model m = fitStructured(g, o, &r);
      EXPECT_LT(r.maxError, 2e-6) << "lambda " << lambda << " n " << n[0];
      EXPECT_DOUBLE_EQ(r.smoothing, lambda);
      EXPECT_DOUBLE_EQ(m.provenance().smoothing, lambda);
      EXPECT_EQ(m.provenance().encoder, "structured-smoothing");
    }
}

TEST(GridSmoothing, ZeroIsThePlainFitBitForBit) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:23x19x17");
  for (const Index3& n : {Index3{0, 0, 0}, Index3{15, 12, 11}}) {
    StructuredFitOptions plain;
    plain.controlCounts = n;
    StructuredFitOptions zero = plain;
    zero.smoothing = 0.0;
    const Model a = fitStructured(g, plain), b = fitStructured(g, zero);
    EXPECT_EQ(test::values(a.spline().controlPoints()), test::values(b.spline().controlPoints()));
    EXPECT_EQ(b.provenance().encoder, "structured-least-squares");
    // Any positive weight changes the interpolating fit, and more smoothing moves it further
    // from the samples.
    zero.smoothing = 1e-4;
    FitReport weak, strong;
    fitStructured(g, zero, &weak);
    zero.smoothing = 1e-1;
    fitStructured(g, zero, &strong);
    EXPECT_GT(weak.rmsError, 1e-7);
    EXPECT_GT(strong.rmsError, weak.rmsError);
  }
}

TEST(GridSmoothing, BadWeightsAreClearErrors) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:9");
  for (double bad : {-1e-3, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity(), 2 * kMaxGridSmoothing}) {
    StructuredFitOptions o;
    o.smoothing = bad;
    try {
      fitStructured(g, o);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("smoothing weight"), std::string::npos) << e.what();
    }
    EncodeOptions eo;
    eo.smoothing = bad;
    EXPECT_THROW(encodeStructured(g, eo), Error);
  }
  EncodeOptions both;
  both.smoothing = 0.1;
  both.autoSmoothing = true;
  EXPECT_THROW(encodeStructured(g, both), Error);
}

// The hat matrix's trace: the control count without smoothing, the polynomials of degree p
// ((p+1)^3 of them) under very strong smoothing.
TEST(GridSmoothing, EffectiveParametersRunFromTheControlCountToThePolynomials) {
  const Index3 dims{30, 25, 20};
  std::array<KnotVector, 3> knots;
  for (int a = 0; a < 3; ++a) knots[a] = knotsForSamples(3, static_cast<int>(dims[a] - 6), dims[a]);
  EXPECT_NEAR(effectiveParameters(knots, dims, 0.0), 24.0 * 19 * 14, 1e-6 * 24 * 19 * 14);
  EXPECT_NEAR(effectiveParameters(knots, dims, kMaxGridSmoothing), 64.0, 0.5);
  double last = 24.0 * 19 * 14;
  for (double lambda : {1e-4, 1e-2, 1.0, 1e2}) {
    const double t = effectiveParameters(knots, dims, lambda);
    EXPECT_LT(t, last);
    last = t;
  }
}

StructuredGrid withNoise(StructuredGrid g, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, sigma);
  for (float& v : g.values) v = static_cast<float>(v + n(rng));
  return g;
}

double rmsAgainst(const Model& m, const StructuredGrid& clean) {
  return errorsOnGrid(m.spline(), clean).rms;
}

// A smooth field with noise: automatic smoothing finds a weight, estimates the noise level,
// and comes closer to the clean field than the interpolating model and plain least squares.
TEST(SmoothingChoice, ReducesNoiseAndEstimatesItsLevel) {
  const StructuredGrid clean = sampleBuiltinSpec("builtin:gaussian-beam:40");
  const double sigma = 0.03;
  const StructuredGrid noisy = withNoise(clean, sigma, 7);
  EncodeOptions o;
  o.autoSmoothing = true;
  FitReport r;
  const Model smooth = encodeStructured(noisy, o, &r);
  EXPECT_GT(r.smoothing, 0.0);
  EXPECT_NEAR(r.noiseEstimate, sigma, 0.2 * sigma);
  EXPECT_NE(r.smoothingNote.find("cross-validation"), std::string::npos);
  const Model interpolating = encodeStructured(noisy, EncodeOptions{});
  EncodeOptions lsq;
  lsq.controlCounts = {25, 25, 25};
  const Model fewer = encodeStructured(noisy, lsq);
  const double eSmooth = rmsAgainst(smooth, clean);
  EXPECT_LT(eSmooth, 0.5 * rmsAgainst(interpolating, clean));
  EXPECT_LT(eSmooth, rmsAgainst(fewer, clean));
}

// Noise-free smooth samples: the choice keeps the fit as accurate as the interpolating one.
TEST(SmoothingChoice, KeepsTheAccuracyOfCleanData) {
  const auto f = makeBuiltin("gaussian-beam");
  const StructuredGrid g = sampleBuiltin(*f, {33, 33, 33});
  EncodeOptions o;
  o.autoSmoothing = true;
  FitReport r;
  const Model smooth = encodeStructured(g, o, &r);
  const Model interpolating = encodeStructured(g, EncodeOptions{});
  // Against the function between the samples (a finer grid), not the samples themselves.
  const StructuredGrid fine = sampleBuiltin(*f, {65, 65, 65});
  const double eSmooth = rmsAgainst(smooth, fine), eInterp = rmsAgainst(interpolating, fine);
  EXPECT_LT(eSmooth, 1.2 * eInterp + 1e-6) << "lambda " << r.smoothing;
}

// Large grids are judged on bricks, with the same knot density: the choice comes out close to
// the whole grid's.
TEST(SmoothingChoice, BricksAgreeWithTheWholeGrid) {
  const StructuredGrid noisy = withNoise(sampleBuiltinSpec("builtin:gaussian-beam:56"), 0.05, 3);
  StructuredFitOptions fit;
  SmoothingSearch search;
  search.wholeGridSamples = 40 * 40 * 40;
  search.brickSamples = 24;
  const SmoothingChoice bricks = chooseSmoothing(noisy, fit, search);
  EXPECT_EQ(bricks.bricks, 8);
  EXPECT_EQ(bricks.samplesJudged, 8 * 24 * 24 * 24);
  EXPECT_NEAR(bricks.noiseRms, 0.05, 0.01);
  EXPECT_NE(bricks.note.find("8 bricks of 24^3 samples"), std::string::npos) << bricks.note;
  const SmoothingChoice whole = chooseSmoothing(noisy, fit);
  EXPECT_EQ(whole.bricks, 0);
  EXPECT_EQ(whole.samplesJudged, 56 * 56 * 56);
  EXPECT_LT(std::abs(std::log10(whole.lambda / bricks.lambda)), 0.51)
      << whole.lambda << " vs " << bricks.lambda;
}

// A smooth field quantized coarsely: GCV alone keeps the terraces (it takes them for signal);
// the floor raises lambda until the implied noise is the quantization's, which brings the
// model closer to the field than the interpolating one.
TEST(SmoothingChoice, QuantizationStepIsAFloorOnTheNoise) {
  const auto f = makeBuiltin("gaussian-beam");
  const StructuredGrid clean = sampleBuiltin(*f, {40, 40, 40});
  StructuredGrid quantized = clean;
  const double step = 1.0 / 32.0;
  for (float& v : quantized.values) v = static_cast<float>(step * std::round(v / step));
  StructuredFitOptions fit;
  SmoothingSearch search;
  const SmoothingChoice plain = chooseSmoothing(quantized, fit, search);
  search.quantizationStep = step;
  const SmoothingChoice floored = chooseSmoothing(quantized, fit, search);
  EXPECT_FALSE(plain.raisedToQuantization);
  EXPECT_LT(plain.noiseRms, step / std::sqrt(12.0));
  EXPECT_TRUE(floored.raisedToQuantization);
  EXPECT_GT(floored.lambda, plain.lambda);
  EXPECT_NEAR(floored.noiseRms, step / std::sqrt(12.0), 0.15 * step / std::sqrt(12.0));
  EXPECT_NE(floored.note.find("quantization floor"), std::string::npos);
  fit.smoothing = floored.lambda;
  const Model smooth = fitStructured(quantized, fit);
  fit.smoothing = 0.0;
  const Model interpolating = fitStructured(quantized, fit);
  const StructuredGrid fine = sampleBuiltin(*f, {79, 79, 79});
  EXPECT_LT(rmsAgainst(smooth, fine), rmsAgainst(interpolating, fine));
  search.quantizationStep = -1.0;
  EXPECT_THROW(chooseSmoothing(quantized, fit, search), Error);
}

}  // namespace
}  // namespace mfadvr
