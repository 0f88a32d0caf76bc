// sampleMethod: each reconstruction's value and gradient at points, as the ray caster samples them.
#include <gtest/gtest.h>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/Encoder.h"
#include "core/render/ReconstructionMethod.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

TEST(SampleMethod, EachMethodReproducesALinearFieldAndTheTruthIsTheFunction) {
  // F = 2x - y + 3z + 1 sampled on 9^3 points: trilinear, tricubic and an interpolating model all
  // reproduce a linear field, value and gradient, between the samples (away from the boundary
  // cells, where the tricubic filter takes its derivatives from padding).
  StructuredGrid grid = sampleBuiltin(*makeBuiltin("gaussian-beam"), {9, 9, 9});
  for (std::int64_t k = 0; k < 9; ++k)
    for (std::int64_t j = 0; j < 9; ++j)
      for (std::int64_t i = 0; i < 9; ++i) {
        const Vec3d p = grid.position(i, j, k);
        grid.at(i, j, k) = static_cast<float>(2 * p[0] - p[1] + 3 * p[2] + 1);
      }
  const Model model = encodeStructured(grid, EncodeOptions{});
  const auto beam = makeBuiltin("gaussian-beam");
  SceneData scene;
  scene.grid = &grid;
  scene.model = &model;
  scene.truth = beam.get();
  const std::vector<Vec3d> points = {{0.1, -0.33, 0.71}, {-0.6, 0.05, 0.2}, {0.0, 0.0, 0.0}};
  for (ReconstructionMethod m : {ReconstructionMethod::Trilinear, ReconstructionMethod::Tricubic,
                                 ReconstructionMethod::Mfa}) {
    const auto got = sampleMethod(scene, m, points);
    ASSERT_EQ(got.size(), points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec3d& p = points[i];
      EXPECT_NEAR(got[i].value, 2 * p[0] - p[1] + 3 * p[2] + 1, 1e-4) << methodName(m);
      EXPECT_NEAR(got[i].gradient[0], 2.0, 1e-3) << methodName(m);
      EXPECT_NEAR(got[i].gradient[1], -1.0, 1e-3) << methodName(m);
      EXPECT_NEAR(got[i].gradient[2], 3.0, 1e-3) << methodName(m);
    }
  }
  const auto truth = sampleMethod(scene, ReconstructionMethod::Truth, points);
  for (size_t i = 0; i < points.size(); ++i) {
    Vec3d g;
    EXPECT_NEAR(truth[i].value, beam->valueGradient(points[i], g), 1e-3);
    EXPECT_NEAR((truth[i].gradient.cast<double>() - g).norm(), 0.0, 1e-3 * (1 + g.norm()));
  }
}

TEST(SampleMethod, AMethodWithoutItsDataIsAClearError) {
  SceneData empty;
  EXPECT_THROW(sampleMethod(empty, ReconstructionMethod::Trilinear, {{0, 0, 0}}), Error);
  EXPECT_THROW(sampleMethod(empty, ReconstructionMethod::Mfa, {{0, 0, 0}}), Error);
  EXPECT_THROW(sampleMethod(empty, ReconstructionMethod::Truth, {{0, 0, 0}}), Error);
}

}  // namespace
}  // namespace mfadvr
