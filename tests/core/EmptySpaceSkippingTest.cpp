// Exact empty-space skipping: the span ranges bound the spline, the table's transparency test
// agrees with classification, and images are bit-identical with skipping on and off (masked and
// unmasked models, shaded and not, several transfer functions), for any thread count. Also: the
// model's own render path against the generic field path (same rays, same function).
#include <gtest/gtest.h>

#include <random>
#include <type_traits>
#include <utility>
#include <vector>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/field/ModelField.h"
#include "core/image/ImageMetrics.h"
#include "core/model/BlockModelFile.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/render/ReconstructionMethod.h"
#include "core/render/kernel/SplineRaySampler.h"
#include "core/spline/SplineKernel.h"

namespace mfadvr {
namespace {

const Model& marschnerLobb() {
  static const Model m = [] {
    const auto f = makeBuiltin("marschner-lobb");
    StructuredFitOptions o;
    o.controlCounts = {24, 24, 24};
    return fitStructured(sampleBuiltin(*f, {33, 33, 33}), o);
  }();
  return m;
}

// The same model with a domain mask: a ball of nodes.
const Model& maskedMarschnerLobb() {
  static const Model m = [] {
    Model copy = marschnerLobb();
    copy.setMask(test::ballMask());
    return copy;
  }();
  return m;
}

TransferFunction tfWith(std::vector<OpacityPoint> opacity) {
  TransferFunction tf;
  tf.space = TfSpace::Data;
  tf.color = {
      {0.0, Vec3f(0.1f, 0.2f, 1.0f)}, {0.5, Vec3f(1, 1, 1)}, {1.0, Vec3f(1.0f, 0.3f, 0.1f)}};
  tf.opacity = std::move(opacity);
  return tf;
}

std::vector<TransferFunction> testTransferFunctions() {
  return {
      tfWith({{0.5, 0.0f}, {0.5, 0.8f}, {1.0, 0.8f}}),                             // step at 0.5
      tfWith({{0.0, 0.0f}, {0.6, 0.0f}, {0.9, 1.0f}}),                             // ramp from 0.6
      tfWith({{0.0, 0.0f}, {0.2, 0.0f}, {0.25, 0.7f}, {0.3, 0.0f}, {1.0, 0.0f}}),  // one band
      tfWith({{0.0, 0.0f}, {1.0, 1.0f}}),  // ramp from 0: only exact zeros are invisible
      tfWith({{0.0, 0.0f}, {1.0, 0.0f}}),  // nothing visible
  };
}

RenderSettings settingsFor(const Model& m, const TransferFunction& tf, bool shade) {
  RenderSettings s;
  s.width = 64;
  s.height = 48;
  s.camera.resetToBounds(m.domain().min, m.domain().max);
  s.camera.azimuth(25);
  s.camera.elevation(15);
  s.sampleDistance = 0.5 * m.dataSpacing().minCoeff();
  s.opacityUnitDistance = m.dataSpacing().minCoeff();
  s.transferFunction = tf;
  s.shade = shade;
  s.background = Vec3f(0.1f, 0.1f, 0.15f);
  return s;
}

// Every cell's bounds, x fastest, from one scanner going through the planes in order: the
// control points' ranges (SpanRangeScanner) or the Bezier ranges (BezierRangeScanner).
struct CellBounds {
  std::vector<float> lo, hi;
  double rounding = 0.0;  // Bezier bounds: their relative rounding bound
};
template <class Scanner = SpanRangeScanner>
CellBounds allCellBounds(const TensorBSpline& spline) {
  const SpanRanges& r = *spline.spanRanges();
  const std::int64_t plane = std::int64_t(r.cells[0]) * r.cells[1];
  CellBounds b;
  b.lo.resize(static_cast<size_t>(r.cellCount()));
  b.hi.resize(b.lo.size());
  Scanner scan(spline.view());
  if constexpr (std::is_same_v<Scanner, BezierRangeScanner>) b.rounding = scan.relativeRounding();
  for (int z = 0; z < r.cells[2]; ++z) scan.plane(z, &b.lo[z * plane], &b.hi[z * plane]);
  return b;
}

TEST(SpanRanges, BoundEveryValueOfTheCell) {
  const Model& m = marschnerLobb();
  const SpanRanges& r = *m.spline().spanRanges();
  const CellBounds b = allCellBounds(m.spline());
  const SplineView v = m.spline().view();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (int t = 0; t < 5000; ++t) {
    const double u[3] = {uni(rng), uni(rng), uni(rng)};
    AxisLocation loc[3];
    locatePoint(v, u, loc);
    const std::int64_t cell =
        (loc[0].span - 3) +
        r.cells[0] * ((loc[1].span - 3) + std::int64_t(r.cells[1]) * (loc[2].span - 3));
    const float value = splineValue<3>(v, u);
    const float lo = b.lo[static_cast<size_t>(cell)], hi = b.hi[static_cast<size_t>(cell)];
    const float pad = static_cast<float>(r.relativeRounding) * std::max(std::abs(lo), std::abs(hi));
    EXPECT_GE(value, lo - pad);
    EXPECT_LE(value, hi + pad);
  }
  EXPECT_GT(r.relativeRounding, 0.0);
  EXPECT_LT(r.relativeRounding, 1e-3);  // a bound, not a guess: it should stay small
}

// Each cell's bounds are the least and greatest of its (p+1)^3 control points, for mixed
// degrees and uneven counts (brute force against the separable sliding windows), whether a
// scanner starts at the first plane, in the middle, or jumps back and forth.
TEST(SpanRanges, AreTheControlPointRangeOfEachCell) {
  const int degree[3] = {1, 2, 3}, count[3] = {7, 6, 19};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uni(-5.0f, 5.0f);
  std::vector<float> ctrl(static_cast<size_t>(count[0] * count[1] * count[2]));
  for (float& c : ctrl) c = uni(rng);
  const TensorBSpline spline({KnotVector::clampedUniform(degree[0], count[0]),
                              KnotVector::clampedUniform(degree[1], count[1]),
                              KnotVector::clampedUniform(degree[2], count[2])},
                             ctrl);
  const SpanRanges& r = *spline.spanRanges();
  for (int a = 0; a < 3; ++a) ASSERT_EQ(r.cells[a], count[a] - degree[a]);
  EXPECT_EQ(r.lowest, *std::min_element(ctrl.begin(), ctrl.end()));
  EXPECT_EQ(r.highest, *std::max_element(ctrl.begin(), ctrl.end()));
  const int plane = r.cells[0] * r.cells[1];
  const auto expectExact = [&](const float* boundLo, const float* boundHi, int k) {
    for (int j = 0; j < r.cells[1]; ++j)
      for (int i = 0; i < r.cells[0]; ++i) {
        float lo = INFINITY, hi = -INFINITY;
        for (int z = k; z <= k + degree[2]; ++z)
          for (int y = j; y <= j + degree[1]; ++y)
            for (int x = i; x <= i + degree[0]; ++x) {
              const float c = ctrl[static_cast<size_t>(x + count[0] * (y + count[1] * z))];
              lo = std::min(lo, c);
              hi = std::max(hi, c);
            }
        EXPECT_EQ(boundLo[i + r.cells[0] * j], lo) << i << " " << j << " " << k;
        EXPECT_EQ(boundHi[i + r.cells[0] * j], hi) << i << " " << j << " " << k;
      }
  };
  const CellBounds all = allCellBounds(spline);
  for (int k = 0; k < r.cells[2]; ++k) expectExact(&all.lo[k * plane], &all.hi[k * plane], k);
  SpanRangeScanner scan(spline.view());
  std::vector<float> lo(plane), hi(plane);
  for (int k : {9, 10, 11, 15, 3, 4, 15, 13, 0}) {
    scan.plane(k, lo.data(), hi.data());
    expectExact(lo.data(), hi.data(), k);
  }
}

// A cell with a control point that is NaN or infinite gets the whole line as its range (it is
// never skipped); the others keep theirs, and NaN makes the whole range NaN.
TEST(SpanRanges, CellsWithoutFiniteControlPointsHaveNoBounds) {
  std::vector<float> ctrl(6 * 6 * 6);
  for (size_t i = 0; i < ctrl.size(); ++i) ctrl[i] = static_cast<float>(i % 7);
  ctrl[0] = INFINITY;
  const auto spline = [&] {
    const KnotVector k = KnotVector::clampedUniform(2, 6);
    return TensorBSpline({k, k, k}, ctrl);
  };
  const TensorBSpline withInfinity = spline();
  const CellBounds inf = allCellBounds(withInfinity);
  EXPECT_EQ(inf.lo.front(), -INFINITY);
  EXPECT_EQ(inf.hi.front(), INFINITY);
  EXPECT_EQ(inf.lo.back(), 0.0f);
  EXPECT_EQ(inf.hi.back(), 6.0f);
  EXPECT_EQ(withInfinity.spanRanges()->highest, INFINITY);
  ctrl[0] = NAN;
  const TensorBSpline withNan = spline();
  const CellBounds nan = allCellBounds(withNan);
  EXPECT_EQ(nan.lo.front(), -INFINITY);
  EXPECT_EQ(nan.hi.front(), INFINITY);
  EXPECT_EQ(nan.hi.back(), 6.0f);
  EXPECT_TRUE(std::isnan(withNan.spanRanges()->lowest));
}

// 2000 value ranges [lo, hi] around the test functions' [0, 1], every third one narrow (as most
// cells' ranges are).
std::vector<std::pair<float, float>> randomRanges(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uni(-0.2f, 1.2f);
  std::vector<std::pair<float, float>> out;
  for (int t = 0; t < 2000; ++t) {
    float lo = uni(rng), hi = uni(rng);
    if (lo > hi) std::swap(lo, hi);
    if (t % 3 == 0) hi = lo + 1e-3f * (hi - lo);
    out.emplace_back(lo, hi);
  }
  return out;
}

TEST(TransferFunctionTable, TransparentOverAgreesWithClassification) {
  for (const TransferFunction& tf : testTransferFunctions()) {
    const TransferFunctionTable table(tf, OpacityCorrection(0.5));
    for (const auto& [lo, hi] : randomRanges(3)) {
      if (!table.transparentOver(lo, hi)) continue;
      // Claimed transparent: every value in between classifies to opacity 0.
      for (int i = 0; i <= 64; ++i) {
        const float x = lo + (hi - lo) * static_cast<float>(i) / 64.0f;
        EXPECT_EQ(table.classify(x).alpha, 0.0f) << "range " << lo << ".." << hi;
      }
    }
  }
  // A range with visible values is never claimed transparent.
  const TransferFunctionTable step(testTransferFunctions()[0], OpacityCorrection(0.5));
  EXPECT_FALSE(step.transparentOver(0.4f, 0.6f));
  EXPECT_TRUE(step.transparentOver(0.0f, 0.45f));
}

// The whole-range test behind the shortcut of buildEmptySpaceFlags: a range with a
// transparent value is always reported; a range clear of the transparent entries is not.
TEST(TransferFunctionTable, MayBeTransparentOverFindsEveryTransparentRange) {
  for (const TransferFunction& tf : testTransferFunctions()) {
    const TransferFunctionTable table(tf, OpacityCorrection(0.5));
    for (const auto& [lo, hi] : randomRanges(5)) {
      if (table.transparentOver(lo, hi)) {
        EXPECT_TRUE(table.mayBeTransparentOver(lo, hi));
      }
      // rangeOpacity is both answers in one lookup.
      using O = TransferFunctionTable::RangeOpacity;
      const O both = table.transparentOver(lo, hi)        ? O::Transparent
                     : table.mayBeTransparentOver(lo, hi) ? O::Mixed
                                                          : O::Visible;
      EXPECT_EQ(table.rangeOpacity(lo, hi), both) << lo << ".." << hi;
      bool zeroInside = false;
      for (int i = 0; i <= 256; ++i)
        zeroInside |= table.classify(lo + (hi - lo) * static_cast<float>(i) / 256.0f).alpha == 0;
      if (zeroInside) {
        EXPECT_TRUE(table.mayBeTransparentOver(lo, hi)) << lo << ".." << hi;
      }
    }
  }
  const TransferFunctionTable step(testTransferFunctions()[0], OpacityCorrection(0.5));
  EXPECT_FALSE(step.mayBeTransparentOver(0.6f, 0.9f));  // entirely above the step
  EXPECT_TRUE(step.mayBeTransparentOver(0.4f, 0.9f));
  EXPECT_TRUE(step.mayBeTransparentOver(NAN, 0.9f));
  EXPECT_EQ(step.rangeOpacity(0.6f, 0.9f), TransferFunctionTable::RangeOpacity::Visible);
  EXPECT_EQ(step.rangeOpacity(0.4f, 0.9f), TransferFunctionTable::RangeOpacity::Mixed);
  EXPECT_EQ(step.rangeOpacity(0.1f, 0.3f), TransferFunctionTable::RangeOpacity::Transparent);
  EXPECT_EQ(step.rangeOpacity(NAN, 0.9f), TransferFunctionTable::RangeOpacity::Mixed);
}

// Flags built with the whole-range shortcut equal the per-cell pass: for transfer functions
// that hide part of the range and those that hide nothing the model takes.
TEST(EmptySpaceFlags, NoCellEmptyWhenTheWholeRangeIsVisible) {
  const Model& m = marschnerLobb();
  const SpanRanges& r = *m.spline().spanRanges();
  const CellBounds b = allCellBounds(m.spline());
  const CellBounds bezier = allCellBounds<BezierRangeScanner>(m.spline());
  EXPECT_LE(r.lowest, r.highest);
  std::vector<TransferFunction> tfs = testTransferFunctions();
  // Transparent only below the model's values: nothing can be skipped.
  tfs.push_back(tfWith({{r.lowest - 1.0, 0.0f}, {r.lowest - 0.5, 0.4f}, {r.highest + 1.0, 1.0f}}));
  int shortcuts = 0;
  for (const TransferFunction& tf : tfs) {
    const TransferFunctionTable table(tf, OpacityCorrection(0.5));
    const EmptySpaceFlags f = buildEmptySpaceFlags(m.spline().view(), r, table);
    const EmptySpaceFlags byControlPoints =
        buildEmptySpaceFlags(m.spline().view(), r, table, /*bezierRanges=*/false);
    std::int64_t empty = 0, emptyByControlPoints = 0;
    for (std::int64_t i = 0; i < r.cellCount(); ++i) {
      const size_t q = static_cast<size_t>(i);
      const float lo = b.lo[q], hi = b.hi[q];
      const float pad = skippingMargin(r, lo, hi);
      const bool cpEmpty = table.transparentOver(lo - pad, hi + pad);
      emptyByControlPoints += cpEmpty ? 1 : 0;
      if (!byControlPoints.cells.empty()) {
        ASSERT_EQ(byControlPoints.cells[q] != 0, cpEmpty) << "cell " << i;
        if (cpEmpty) {
          ASSERT_NE(f.cells[q], 0) << "cell " << i;
        }
      }
      float l, h;
      ASSERT_TRUE(skippingRange(r, bezier.rounding, lo, hi, bezier.lo[q], bezier.hi[q], l, h));
      empty += table.transparentOver(l, h) ? 1 : 0;
    }
    EXPECT_GE(empty, emptyByControlPoints);
    EXPECT_EQ(f.emptyCells, empty);
    EXPECT_EQ(byControlPoints.emptyCells, emptyByControlPoints);
    EXPECT_EQ(byControlPoints.cells.empty(), f.cells.empty());
    if (f.cells.empty()) {
      ++shortcuts;
      EXPECT_EQ(empty, 0);
    }
  }
  EXPECT_GE(shortcuts, 1);
}

// Skipping with flags from a cache (Bezier ranges) and flags made for the frame (Bezier ranges
// or, for a frame of few samples per cell, the control points alone: bezierRangesPayOff) gives
// the image of no skipping; the thumbnail frames take the control-point flags.
void expectIdenticalWithAndWithoutSkipping(const Model& m) {
  int skippedSomewhere = 0, controlPointFrames = 0;
  for (const TransferFunction& tf : testTransferFunctions())
    for (bool shade : {false, true})
      for (const int width : {64, 16}) {
        RenderSettings s = settingsFor(m, tf, shade);
        s.width = width;
        s.height = width * 3 / 4;
        const bool bezier = bezierRangesPayOff(m, s);
        controlPointFrames += bezier ? 0 : 1;
        RenderStats on, cached, off;
        const Image a = renderVolume(ModelField(m), s, &on);
        EmptySpaceCache cache;
        const Image c = renderVolume(ModelField(m, &cache), s, &cached);
        s.skipEmptySpace = false;
        const Image b = renderVolume(ModelField(m), s, &off);
        EXPECT_EQ(a.rgba, b.rgba) << "shade " << shade << " width " << width;
        EXPECT_EQ(c.rgba, b.rgba) << "shade " << shade << " width " << width;
        EXPECT_EQ(off.skipped, 0);
        EXPECT_LE(on.samples, off.samples);
        EXPECT_LE(cached.samples, on.samples);
        if (bezier) {
          EXPECT_EQ(cached.samples, on.samples);
        }
        if (on.skipped > 0) ++skippedSomewhere;
      }
  EXPECT_GE(skippedSomewhere, 12);  // the test has to exercise the skipping
  EXPECT_GE(controlPointFrames, 10);
}

TEST(EmptySpaceSkipping, ImagesAreBitIdenticalOnAnUnmaskedModel) {
  expectIdenticalWithAndWithoutSkipping(marschnerLobb());
}

TEST(EmptySpaceSkipping, ImagesAreBitIdenticalOnAMaskedModel) {
  expectIdenticalWithAndWithoutSkipping(maskedMarschnerLobb());
}

// Flags made for one frame get Bezier ranges when the frame's rays take enough samples per
// cell: not for a thumbnail, yes for a large image; never for a region no ray crosses, nor
// when every ray has ended.
TEST(EmptySpaceSkipping, BezierRangesForFramesWithManySamplesPerCell) {
  const Model& m = marschnerLobb();
  RenderSettings s = settingsFor(m, testTransferFunctions()[0], false);
  s.width = s.height = 8;
  EXPECT_FALSE(bezierRangesPayOff(m, s));
  s.width = s.height = 2000;
  EXPECT_TRUE(bezierRangesPayOff(m, s));
  RenderSettings coarse = s;
  coarse.sampleDistance *= 1e6;
  EXPECT_FALSE(bezierRangesPayOff(m, coarse));
  RenderSettings ended = s;
  ended.rayEnd.assign(static_cast<size_t>(s.width) * s.height, 0.0f);
  EXPECT_FALSE(bezierRangesPayOff(m, ended));
  RenderSettings away = s;
  away.clipBox = DomainBox{m.domain().max + Vec3d::Ones(), m.domain().max + 2.0 * Vec3d::Ones()};
  EXPECT_FALSE(bezierRangesPayOff(m, away));
}

TEST(EmptySpaceSkipping, SkipsMostOfASparseScene) {
  // A Gaussian beam with a step at half its range: the beam's core is visible, the rest empty.
  const auto f = makeBuiltin("gaussian-beam");
  StructuredFitOptions o;
  o.degree = {2, 2, 2};
  const Model m = fitStructured(sampleBuiltin(*f, {32, 32, 32}), o);
  const double mid = 0.5 * (m.valueMin() + m.valueMax());
  TransferFunction tf = tfWith({{mid, 0.0f}, {mid, 0.8f}, {m.valueMax(), 0.8f}});
  tf.color = {{m.valueMin(), Vec3f(1, 1, 1)}, {m.valueMax(), Vec3f(1, 0, 0)}};
  RenderSettings s = settingsFor(m, tf, false);
  RenderStats on, off;
  renderVolume(ModelField(m), s, &on);
  s.skipEmptySpace = false;
  renderVolume(ModelField(m), s, &off);
  EXPECT_LT(on.samples, off.samples / 2);
}

// An empty-space jump walks on from the cell's largest empty block through the neighbouring
// blocks (SplineRaySampler::emptyAlong): every point of the ray up to where the jump ends lies
// in an empty cell, the jump reaches at least the cell's own block's far face, and often goes
// further. Rays in random directions, along the axes (in knot planes too) and along diagonals
// (faces left at the same distance).
TEST(EmptySpaceSkipping, JumpsWalkOnlyThroughEmptyCells) {
  const Model& m = marschnerLobb();
  for (int f : {0, 2}) {
    const RenderSettings s = settingsFor(m, testTransferFunctions()[f], false);
    const ModelField field(m);
    const ModelRenderSetup setup(field, s);
    const ModelView& v = setup.view();
    ASSERT_NE(v.empty, nullptr);
    using Sampler = SplineRaySampler<0, true, false>;
    Sampler sampler(v);
    int cells[3], p[3];
    for (int a = 0; a < 3; ++a) {
      p[a] = v.spline.axis[a].degree;
      cells[a] = v.spline.axis[a].count - p[a];
    }
    const Eigen::Vector3d lo = m.domain().min, hi = m.domain().max;
    std::mt19937 rng(7 + f);
    std::uniform_real_distribution<double> unit(0.0, 1.0), normal(-1.0, 1.0);
    std::vector<Eigen::Vector3d> directions;
    for (int a = 0; a < 3; ++a)
      for (double sign : {1.0, -1.0}) {
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d[a] = sign;
        directions.push_back(d);
      }
    directions.push_back(Eigen::Vector3d(1, 1, 1).normalized());
    directions.push_back(Eigen::Vector3d(1, -1, 0).normalized());
    int jumps = 0, further = 0;
    for (int i = 0; i < 3000; ++i) {
      Eigen::Vector3d d;
      if (i % 3 == 0) {
        d = directions[static_cast<size_t>(i / 3) % directions.size()];
      } else {
        do d = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
        while (d.norm() < 0.1);
        d.normalize();
      }
      Eigen::Vector3d o;
      for (int a = 0; a < 3; ++a) o[a] = lo[a] + unit(rng) * (hi[a] - lo[a]);
      if (i % 6 == 0) {  // on a knot plane of each axis
        for (int a = 0; a < 3; ++a) {
          const int knot = p[a] + static_cast<int>(unit(rng) * cells[a]);
          o[a] = lo[a] + v.spline.axis[a].knots[knot] / v.inverseExtent[a];
        }
      }
      Sampler::RayMarch r;
      sampler.beginMarch(o.data(), d.data(), r);
      AxisLocation loc[3];
      double tLeave;
      if (!sampler.emptyAlong(r, o.data(), tLeave, loc)) continue;
      ++jumps;
      // The far face of the cell's own largest empty block, as a jump without the walk finds it.
      const int level = v.empty[(loc[0].span - p[0]) +
                                cells[0] * ((loc[1].span - p[1]) +
                                            std::int64_t(cells[1]) * (loc[2].span - p[2]))] -
                        1;
      double single = INFINITY;
      for (int a = 0; a < 3; ++a) {
        const int first = ((loc[a].span - p[a]) >> level) << level;
        const int end = std::min(first + (1 << level), cells[a]);
        const double* U = v.spline.axis[a].knots;
        if (r.ud[a] > 0.0)
          single = std::min(single, (U[p[a] + end] - Sampler::kEmptyInset - r.uo[a]) * r.invUd[a]);
        else if (r.ud[a] < 0.0)
          single =
              std::min(single, (U[p[a] + first] + Sampler::kEmptyInset - r.uo[a]) * r.invUd[a]);
      }
      ASSERT_GE(tLeave, single) << "ray " << i;
      if (tLeave > single + 1e-9) ++further;
      ASSERT_TRUE(std::isfinite(tLeave));
      // Every point up to tLeave is in an empty cell (the jump's end included). A start on a
      // face the ray leaves by ends its jump there (at most an inset behind it).
      RaySegment ray;
      for (int a = 0; a < 3; ++a) {
        ray.o[a] = o[a];
        ray.d[a] = d[a];
      }
      sampler.beginRay(ray);
      for (int k = 1; k <= 256 && tLeave > 0.0; ++k) {
        const double t = k == 256 ? tLeave : tLeave * k / 256.0;
        const Eigen::Vector3d q = o + t * d;
        double ignored;
        ASSERT_TRUE(sampler.emptyAt(q.data(), ignored))
            << "transfer function " << f << ", ray " << i << ", point " << k << " of 256";
      }
    }
    EXPECT_GT(jumps, 500) << "transfer function " << f;
    EXPECT_GT(further, jumps / 10) << "transfer function " << f;
  }
}

TEST(EmptySpaceSkipping, SameImageForAnyThreadCount) {
  const Model& m = maskedMarschnerLobb();
  RenderSettings s = settingsFor(m, testTransferFunctions()[1], true);
  s.threads = 1;
  const Image one = renderVolume(ModelField(m), s);
  s.threads = 2;
  const Image two = renderVolume(ModelField(m), s);
  s.threads = 0;
  const Image all = renderVolume(ModelField(m), s);
  EXPECT_EQ(one.rgba, two.rgba);
  EXPECT_EQ(one.rgba, all.rgba);
}

TEST(EmptySpaceCache, RebuildsOnlyWhenTheZeroSetChanges) {
  const Model& m = marschnerLobb();
  EmptySpaceCache cache;
  const TransferFunctionTable a(testTransferFunctions()[0], OpacityCorrection(0.5));
  const auto first = cache.flags(m.spline(), a);
  EXPECT_EQ(cache.flags(m.spline(), a), first);  // same table: the same flags object
  // Another colour map with the same zero set keeps the flags.
  TransferFunction recoloured = testTransferFunctions()[0];
  recoloured.color = {{0.0, Vec3f(1, 0, 0)}, {1.0, Vec3f(0, 1, 0)}};
  EXPECT_EQ(cache.flags(m.spline(), TransferFunctionTable(recoloured, OpacityCorrection(0.5))),
            first);
  const auto other = cache.flags(
      m.spline(), TransferFunctionTable(testTransferFunctions()[1], OpacityCorrection(0.5)));
  EXPECT_NE(other, first);
  EXPECT_NE(other->cells, first->cells);
  // Every level of the pyramid: a block is empty exactly when all its cells are; the last level
  // is one block.
  const SpanRanges& r = *m.spline().spanRanges();
  ASSERT_GT(other->levels, 0);
  const EmptyLevelView& top = other->level[other->levels - 1];
  EXPECT_EQ(top.count[0] * top.count[1] * top.count[2], 1);
  std::int64_t blocksChecked = 0, emptyBlocks = 0;
  for (int l = 1; l <= other->levels; ++l) {
    const EmptyLevelView& L = other->level[l - 1];
    const int side = 1 << l;
    for (int a = 0; a < 3; ++a) EXPECT_EQ(L.count[a], (r.cells[a] + side - 1) / side);
    for (int bk = 0; bk < L.count[2]; ++bk)
      for (int bj = 0; bj < L.count[1]; ++bj)
        for (int bi = 0; bi < L.count[0]; ++bi) {
          bool all = true;
          for (int k = bk * side; k < std::min((bk + 1) * side, r.cells[2]); ++k)
            for (int j = bj * side; j < std::min((bj + 1) * side, r.cells[1]); ++j)
              for (int i = bi * side; i < std::min((bi + 1) * side, r.cells[0]); ++i)
                all = all && other->cells[i + r.cells[0] * (j + r.cells[1] * k)];
          const bool flag =
              other->pyramid[L.offset + bi + L.count[0] * (bj + L.count[1] * std::int64_t(bk))];
          EXPECT_EQ(flag, all) << "level " << l << " block " << bi << " " << bj << " " << bk;
          ++blocksChecked;
          emptyBlocks += flag;
        }
  }
  EXPECT_GT(emptyBlocks, 0);              // the test sees empty blocks ...
  EXPECT_LT(emptyBlocks, blocksChecked);  // ... and non-empty ones
  // Every cell's flag: 0 when the cell is not empty, else 1 + the level of the largest aligned
  // block around it whose cells are all empty (found from the cells, not from the pyramid).
  const auto cellEmpty = [&](int i, int j, int k) {
    return other->cells[i + r.cells[0] * (j + r.cells[1] * k)] != 0;
  };
  std::vector<int> levelsSeen(other->levels + 2, 0);
  for (int k = 0; k < r.cells[2]; ++k)
    for (int j = 0; j < r.cells[1]; ++j)
      for (int i = 0; i < r.cells[0]; ++i) {
        int expected = 0;
        if (cellEmpty(i, j, k)) {
          expected = 1;
          for (int l = 1; l <= other->levels; ++l) {
            const int side = 1 << l;
            const int x0 = i / side * side, y0 = j / side * side, z0 = k / side * side;
            bool all = true;
            for (int z = z0; all && z < std::min(z0 + side, r.cells[2]); ++z)
              for (int y = y0; all && y < std::min(y0 + side, r.cells[1]); ++y)
                for (int x = x0; all && x < std::min(x0 + side, r.cells[0]); ++x)
                  all = cellEmpty(x, y, z);
            if (!all) break;
            expected = l + 1;
          }
        }
        ASSERT_EQ(other->cells[i + r.cells[0] * (j + r.cells[1] * k)], expected)
            << "cell " << i << " " << j << " " << k;
        ++levelsSeen[expected];
      }
  // The model has cells that are not empty, empty cells alone, and blocks of 2 and 4 cells.
  for (int v = 0; v <= 3; ++v) EXPECT_GT(levelsSeen[v], 0) << "flag " << v;
}

// A scene that carries caches keeps each model's flags from one render to the next (the
// command line's frames), for a single model and for each block of a multi-block one.
TEST(EmptySpaceCache, SceneCachesKeepTheFlagsBetweenRenders) {
  const Model& m = marschnerLobb();
  const RenderSettings s = settingsFor(m, testTransferFunctions()[1], true);
  MethodSpec spec;
  spec.method = ReconstructionMethod::Mfa;

  EmptySpaceCache single;
  SceneData scene;
  scene.model = &m;
  scene.emptySpace = &single;
  EXPECT_EQ(single.current(), nullptr);
  const Image first = renderMethod(scene, spec, s);
  const auto flags = single.current();
  ASSERT_NE(flags, nullptr);
  EXPECT_GT(flags->emptyCells, 0);
  EXPECT_EQ(renderMethod(scene, spec, s).rgba, first.rgba);
  EXPECT_EQ(single.current(), flags);  // not rebuilt
  scene.emptySpace = nullptr;
  EXPECT_EQ(renderMethod(scene, spec, s).rgba, first.rgba);

  // Two blocks, the model's halves in x: one cache each, each holding its own block's flags.
  const DomainBox box = m.domain();
  const double middle = 0.5 * (box.min.x() + box.max.x());
  std::vector<ModelBlock> blocks(2, ModelBlock{box, m});
  blocks[0].region.max.x() = middle;
  blocks[1].region.min.x() = middle;
  EmptySpaceCache perBlock[2];
  SceneData split;
  split.model = &blocks[0].model;
  split.blocks = &blocks;
  split.emptySpace = perBlock;
  const Image pieces = renderMethod(split, spec, s);
  ASSERT_NE(perBlock[0].current(), nullptr);
  ASSERT_NE(perBlock[1].current(), nullptr);
  const auto blockFlags = perBlock[1].current();
  EXPECT_EQ(renderMethod(split, spec, s).rgba, pieces.rgba);
  EXPECT_EQ(perBlock[1].current(), blockFlags);
}

// A model wrapped so that renderVolume takes the generic field path (FieldRaySampler over the
// model's point queries) instead of the spline ray sampler.
struct GenericModelField {
  ModelField inner;
  Vec3d boxMin() const { return inner.boxMin(); }
  Vec3d boxMax() const { return inner.boxMax(); }
  ModelField::Sampler sampler() const { return inner.sampler(); }
};

TEST(ModelRenderPath, AgreesWithTheGenericFieldPath) {
  for (const Model* m : {&marschnerLobb(), &maskedMarschnerLobb()})
    for (bool shade : {false, true}) {
      const RenderSettings s = settingsFor(*m, testTransferFunctions()[1], shade);
      const Image a = renderVolume(ModelField(*m), s);
      const Image b = renderVolume(GenericModelField{ModelField(*m)}, s);
      EXPECT_GE(compareImages(toImage8(a), toImage8(b)).psnr, 60.0) << "shade " << shade;
    }
}

}  // namespace
}  // namespace mfadvr
