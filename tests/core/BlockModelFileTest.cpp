// The multi-block model file: round trip, reading one block alone, and every truncation and
// corruption an error.
#include "core/model/BlockModelFile.h"

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/PieceEncoder.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

std::vector<ModelBlock> smallBlocks() {
  const StructuredGrid grid = sampleBuiltinSpec("builtin:marschner-lobb:9x8x7");
  EncodeOptions o;
  o.degree = {2, 2, 2};
  return encodeStructuredBlocks(grid, {2, 1, 2}, 1, o);
}

std::vector<std::uint8_t> bytesOf(const std::string& s) {
  return {s.begin(), s.end()};
}

std::string errorOf(const std::vector<std::uint8_t>& b) {
  try {
    parseBlockModels(b);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(BlockModelFile, RoundTripsAndReadsBlocksAlone) {
  const auto blocks = smallBlocks();
  const auto dir = test::scratchDir();
  saveBlockModels(blocks, {2, 1, 2}, dir / "b.mfa");
  EXPECT_TRUE(isBlockModelFile(dir / "b.mfa"));
  const BlockIndex index = readBlockIndex(dir / "b.mfa");
  EXPECT_EQ(index.blocks, (Index3{2, 1, 2}));
  ASSERT_EQ(index.entries.size(), 4u);
  EXPECT_EQ(index.valueMin, blocks[0].model.valueMin());
  for (size_t i = 0; i < blocks.size(); ++i) {
    const Model m = loadBlock(dir / "b.mfa", index, i);
    EXPECT_EQ(serializeModel(m), serializeModel(blocks[i].model));
    EXPECT_EQ(index.entries[i].region.min, blocks[i].region.min);
    EXPECT_EQ(index.entries[i].region.max, blocks[i].region.max);
  }
  const auto all = loadBlockModels(dir / "b.mfa");
  EXPECT_EQ(all.size(), 4u);
  // The box is the union of the regions.
  EXPECT_EQ(index.box.min, blocks[0].region.min);
  EXPECT_EQ(index.box.max, blocks[3].region.max);
  // A single model is not a multi-block file, and the other way round.
  saveModel(blocks[0].model, dir / "one.mfa");
  EXPECT_FALSE(isBlockModelFile(dir / "one.mfa"));
  EXPECT_THROW(readBlockIndex(dir / "one.mfa"), Error);
  EXPECT_THROW(loadModel(dir / "b.mfa"), Error);
  EXPECT_THROW(readBlockIndex(dir / "missing.mfa"), Error);
}

TEST(BlockModelFile, EveryTruncationAndCorruptionIsAnError) {
  const auto full = bytesOf(serializeBlockModels(smallBlocks(), {2, 1, 2}));
  EXPECT_EQ(errorOf(full), "");
  for (size_t n = 0; n < full.size(); n += (n < 600 ? 1 : 37)) {
    const std::vector<std::uint8_t> cut(full.begin(), full.begin() + n);
    EXPECT_NE(errorOf(cut), "") << "prefix of " << n << " bytes parsed";
  }
  auto longer = full;
  longer.push_back(0);
  EXPECT_NE(errorOf(longer).find("trailing"), std::string::npos) << errorOf(longer);
  for (size_t i = 0; i < full.size(); i += (i < 600 ? 1 : 13)) {
    auto b = full;
    b[i] ^= 0x5a;
    EXPECT_NE(errorOf(b), "") << "flip at byte " << i << " went unnoticed";
  }
}

TEST(BlockModelFile, RefusesInconsistentBlockSets) {
  auto blocks = smallBlocks();
  EXPECT_THROW(serializeBlockModels(blocks, {2, 2, 2}), Error);
  EXPECT_THROW(serializeBlockModels({}, {1, 1, 1}), Error);
}

}  // namespace
}  // namespace mfadvr
