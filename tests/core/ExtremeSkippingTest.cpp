// Maximum and minimum intensity skipping (ExtremeBounds.h, SplineRaySampler::boundedAt) and
// additive skipping: the transfer function's transparent ends, the bytes' level searches, the
// bounds of every cell and block, and images bit-identical with skipping on and off (masked and
// unmasked models, several transfer functions) while far fewer samples are taken.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/field/ModelField.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/ExtremeBounds.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/spline/SplineKernel.h"

namespace mfadvr {
namespace {

const Model& gaussianBeam() {
  static const Model m = [] {
    const auto f = makeBuiltin("gaussian-beam");
    StructuredFitOptions o;
    o.controlCounts = {20, 24, 28};
    return fitStructured(sampleBuiltin(*f, {33, 33, 33}), o);
  }();
  return m;
}

const Model& maskedGaussianBeam() {
  static const Model m = [] {
    Model copy = gaussianBeam();
    copy.setMask(test::ballMask());
    return copy;
  }();
  return m;
}

TransferFunction tfWith(std::vector<OpacityPoint> opacity) {
  TransferFunction tf;
  tf.space = TfSpace::Normalized;
  tf.color = {{0.0, Vec3f(0.1f, 0.2f, 1.0f)}, {0.5, Vec3f(1, 1, 1)}, {1.0, Vec3f(1, 0.3f, 0.1f)}};
  tf.opacity = std::move(opacity);
  return tf;
}

std::vector<TransferFunction> testTransferFunctions() {
  return {
      tfWith({{0.0, 0.0f}, {1.0, 1.0f}}),                            // ramp from 0
      tfWith({{0.0, 0.0f}, {0.4, 0.0f}, {0.9, 1.0f}}),               // transparent below 0.4
      tfWith({{0.0, 0.9f}, {0.3, 0.5f}, {0.6, 0.0f}, {1.0, 0.0f}}),  // transparent above 0.6
      tfWith({{0.0, 0.0f}, {0.2, 0.0f}, {0.25, 0.7f}, {0.3, 0.0f}, {1.0, 0.0f}}),  // one band
      tfWith({{0.0, 0.6f}, {1.0, 0.6f}}),  // visible everywhere
      tfWith({{0.0, 0.0f}, {1.0, 0.0f}}),  // nothing visible
  };
}

RenderSettings settingsFor(const Model& m, const TransferFunction& tf, BlendMode blend) {
  RenderSettings s;
  s.width = 48;
  s.height = 36;
  s.camera.resetToBounds(m.domain().min, m.domain().max);
  s.camera.azimuth(25);
  s.camera.elevation(15);
  s.sampleDistance = 0.5 * m.dataSpacing().minCoeff();
  s.opacityUnitDistance = m.dataSpacing().minCoeff();
  s.transferFunction = tf.resolved(m.valueMin(), m.valueMax());
  s.blend = blend;
  s.background = Vec3f(0.1f, 0.1f, 0.15f);
  return s;
}

TEST(TransferFunctionTable, TransparentEndsBoundTheTransparentValues) {
  for (const TransferFunction& f : testTransferFunctions()) {
    const TransferFunction tf = f.resolved(-2.0, 3.0);
    const TransferFunctionTable table(tf, OpacityCorrection(1.0));
    const float upTo = table.transparentUpTo(), from = table.transparentFrom();
    // Every value at or below upTo (at or above from) is transparent; one table entry further
    // in is not (the search finds the end, not a value short of it).
    const float entry = 5.0f / (TransferFunctionTable::kEntries - 1);
    for (int i = 0; i <= 1000; ++i) {
      const float v = -4.0f + 8.0f * static_cast<float>(i) / 1000.0f;
      if (v <= upTo) {
        EXPECT_EQ(table.classify(v).alpha, 0.0f) << v;
      }
      if (v >= from) {
        EXPECT_EQ(table.classify(v).alpha, 0.0f) << v;
      }
    }
    if (std::isfinite(upTo)) {
      EXPECT_EQ(table.classify(upTo).alpha, 0.0f);
      EXPECT_GT(table.classify(upTo + 2.0f * entry).alpha, 0.0f);
    }
    if (std::isfinite(from)) {
      EXPECT_EQ(table.classify(from).alpha, 0.0f);
      EXPECT_GT(table.classify(from - 2.0f * entry).alpha, 0.0f);
    }
  }
  // The ends of the list above: none, a lower end, an upper end; everything transparent.
  auto ends = [](const TransferFunction& f) {
    const TransferFunctionTable t(f.resolved(0.0, 1.0), OpacityCorrection(1.0));
    return std::pair(t.transparentUpTo(), t.transparentFrom());
  };
  const std::vector<TransferFunction> tfs = testTransferFunctions();
  EXPECT_EQ(ends(tfs[4]), std::pair(-INFINITY, INFINITY));
  EXPECT_NEAR(ends(tfs[1]).first, 0.4f, 0.01f);
  EXPECT_EQ(ends(tfs[1]).second, INFINITY);
  EXPECT_EQ(ends(tfs[2]).first, -INFINITY);
  EXPECT_NEAR(ends(tfs[2]).second, 0.6f, 0.01f);
  EXPECT_EQ(ends(tfs[5]), std::pair(INFINITY, -INFINITY));
}

TEST(ExtremeBounds, LevelSearchesAgreeWithBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uni(-1.0f, 1.0f);
  std::vector<float> levels(kExtremeLevels);
  for (float& l : levels) l = uni(rng);
  std::sort(levels.begin(), levels.end());
  levels[3] = levels[4];  // a tie
  for (int t = 0; t < 2000; ++t) {
    const float v = t == 0 ? levels[3] : t == 1 ? -INFINITY : t == 2 ? INFINITY : 1.2f * uni(rng);
    int atMost = -1, atLeast = kExtremeLevels;
    for (int i = 0; i < kExtremeLevels; ++i)
      if (levels[i] <= v) atMost = i;
    for (int i = kExtremeLevels - 1; i >= 0; --i)
      if (levels[i] >= v) atLeast = i;
    EXPECT_EQ(upperByteAtMost(levels.data(), v), atMost) << v;
    EXPECT_EQ(lowerByteAtLeast(levels.data(), v), atLeast) << v;
  }
}

// Every value of a cell lies between the levels of its bytes, and every block's byte is the
// greatest (least) of its cells'.
TEST(ExtremeBounds, BoundEveryValueOfEveryCellAndBlock) {
  const Model& m = gaussianBeam();
  const SpanRanges& r = *m.spline().spanRanges();
  const SplineView v = m.spline().view();
  for (const bool bezier : {true, false}) {
    const ExtremeBounds b = buildExtremeBounds(v, r, bezier);
    ASSERT_EQ(b.upper.size(), static_cast<size_t>(r.cellCount()));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    int tight = 0;
    for (int t = 0; t < 20000; ++t) {
      const double u[3] = {uni(rng), uni(rng), uni(rng)};
      AxisLocation loc[3];
      locatePoint(v, u, loc);
      const std::int64_t cell =
          (loc[0].span - 3) +
          r.cells[0] * ((loc[1].span - 3) + std::int64_t(r.cells[1]) * (loc[2].span - 3));
      const float value = splineValue<3>(v, u);
      const int up = b.upper[static_cast<size_t>(cell)], down = b.lower[static_cast<size_t>(cell)];
      ASSERT_LE(value, b.upperLevels[up]);
      ASSERT_GE(value, b.lowerLevels[down]);
      if (up < kExtremeLevels - 1 && down > 0) ++tight;
    }
    EXPECT_EQ(tight, 20000);  // a finite model: every cell has finite bounds
    for (int l = 0; l < b.upperPyramid.levels; ++l) {
      const EmptyLevelView& L = b.upperPyramid.level[l];
      const int side = 2 << l;
      for (std::int64_t z = 0; z < r.cells[2]; ++z)
        for (std::int64_t y = 0; y < r.cells[1]; ++y)
          for (std::int64_t x = 0; x < r.cells[0]; ++x) {
            const size_t cell = static_cast<size_t>(x + r.cells[0] * (y + r.cells[1] * z));
            const size_t block = static_cast<size_t>(
                L.offset + x / side +
                L.count[0] * (y / side + std::int64_t(L.count[1]) * (z / side)));
            ASSERT_GE(b.upperPyramid.bytes[block], b.upper[cell]);
            ASSERT_LE(b.lowerPyramid.bytes[block], b.lower[cell]);
          }
    }
    EXPECT_GE(b.upperPyramid.levels, 5);  // 2^5 cells cover the grid's 25 cells along z
  }
}

void expectIdenticalWithAndWithoutSkipping(const Model& m) {
  int skippedSomewhere = 0;
  for (const BlendMode blend : {BlendMode::Maximum, BlendMode::Minimum, BlendMode::Additive})
    for (const TransferFunction& tf : testTransferFunctions())
      for (const bool cached : {false, true}) {
        RenderSettings s = settingsFor(m, tf, blend);
        s.depth = true;
        RenderStats on, off;
        EmptySpaceCache cache;
        const Image a = renderVolume(cached ? ModelField(m, &cache) : ModelField(m), s, &on);
        s.skipEmptySpace = false;
        const Image b = renderVolume(ModelField(m), s, &off);
        const std::string what = std::string(blendModeName(blend)) + (cached ? " cached" : "");
        EXPECT_EQ(a.rgba, b.rgba) << what;
        ASSERT_EQ(a.depth.size(), b.depth.size());
        for (size_t i = 0; i < a.depth.size(); ++i)
          ASSERT_TRUE(a.depth[i] == b.depth[i] ||
                      (std::isnan(a.depth[i]) && std::isnan(b.depth[i])))
              << what << " pixel " << i;
        EXPECT_EQ(off.skipped, 0);
        // Jumps over a masked model's steps count those outside the mask as skipped too.
        if (m.mask().empty()) {
          EXPECT_EQ(on.samples + on.skipped, off.samples) << what;
        } else {
          EXPECT_LE(on.samples, off.samples) << what;
        }
        if (on.skipped > 0) ++skippedSomewhere;
      }
  EXPECT_GE(skippedSomewhere, 20);  // the test has to exercise the skipping
}

TEST(ExtremeSkipping, ImagesAreBitIdenticalOnAnUnmaskedModel) {
  expectIdenticalWithAndWithoutSkipping(gaussianBeam());
}

TEST(ExtremeSkipping, ImagesAreBitIdenticalOnAMaskedModel) {
  expectIdenticalWithAndWithoutSkipping(maskedGaussianBeam());
}

// A beam along the volume: most cells lie far below its peak. With a transfer function
// transparent below 0.4 a maximum intensity ray passes over them from its start; with a ramp
// from 0 (no transparent low end) maximum intensity does not skip (ModelRenderSetup: it cost
// more than it saved on a dense field), minimum intensity does.
TEST(ExtremeSkipping, SkipsMostSamplesOfAPeakedField) {
  const Model& m = gaussianBeam();
  struct Case {
    BlendMode blend;
    int tf;
  };
  for (const Case c :
       {Case{BlendMode::Maximum, 0}, Case{BlendMode::Maximum, 1}, Case{BlendMode::Minimum, 0}}) {
    RenderSettings s = settingsFor(m, testTransferFunctions()[c.tf], c.blend);
    RenderStats on, off;
    renderVolume(ModelField(m), s, &on);
    s.skipEmptySpace = false;
    renderVolume(ModelField(m), s, &off);
    std::printf("%s, tf %d: %lld of %lld samples taken\n", blendModeName(c.blend), c.tf,
                static_cast<long long>(on.samples), static_cast<long long>(off.samples));
    if (c.blend == BlendMode::Maximum && c.tf == 0) {
      EXPECT_EQ(on.skipped, 0);
    } else {
      EXPECT_LT(on.samples, off.samples / 2) << blendModeName(c.blend) << " tf " << c.tf;
    }
  }
}

// Average renders count transparent values: nothing is skipped; nor in shaded renders, whose
// loops do not reduce with skipping.
TEST(ExtremeSkipping, AverageAndShadedReductionsSampleEveryStep) {
  const Model& m = gaussianBeam();
  RenderSettings s = settingsFor(m, testTransferFunctions()[1], BlendMode::Average);
  RenderStats stats;
  renderVolume(ModelField(m), s, &stats);
  EXPECT_EQ(stats.skipped, 0);
  EXPECT_GT(stats.samples, 0);
  s.blend = BlendMode::Maximum;
  s.shade = true;
  const ModelField field(m);
  EXPECT_FALSE(ModelRenderSetup(field, s).skipsExtremes());
  s.shade = false;
  EXPECT_TRUE(ModelRenderSetup(field, s).skipsExtremes());
}

TEST(ExtremeSkipping, CacheKeepsTheBoundsOfAModel) {
  const Model& m = gaussianBeam();
  EmptySpaceCache cache;
  const auto a = cache.extremeBounds(m.spline());
  const auto b = cache.extremeBounds(m.spline());
  EXPECT_EQ(a.get(), b.get());
}

}  // namespace
}  // namespace mfadvr
