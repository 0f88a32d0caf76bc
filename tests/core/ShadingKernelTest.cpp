// Blinn-Phong shading of one sample and of eight lanes (kernel/ShadingKernel.h): the lane form
// gives each lane what the one-sample form gives it, bit for bit, across the cases the formula
// selects between (no normal, back-facing normal, lights behind the surface, no highlight,
// whole and fractional specular powers); and the one-sample form gives the Blinn-Phong values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/render/Lighting.h"
#include "core/spline/SplineKernel.h"

namespace mfadvr {
namespace {

std::vector<Lighting> lightings() {
  std::vector<Lighting> all;
  all.emplace_back();  // the headlight alone, power 10
  Lighting several;
  several.specularPower = 7.5f;  // not a whole number: powf
  several.lights.push_back({Vec3d{1.0, 0.0, 0.0}, Vec3f{1.0f, 0.5f, 0.25f}, 0.8f});
  several.lights.push_back({Vec3d{0.0, 0.0, 1.0}, Vec3f{0.2f, 1.0f, 0.3f}, 1.5f});  // from behind
  all.push_back(several);
  Lighting noHeadlight;
  noHeadlight.headlight = false;
  noHeadlight.specularPower = 1.0f;
  noHeadlight.lights.push_back({Vec3d{-1.0, 2.0, 0.5}, Vec3f{1.0f, 1.0f, 1.0f}, 1.0f});
  all.push_back(noHeadlight);
  return all;
}

#if defined(MFADVR_KERNEL_VECTOR_LANES)
bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
#endif

TEST(ShadingKernel, LanesShadeAsOneSampleEachBitForBit) {
#if !defined(MFADVR_KERNEL_VECTOR_LANES)
  GTEST_SKIP() << "no SIMD lanes on this build";
#else
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), colour(0.0f, 1.0f);
  const Vec3d camera{0.3, -0.2, -1.0};
  int lanesChecked = 0, noNormal = 0;
  for (const Lighting& lighting : lightings()) {
    const ShadingParams params = makeShadingParams(lighting, camera);
    for (int round = 0; round < 200; ++round) {
      RayShading one[8];
      RayShadingOf<LaneVector8> lanes = {};
      LaneVector8 colors[3], grads[3], shaded[3];
      for (int l = 0; l < 8; ++l) {
        // Rays of a packet look in slightly different directions.
        const float dir[3] = {0.3f + 0.05f * unit(rng), -0.2f + 0.05f * unit(rng), -1.0f};
        prepareRayShading(params, dir, one[l]);
        for (int c = 0; c < 3; ++c) {
          lanes.toEye[c][l] = one[l].toEye[c];
          for (int i = 0; i < params.lightCount; ++i) lanes.half[i][c][l] = one[l].half[i][c];
          colors[c][l] = colour(rng);
          // Gradients of every size, some zero or too small for a normal.
          const int kind = (round + l) % 5;
          grads[c][l] = kind == 0 ? 0.0f : kind == 1 ? 1e-17f * unit(rng) : 1e3f * unit(rng);
        }
      }
      shadeSample(params, lanes, colors, grads, shaded);
      for (int l = 0; l < 8; ++l) {
        const float color[3] = {colors[0][l], colors[1][l], colors[2][l]};
        const float g[3] = {grads[0][l], grads[1][l], grads[2][l]};
        float out[3];
        shadeSample(params, one[l], color, g, out);
        for (int c = 0; c < 3; ++c)
          ASSERT_TRUE(sameBits(out[c], shaded[c][l]))
              << "lane " << l << " channel " << c << ": " << out[c] << " vs " << shaded[c][l];
        ++lanesChecked;
        if (!(g[0] * g[0] + g[1] * g[1] + g[2] * g[2] > 1e-30f)) ++noNormal;
      }
    }
  }
  EXPECT_EQ(lanesChecked, 3 * 200 * 8);
  EXPECT_GT(noNormal, 0);
  EXPECT_LT(noNormal, lanesChecked);
#endif
}

TEST(ShadingKernel, OneSampleGivesBlinnPhong) {
  Lighting lighting;  // headlight: the light comes from the eye
  const Vec3d camera{0.0, 0.0, -1.0};
  const ShadingParams params = makeShadingParams(lighting, camera);
  const float dir[3] = {0.0f, 0.0f, -1.0f};
  RayShading ray;
  prepareRayShading(params, dir, ray);
  const float color[3] = {0.5f, 0.25f, 1.0f};
  float out[3];

  // Facing the eye (and the light): n.l = n.h = 1.
  const float facing[3] = {0.0f, 0.0f, 4.0f};
  shadeSample(params, ray, color, facing, out);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(out[c], (lighting.ambient + lighting.diffuse) * color[c] + lighting.specular, 1e-6);

  // Two-sided: the opposite gradient shades the same.
  const float away[3] = {0.0f, 0.0f, -4.0f};
  float outAway[3];
  shadeSample(params, ray, color, away, outAway);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(outAway[c], out[c]);

  // At 60 degrees: n.l = n.h = 1/2.
  const float tilted[3] = {std::sqrt(3.0f), 0.0f, 1.0f};
  shadeSample(params, ray, color, tilted, out);
  const float highlight = lighting.specular * std::pow(0.5f, lighting.specularPower);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(out[c], (lighting.ambient + 0.5f * lighting.diffuse) * color[c] + highlight, 1e-6);

  // No normal: ambient and diffuse as if facing the light, no highlight.
  const float zero[3] = {0.0f, 0.0f, 0.0f};
  shadeSample(params, ray, color, zero, out);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(out[c], (lighting.ambient + lighting.diffuse) * color[c], 1e-6);
}

}  // namespace
}  // namespace mfadvr
