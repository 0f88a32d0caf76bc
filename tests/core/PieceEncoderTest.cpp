// Partitioned encoding: piece ranges, and blocks fitted with ghost layers that render, clipped
// to their regions and composited, like the model of the whole grid.
#include "core/encode/PieceEncoder.h"

#include <gtest/gtest.h>

#include "TestSupport.h"

#include "MarschnerLobbScene.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/analytic/BuiltinGridSource.h"
#include "core/field/ModelField.h"
#include "core/image/ImageMetrics.h"
#include "core/render/PieceCompositor.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

TEST(PieceEncoder, PiecesShareTheirBoundarySamplesAndTileTheGrid) {
  const Index3 dims{10, 7, 2};
  const SampleRange a = pieceRange(dims, {3, 2, 1}, {0, 0, 0});
  const SampleRange b = pieceRange(dims, {3, 2, 1}, {1, 0, 0});
  const SampleRange c = pieceRange(dims, {3, 2, 1}, {2, 1, 0});
  EXPECT_EQ(a.lo, (Index3{0, 0, 0}));
  EXPECT_EQ(a.hi, (Index3{3, 3, 1}));
  EXPECT_EQ(b.lo[0], 3);  // shares sample 3 with piece 0
  EXPECT_EQ(b.hi[0], 6);
  EXPECT_EQ(c.hi, (Index3{9, 6, 1}));
  const SampleRange g = withGhostLayers(b, 2, dims);
  EXPECT_EQ(g.lo, (Index3{1, 0, 0}));
  EXPECT_EQ(g.hi, (Index3{8, 5, 1}));
  EXPECT_THROW(pieceRange(dims, {1, 1, 2}, {0, 0, 0}), Error);  // 2 pieces of 1 interval
  EXPECT_NO_THROW(pieceRange({10, 7, 3}, {1, 1, 2}, {0, 0, 1}));
  EXPECT_THROW(pieceRange(dims, {1, 7, 1}, {0, 0, 0}), Error);  // 7 pieces of 6 intervals
  EXPECT_THROW(pieceRange(dims, {3, 2, 1}, {3, 0, 0}), Error);
}

TEST(PieceEncoder, SubGridKeepsPositionsAndValues) {
  const StructuredGrid grid = sampleBuiltinSpec("builtin:marschner-lobb:9x8x7");
  const SampleRange r{{2, 1, 3}, {6, 7, 5}};
  const StructuredGrid sub = subGrid(grid, r);
  EXPECT_EQ(sub.dims, (Index3{5, 7, 3}));
  EXPECT_EQ(sub.origin, grid.position(2, 1, 3));
  EXPECT_EQ(sub.at(4, 6, 2), grid.at(6, 7, 5));
  EXPECT_EQ(sub.at(0, 0, 0), grid.at(2, 1, 3));
}

TEST(PieceEncoder, BlocksCompositeToTheWholeModelsImage) {
  const StructuredGrid grid = sampleBuiltinSpec("builtin:marschner-lobb:33x33x33");
  EncodeOptions options;  // interpolating cubic fits
  const Model whole = encodeStructured(grid, options);
  const std::vector<ModelBlock> blocks = encodeStructuredBlocks(grid, {2, 2, 1}, -1, options);
  ASSERT_EQ(blocks.size(), 4u);
  for (const ModelBlock& b : blocks) {
    // The blocks' value range is the whole grid's, and each model covers its ghost layers.
    EXPECT_EQ(b.model.valueMin(), whole.valueMin());
    EXPECT_EQ(b.model.valueMax(), whole.valueMax());
    EXPECT_TRUE(((b.model.domain().min - b.region.min).array() <= 0.0).all());
    EXPECT_TRUE(((b.model.domain().max - b.region.max).array() >= 0.0).all());
  }

  RenderSettings s = mlSettings(64);
  s.earlyTerminationOpacity = 2.0;
  s.alignSamplesToCamera = true;
  const Image reference = renderVolume(ModelField(whole), s);
  std::vector<DomainBox> boxes;
  std::vector<Image> pieces;
  for (const ModelBlock& b : blocks) {
    RenderSettings piece = s;
    piece.clipBox = b.region;
    boxes.push_back(b.region);
    pieces.push_back(renderVolume(ModelField(b.model), piece));
  }
  const double psnr =
      compareImages(toImage8(reference), toImage8(compositeInVisibilityOrder(s, boxes, pieces)))
          .psnr;
  EXPECT_GT(psnr, 40.0);
  // Without ghost layers the pieces disagree more along their common faces.
  const std::vector<ModelBlock> bare = encodeStructuredBlocks(grid, {2, 2, 1}, 0, options);
  std::vector<Image> barePieces;
  for (size_t i = 0; i < bare.size(); ++i) {
    RenderSettings piece = s;
    piece.clipBox = bare[i].region;
    barePieces.push_back(renderVolume(ModelField(bare[i].model), piece));
  }
  const double barePsnr =
      compareImages(toImage8(reference), toImage8(compositeInVisibilityOrder(s, boxes, barePieces)))
          .psnr;
  EXPECT_GT(psnr, barePsnr);
  RecordProperty("psnr_ghost", std::to_string(psnr));
  RecordProperty("psnr_no_ghost", std::to_string(barePsnr));
  std::printf("blocks vs whole: %.2f dB with ghost layers, %.2f dB without\n", psnr, barePsnr);
}

TEST(PieceEncoder, ControlCountsKeepTheirDensity) {
  const StructuredGrid grid = sampleBuiltinSpec("builtin:marschner-lobb:41x41x41");
  EncodeOptions options;
  options.controlCounts = {21, 21, 21};
  const std::vector<ModelBlock> blocks = encodeStructuredBlocks(grid, {2, 1, 1}, 0, options);
  // 20 of 40 sample intervals: (21 - 3) / 40 * 20 + 3 = 12 control points along x.
  EXPECT_EQ(blocks[0].model.spline().counts()[0], 12);
  EXPECT_EQ(blocks[0].model.spline().counts()[1], 21);
}

// A source that samples boxes on demand gives the samples the whole grid holds.
TEST(PieceEncoder, BuiltinSourceReadsTheBoxesOfTheWholeGrid) {
  const StructuredGrid grid = sampleBuiltinSpec("builtin:marschner-lobb:9x8x7");
  BuiltinGridSource source("builtin:marschner-lobb:9x8x7");
  EXPECT_EQ(source.layout().dims, grid.dims);
  EXPECT_TRUE(source.layout().values.empty());
  for (const SampleRange& r : {SampleRange{{2, 1, 3}, {6, 7, 5}}, wholeRange(grid.dims),
                               SampleRange{{0, 0, 6}, {8, 7, 6}}}) {
    const StructuredGrid box = source.read(r);
    const StructuredGrid expected = subGrid(grid, r);
    EXPECT_EQ(box.values, expected.values);
    EXPECT_EQ(box.origin, expected.origin);
  }
  const auto [lo, hi] = std::minmax_element(grid.values.begin(), grid.values.end());
  EXPECT_EQ(source.valueRange(), (std::pair<double, double>(*lo, *hi)));
  EXPECT_THROW(source.read({{0, 0, 0}, {9, 0, 0}}), Error);  // outside the grid
}

// Blocks read one at a time from a source are the blocks of the grid in memory, byte for byte,
// and reach the sink in file order.
TEST(PieceEncoder, BlocksFromASourceEqualBlocksFromMemory) {
  const std::string spec = "builtin:marschner-lobb:21x17x19";
  EncodeOptions options;
  options.degree = {2, 3, 2};
  const std::vector<ModelBlock> inMemory =
      encodeStructuredBlocks(sampleBuiltinSpec(spec), {2, 2, 3}, -1, options);
  BuiltinGridSource source(spec);
  std::vector<ModelBlock> streamed;
  std::vector<double> fractions;
  options.progress = [&](double f, const std::string&) { fractions.push_back(f); };
  encodeStructuredBlocks(source, {2, 2, 3}, -1, options, [&](ModelBlock&& b, const FitReport& r) {
    EXPECT_GT(r.controlCounts[0], 0);
    streamed.push_back(std::move(b));
  });
  ASSERT_EQ(streamed.size(), inMemory.size());
  for (size_t i = 0; i < streamed.size(); ++i) {
    // (The files would differ only in the fit times and dates of their provenance.)
    const TensorBSpline &a = streamed[i].model.spline(), &b = inMemory[i].model.spline();
    EXPECT_EQ(a.counts(), b.counts()) << "block " << i;
    EXPECT_EQ(test::values(a.controlPoints()), test::values(b.controlPoints())) << "block " << i;
    EXPECT_EQ(streamed[i].region.min, inMemory[i].region.min);
    EXPECT_EQ(streamed[i].region.max, inMemory[i].region.max);
    EXPECT_EQ(streamed[i].model.valueMax(), inMemory[i].model.valueMax());
  }
  ASSERT_FALSE(fractions.empty());
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.back(), 1.0);

  // lambda by cross-validation needs every sample at once: a source on disk cannot give it.
  options.autoSmoothing = true;
  EXPECT_THROW(
      encodeStructuredBlocks(source, {2, 1, 1}, -1, options, [](ModelBlock&&, const FitReport&) {}),
      Error);
}

TEST(PieceEncoder, DefaultBlocksHoldAtMost256Intervals) {
  EXPECT_EQ(defaultBlockCounts({257, 256, 2}), (Index3{1, 1, 1}));
  EXPECT_EQ(defaultBlockCounts({258, 1024, 2048}), (Index3{2, 4, 8}));
  EXPECT_EQ(defaultBlockCounts({1, 1, 1}), (Index3{1, 1, 1}));
}

}  // namespace
}  // namespace mfadvr
