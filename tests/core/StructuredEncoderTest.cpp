#include "core/encode/StructuredEncoder.h"

#include <gtest/gtest.h>
#include <tbb/info.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/analytic/BuiltinFunction.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

StructuredFitOptions fitOptions(Degree3 p, Index3 n = {0, 0, 0}) {
  StructuredFitOptions o;
  o.degree = p;
  o.controlCounts = n;
  return o;
}

// n = N interpolates: the stored model reproduces every sample up to float32 rounding.
TEST(StructuredEncoder, InterpolatesWhenCountsEqualSamples) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:21x17x13");
  for (int p = 1; p <= 4; ++p) {
    FitReport r;
    const Model m = fitStructured(g, fitOptions({p, p, p}), &r);
    EXPECT_EQ(r.controlCounts, g.dims);
    EXPECT_LT(r.maxRelativeError(), 1e-5) << "p=" << p;
    for (std::int64_t k = 0; k < g.dims[2]; k += 3)
      for (std::int64_t j = 0; j < g.dims[1]; j += 2)
        for (std::int64_t i = 0; i < g.dims[0]; ++i)
          EXPECT_NEAR(m.value(g.position(i, j, k)), g.at(i, j, k), 1e-5);
  }
}

// The memory estimate: for an interpolating fit of a large grid, 4 bytes per sample of input and
// 4 for the float coefficient array the passes share (plus each thread's plane of work), or the
// control points and one z slab of the error evaluation; less with fewer control points.
TEST(StructuredEncoder, PeakMemoryEstimate) {
  const Index3 dims{512, 512, 512};
  const double samples = 512.0 * 512 * 512;
  const double full = static_cast<double>(structuredFitPeakBytes(dims, dims));
  const double threads = tbb::info::default_concurrency();
  const double perThreadPlane = 8.0 * 4 * 512 * 512 / samples;
  EXPECT_NEAR(full / samples, 4.0 + std::max(4.0 + threads * perThreadPlane, 4.0 + 16.0 * 16 / 512),
              1e-9);  // slabs of 16 planes
  // Fewer control points: less beyond the samples.
  const double half = static_cast<double>(structuredFitPeakBytes(dims, {256, 256, 256}));
  EXPECT_LT(half - 4.0 * samples, 0.75 * (full - 4.0 * samples));
}

TEST(StructuredEncoder, ReportIsConsistent) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:gaussian-beam:32x24x16");
  FitReport r;
  const Model m = fitStructured(g, fitOptions({3, 2, 3}, {16, 12, 8}), &r);
  EXPECT_EQ(r.samples, (Index3{32, 24, 16}));
  EXPECT_EQ(r.degree, (Degree3{3, 2, 3}));
  EXPECT_EQ(m.spline().counts(), (Index3{16, 12, 8}));
  EXPECT_EQ(r.modelBytes, static_cast<std::int64_t>(serializeModel(m).size()));
  EXPECT_EQ(r.inputBytes, 32 * 24 * 16 * 8);
  EXPECT_NEAR(r.compressionRatio(), double(r.inputBytes) / double(r.modelBytes), 1e-12);
  EXPECT_GT(r.compressionRatio(), 10.0);
  EXPECT_GT(r.maxError, 0.0);
  EXPECT_LE(r.rmsError, r.maxError);
  EXPECT_NEAR(r.maxRelativeError(), r.maxError / (r.valueMax - r.valueMin), 1e-15);
  // The report's max error is the true max over the samples.
  double maxErr = 0.0;
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i)
        maxErr = std::max(maxErr, std::abs(m.value(g.position(i, j, k)) - g.at(i, j, k)));
  EXPECT_NEAR(maxErr, r.maxError, 1e-4 * r.valueRange());
  EXPECT_EQ(m.domain().min, Vec3d::Constant(-1));
  EXPECT_EQ(m.domain().max, Vec3d::Constant(1));
  EXPECT_EQ(m.provenance().source, g.source);
}

// On a smooth function the fit error falls as control points are added (paper Fig. 10 trend).
TEST(StructuredEncoder, MoreControlPointsFitBetter) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:gaussian-beam:40");
  double last = std::numeric_limits<double>::infinity();
  for (std::int64_t n : {6, 10, 20, 40}) {
    FitReport r;
    fitStructured(g, fitOptions({3, 3, 3}, {n, n, n}), &r);
    EXPECT_LT(r.rmsError, last) << "n=" << n;
    last = r.rmsError;
  }
}

TEST(StructuredEncoder, ClearErrorsForBadOptions) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:gaussian-beam:8x8x5");
  auto message = [&](StructuredFitOptions o) {
    try {
      fitStructured(g, o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(fitOptions({3, 3, 3}, {9, 8, 5})).find("exceed"), std::string::npos);
  EXPECT_NE(message(fitOptions({3, 3, 3}, {3, 8, 5})).find("too few"), std::string::npos);
  EXPECT_NE(message(fitOptions({0, 3, 3})).find("degree 0"), std::string::npos);
  EXPECT_NE(message(fitOptions({3, 3, 8})).find("degree 8"), std::string::npos);
  EXPECT_NE(message(fitOptions({3, 3, 5})).find("lower the degree"), std::string::npos);

  StructuredGrid flat = g;
  flat.dims = {8, 8, 1};
  flat.values.resize(64);
  EXPECT_NE(
      [&] {
        try {
          fitStructured(flat, fitOptions({1, 1, 1}));
        } catch (const Error& e) {
          return std::string(e.what());
        }
        return std::string();
      }()
          .find("at least 2"),
      std::string::npos);

  StructuredGrid nan = g;
  nan.values[17] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(fitStructured(nan, fitOptions({2, 2, 2})), Error);
  StructuredGrid inf = g;
  inf.values[3] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(fitStructured(inf, fitOptions({2, 2, 2})), Error);
}

TEST(StructuredEncoder, ConstantDataFitsExactly) {
  StructuredGrid g;
  g.dims = {6, 5, 4};
  g.values.assign(120, 42.0);
  FitReport r;
  const Model m = fitStructured(g, fitOptions({2, 2, 2}, {4, 3, 3}), &r);
  EXPECT_LT(r.maxError, 1e-9);
  EXPECT_EQ(r.maxRelativeError(), r.maxError);  // zero range: relative falls back to absolute
  EXPECT_NEAR(m.value(Vec3d(2.5, 1.5, 1.0)), 42.0f, 1e-5);
}

// Physical gradients come out of the model in physical units (parametric / extent), so they
// match the analytic gradients of the built-ins, and converge like a cubic as the grid refines.
double maxGradientError(const std::string& name, int n, double* maxNorm) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:" + name + ":" + std::to_string(n));
  const auto f = makeBuiltin(name);
  const Model m = fitStructured(g, fitOptions({3, 3, 3}));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> uni(-0.9, 0.9);
  double maxDiff = 0.0;
  *maxNorm = 0.0;
  for (int t = 0; t < 500; ++t) {
    const Vec3d x(uni(rng), uni(rng), uni(rng));
    Vec3d truth;
    f->valueGradient(x, truth);
    *maxNorm = std::max(*maxNorm, truth.norm());
    maxDiff = std::max(maxDiff, (m.valueGradient(x).gradient.cast<double>() - truth).norm());
  }
  return maxDiff;
}

TEST(StructuredEncoder, GradientsMatchBuiltinAnalyticGradients) {
  double norm = 0.0;
  const double beam = maxGradientError("gaussian-beam", 40, &norm);
  EXPECT_LT(beam, 2e-3 * norm);
  // Marschner-Lobb is the hard case: check the cubic convergence rate instead of a level.
  const double coarse = maxGradientError("marschner-lobb", 48, &norm);
  const double fine = maxGradientError("marschner-lobb", 96, &norm);
  EXPECT_LT(fine, coarse / 6.0);
  EXPECT_LT(fine, 0.03 * norm);
}

// Anisotropic boxes: stretching the grid by s on an axis divides that partial by s.
TEST(StructuredEncoder, PhysicalDerivativesScaleWithExtent) {
  StructuredGrid g = sampleBuiltinSpec("builtin:gaussian-beam:20");
  StructuredGrid h = g;
  h.spacing = Vec3d(g.spacing[0] * 2.0, g.spacing[1], g.spacing[2] * 0.5);
  h.origin = Vec3d(g.origin[0] * 2.0, g.origin[1], g.origin[2] * 0.5);
  const Model a = fitStructured(g, fitOptions({3, 3, 3}));
  const Model b = fitStructured(h, fitOptions({3, 3, 3}));
  const Vec3d x(0.3, -0.2, 0.1);
  const Vec3d y(0.6, -0.2, 0.05);
  const ValueGradient ga = a.valueGradient(x), gb = b.valueGradient(y);
  EXPECT_NEAR(ga.value, gb.value, 1e-3);
  EXPECT_NEAR(gb.gradient[0], ga.gradient[0] / 2.0, 1e-3 * std::abs(ga.gradient[0]) + 1e-4);
  EXPECT_NEAR(gb.gradient[1], ga.gradient[1], 1e-3 * std::abs(ga.gradient[1]) + 1e-4);
  EXPECT_NEAR(gb.gradient[2], ga.gradient[2] * 2.0, 1e-3 * std::abs(ga.gradient[2]) + 1e-4);
}

}  // namespace
}  // namespace mfadvr
