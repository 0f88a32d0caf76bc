#include "core/analytic/BuiltinFunction.h"

#include <gtest/gtest.h>

#include <random>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

TEST(BuiltinFunction, GradientsMatchFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (const std::string& name : builtinNames()) {
    const auto f = makeBuiltin(name);
    for (int t = 0; t < 300; ++t) {
      const Vec3d x(uni(rng), uni(rng), uni(rng));
      Vec3d g;
      EXPECT_DOUBLE_EQ(f->valueGradient(x, g), f->value(x));
      const double h = 1e-6;
      for (int a = 0; a < 3; ++a) {
        Vec3d lo = x, hi = x;
        lo[a] -= h;
        hi[a] += h;
        const double fd = (f->value(hi) - f->value(lo)) / (2 * h);
        EXPECT_NEAR(g[a], fd, 1e-5 * (1 + std::abs(fd))) << name << " axis " << a;
      }
    }
    // The axis of Marschner-Lobb (r = 0) is a removable singularity of the formula.
    Vec3d g;
    f->valueGradient(Vec3d(0, 0, 0.3), g);
    EXPECT_TRUE(g.allFinite()) << name;
  }
}

TEST(BuiltinFunction, KnownValues) {
  const auto ml = makeBuiltin("marschner-lobb");
  // At the origin: r = 0, rho = cos(2 pi 6) = 1: (1 - 0 + 0.25 * 2) / 2.5 = 0.6.
  EXPECT_NEAR(ml->value(Vec3d::Zero()), 0.6, 1e-12);
  const auto beam = makeBuiltin("gaussian-beam");
  EXPECT_NEAR(beam->value(Vec3d::Zero()), 255.0, 1e-12);
  // At a corner l = 1: 255 exp(-1 / (2/9)) = 255 exp(-4.5).
  EXPECT_NEAR(beam->value(Vec3d::Ones()), 255.0 * std::exp(-4.5), 1e-9);
  const auto beams = makeBuiltin("gaussian-beams");
  EXPECT_NEAR(beams->value(Vec3d(-0.5, -0.5, 0)), 255.0, 0.5);      // largest beam
  EXPECT_NEAR(beams->value(Vec3d(0.8125, 0.8125, 0)), 255.0, 0.5);  // smallest beam
  // soft-and-sharp: inside the ball 30 + 180 (the blob is 0.85 away: exp(-7.5) of 12), on the
  // blob's centre 30 + 12 (the ball's edge is 0.5 away: H ~ exp(-33)), background 30 + 4 sin.
  const auto scan = makeBuiltin("soft-and-sharp");
  EXPECT_NEAR(scan->value(Vec3d(-0.35, 0, 0)), 210.0, 0.01);
  EXPECT_NEAR(scan->value(Vec3d(0.5, 0, 0.05)), 42.0, 1e-9);
  EXPECT_NEAR(scan->value(Vec3d(0.5, 1.0, 0.05)),
              30.0 + 12.0 * std::exp(-1.0 / (2 * 0.22 * 0.22)) + 4.0 * std::sin(5.6), 1e-9);
}

TEST(BuiltinFunction, SpecParsing) {
  EXPECT_EQ(parseBuiltinSpec("builtin:marschner-lobb").dims, (Index3{41, 41, 41}));
  EXPECT_EQ(parseBuiltinSpec("builtin:gaussian-beam").dims, (Index3{64, 64, 64}));
  EXPECT_EQ(parseBuiltinSpec("builtin:gaussian-beams").dims, (Index3{128, 128, 128}));
  EXPECT_EQ(parseBuiltinSpec("builtin:gaussian-beam:16").dims, (Index3{16, 16, 16}));
  EXPECT_EQ(parseBuiltinSpec("builtin:gaussian-beam:8x9x10").dims, (Index3{8, 9, 10}));
  for (const char* bad :
       {"builtin:", "builtin:nope", "builtin:gaussian-beam:1", "builtin:gaussian-beam:8x9",
        "builtin:gaussian-beam:99999999", "builtin:gaussian-beam:8x", "builtin:gaussian-beam:-4"})
    EXPECT_THROW(parseBuiltinSpec(bad), Error) << bad;
}

TEST(BuiltinFunction, SamplingCoversTheDomain) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:5x6x7");
  EXPECT_EQ(g.dims, (Index3{5, 6, 7}));
  EXPECT_EQ(g.boxMin(), Vec3d::Constant(-1));
  EXPECT_NEAR((g.boxMax() - Vec3d::Constant(1)).norm(), 0.0, 1e-15);
  EXPECT_EQ(g.at(0, 0, 0),
            static_cast<float>(makeBuiltin("marschner-lobb")->value(Vec3d::Constant(-1))));
  EXPECT_EQ(g.inputBytes, 5 * 6 * 7 * 8);
  EXPECT_NO_THROW(g.validate());
}

}  // namespace
}  // namespace mfadvr
