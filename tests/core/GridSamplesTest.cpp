// GridSamples: a grid's samples read where they are, in their own type, as float32 planes; and
// the structured fit through it, which must give the model of the fit of a float32 copy.
#include "core/grid/GridSamples.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/Encoder.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/StructuredEncoder.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// A Marschner-Lobb grid quantized to uint16, as a scan would hold it, and its float32 copy.
struct QuantizedGrid {
  StructuredGrid floats;
  std::vector<std::uint16_t> stored;
};

QuantizedGrid quantized(const Index3& dims) {
  QuantizedGrid q;
  q.floats = sampleBuiltin(*makeBuiltin("marschner-lobb"), dims);
  q.stored.resize(q.floats.values.size());
  for (size_t i = 0; i < q.stored.size(); ++i) {
    q.stored[i] = static_cast<std::uint16_t>(std::lround(q.floats.values[i] * 60000.0));
    q.floats.values[i] = static_cast<float>(q.stored[i]);
  }
  q.floats.sampleType = "uint16";
  return q;
}

StructuredGrid layoutOf(const StructuredGrid& g) {
  StructuredGrid layout = g;
  layout.values.clear();
  return layout;
}

TEST(GridSamples, ConvertsPlanesOfAnyTypeToFloat) {
  const QuantizedGrid q = quantized({5, 4, 3});
  const GridSamples s = GridSamples::of(q.stored.data(), q.floats.dims);
  EXPECT_EQ(s.sampleCount(), 60);
  std::vector<float> scratch;
  const float* plane = s.plane(2, scratch);
  EXPECT_EQ(plane, scratch.data());  // converted
  for (int i = 0; i < 20; ++i) EXPECT_EQ(plane[i], q.floats.values[static_cast<size_t>(40 + i)]);
  EXPECT_EQ(s.toFloats(), q.floats.values);
  const auto [lo, hi] = s.range();
  EXPECT_EQ(lo, *std::min_element(q.floats.values.begin(), q.floats.values.end()));
  EXPECT_EQ(hi, *std::max_element(q.floats.values.begin(), q.floats.values.end()));
  EXPECT_NO_THROW(s.validateFor(q.floats));
}

TEST(GridSamples, ReadsAFloatGridWithoutCopying) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:6x5x4");
  const GridSamples s(g);
  std::vector<float> scratch;
  EXPECT_EQ(s.plane(3, scratch), g.values.data() + 3 * 30);
  EXPECT_TRUE(scratch.empty());
}

TEST(GridSamples, ValidationNamesTheBadSample) {
  StructuredGrid layout = sampleBuiltinSpec("builtin:marschner-lobb:4x4x4");
  std::vector<double> values(64, 1.0);
  values[1 + 4 * (2 + 4 * 3)] = std::numeric_limits<double>::quiet_NaN();
  layout.values.clear();
  try {
    GridSamples::of(values.data(), layout.dims).validateFor(layout);
    FAIL() << "a NaN sample passed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sample (1, 2, 3)"), std::string::npos) << e.what();
  }
  // Beyond float32: infinite as the fit would hold it.
  values[1 + 4 * (2 + 4 * 3)] = 1e300;
  EXPECT_THROW(GridSamples::of(values.data(), layout.dims).validateFor(layout), Error);
  values[1 + 4 * (2 + 4 * 3)] = 1.0;
  EXPECT_NO_THROW(GridSamples::of(values.data(), layout.dims).validateFor(layout));
  // The wrong size, and no samples at all.
  EXPECT_THROW(GridSamples::of(values.data(), Index3{4, 4, 3}).validateFor(layout), Error);
  EXPECT_THROW(GridSamples().validateFor(layout), Error);
}

void expectSameModel(const Model& a, const Model& b) {
  const auto pa = a.spline().controlPoints(), pb = b.spline().controlPoints();
  ASSERT_EQ(pa.size(), pb.size());
  for (size_t i = 0; i < pa.size(); ++i) ASSERT_EQ(pa[i], pb[i]) << "control point " << i;
  EXPECT_EQ(a.valueMin(), b.valueMin());
  EXPECT_EQ(a.valueMax(), b.valueMax());
  EXPECT_EQ(a.provenance().maxError, b.provenance().maxError);
  EXPECT_EQ(a.provenance().rmsError, b.provenance().rmsError);
  EXPECT_EQ(a.provenance().sampleType, b.provenance().sampleType);
}

// Plane by plane from uint16 or from a float32 copy: the same model, bit for bit, interpolating,
// with fewer control points and smoothed.
TEST(GridSamples, FitGivesTheModelOfTheFloatCopy) {
  const QuantizedGrid q = quantized({23, 19, 17});
  const GridSamples s = GridSamples::of(q.stored.data(), q.floats.dims);
  const StructuredGrid layout = layoutOf(q.floats);
  for (const Index3 counts : {Index3{0, 0, 0}, Index3{12, 10, 9}})
    for (const double smoothing : {0.0, 1e-3}) {
      SCOPED_TRACE(::testing::Message() << "counts " << counts[0] << " smoothing " << smoothing);
      StructuredFitOptions o;
      o.controlCounts = counts;
      o.smoothing = smoothing;
      FitReport fromView, fromCopy;
      expectSameModel(fitStructured(layout, s, o, &fromView),
                      fitStructured(q.floats, o, &fromCopy));
      EXPECT_EQ(fromView.maxError, fromCopy.maxError);
    }
}

// The encoder's paths: a plain fit reads the view; an error bound works on a copy; a piece gets
// the whole grid's density either way.
TEST(GridSamples, EncodersGiveTheModelsOfTheFloatCopy) {
  const QuantizedGrid q = quantized({21, 21, 21});
  const GridSamples s = GridSamples::of(q.stored.data(), q.floats.dims);
  const StructuredGrid layout = layoutOf(q.floats);
  EncodeOptions plain;
  plain.controlCounts = {15, 15, 15};
  expectSameModel(encodeStructured(layout, s, plain), encodeStructured(q.floats, plain));
  EncodeOptions bounded;
  bounded.adaptive = AdaptiveOptions{};
  bounded.adaptive->maxRelativeError = 0.05;
  expectSameModel(encodeStructured(layout, s, bounded), encodeStructured(q.floats, bounded));
  expectSameModel(encodeStructuredPiece(layout, s, {41, 41, 41}, plain, 0.0, 60000.0),
                  encodeStructuredPiece(q.floats, {41, 41, 41}, plain, 0.0, 60000.0));
  // Bad layouts and samples are refused as for a grid.
  StructuredGrid badSpacing = layout;
  badSpacing.spacing[1] = 0.0;
  EXPECT_THROW(encodeStructured(badSpacing, s, plain), Error);
  EXPECT_THROW(encodeStructured(layout, GridSamples(), plain), Error);
}

}  // namespace
}  // namespace mfadvr
