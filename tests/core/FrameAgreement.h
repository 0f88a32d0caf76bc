#pragma once
// Two renders of one frame that must agree exactly: the same image bit for bit and the same
// counters (used where two paths of the renderer are claimed to compute the same thing).
#include <gtest/gtest.h>

#include "core/image/Image.h"
#include "core/render/RenderSettings.h"

namespace mfadvr::test {

inline void expectSameFrame(const Image& a, const RenderStats& aStats, const Image& b,
                            const RenderStats& bStats, int render) {
  EXPECT_EQ(a.rgba, b.rgba) << "render " << render;
  EXPECT_EQ(aStats.samples, bStats.samples) << "render " << render;
  EXPECT_EQ(aStats.skipped, bStats.skipped) << "render " << render;
  EXPECT_EQ(aStats.terminated, bStats.terminated) << "render " << render;
  EXPECT_EQ(aStats.raysHit, bStats.raysHit) << "render " << render;
}

}  // namespace mfadvr::test
