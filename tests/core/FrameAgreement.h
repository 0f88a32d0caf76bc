#pragma once
// Two renders of one frame that must agree exactly: the same image bit for bit and the same
// counters (used where two paths of the renderer are claimed to compute the same thing), and
// the reference render those paths are held to.
#include <gtest/gtest.h>

#include <cmath>

#include "core/image/Image.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/render/RenderSettings.h"

namespace mfadvr::test {

// ulps > 0: channels may differ by that many float steps (counters still exactly).
inline void expectSameFrame(const Image& a, const RenderStats& aStats, const Image& b,
                            const RenderStats& bStats, int render, int ulps = 0) {
  if (ulps == 0) {
    EXPECT_EQ(a.rgba, b.rgba) << "render " << render;
  } else {
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    for (size_t i = 0; i < a.rgba.size(); ++i) {
      float x = a.rgba[i];
      for (int u = 0; u < ulps && x < b.rgba[i]; ++u) x = std::nextafter(x, b.rgba[i]);
      for (int u = 0; u < ulps && x > b.rgba[i]; ++u) x = std::nextafter(x, b.rgba[i]);
      ASSERT_EQ(x, b.rgba[i]) << "render " << render << ", float " << i << ": " << a.rgba[i]
                              << " vs " << b.rgba[i];
    }
  }
  EXPECT_EQ(aStats.samples, bStats.samples) << "render " << render;
  EXPECT_EQ(aStats.skipped, bStats.skipped) << "render " << render;
  EXPECT_EQ(aStats.terminated, bStats.terminated) << "render " << render;
  EXPECT_EQ(aStats.raysHit, bStats.raysHit) << "render " << render;
}

// Variation `variant` (0..3) of a small frame, for two paths that must agree: 0 an image `oddWidth`
// wide (other variations 48), 1 steps aligned to the camera, 2 a parallel projection, 3 ray ends
// on every third pixel (some before the box).
inline void varyFrame(RenderSettings& s, int variant, int oddWidth) {
  s.width = variant == 0 ? oddWidth : 48;
  s.height = 36;
  if (variant == 1) s.alignSamplesToCamera = true;
  if (variant == 2) {
    s.camera.parallelProjection = true;
    s.camera.parallelScale = 1.2;
    s.camera.validate();
  }
  if (variant == 3) {
    s.rayEnd.assign(std::size_t(s.width) * s.height, INFINITY);
    for (std::size_t i = 0; i < s.rayEnd.size(); i += 3) s.rayEnd[i] = i % 2 ? 2.5f : 0.1f;
  }
}

// The frame one ray at a time (integrateRay per pixel), with the sampler renderModelView would
// use: what the renderer's faster paths (ray packets, the interleaved march) must reproduce.
// FrameAgreement.cpp: its instantiation of every loop is compiled once, not in every test
// source that uses it. The tests hold models of degree 1..3 (and mixed degrees) to it, so only
// those degrees get loops of their own (kReferenceMaxDegree); a model of one higher degree is
// refused (std::invalid_argument), not rendered through another path than the renderer's.
inline constexpr int kReferenceMaxDegree = kMaxUnrolledDegree < 3 ? kMaxUnrolledDegree : 3;
void requireReferenceDegree(const ModelView& view);
Image renderRayByRay(const RenderSettings& s, const ModelRenderSetup& setup, RenderStats& stats);

// renderModelView's frame of `setup` against renderRayByRay's, image and counters; returns the
// ray-by-ray counters.
inline RenderStats expectFrameOfRayByRay(const RenderSettings& s, const ModelRenderSetup& setup,
                                         int render, int ulps = 0) {
  RenderStats frameStats, rayStats;
  const Image frame = renderModelView(s, setup.params(), setup.view(), &frameStats);
  const Image rays = renderRayByRay(s, setup, rayStats);
  expectSameFrame(frame, frameStats, rays, rayStats, render, ulps);
  return rayStats;
}

}  // namespace mfadvr::test
