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

// Out-of-core encoding appends each block as it is fitted and writes the index last: the file
// reads like one written at once, and nothing appears until the last block is in.
TEST(BlockModelFile, WriterAppendsBlocksThenTheIndex) {
  const auto blocks = smallBlocks();
  const auto dir = test::scratchDir();
  const auto path = dir / "streamed.mfa";
  {
    BlockModelFileWriter writer(path, {2, 1, 2});
    for (const ModelBlock& b : blocks) writer.append(b);
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_THROW(writer.append(blocks[0]), Error);  // a fifth block of a 2 x 1 x 2 grid
    writer.commit();
  }
  const BlockIndex index = readBlockIndex(path);
  EXPECT_EQ(index.blocks, (Index3{2, 1, 2}));
  EXPECT_EQ(index.valueMax, blocks[0].model.valueMax());
  for (size_t i = 0; i < blocks.size(); ++i) {
    EXPECT_EQ(serializeModel(loadBlock(path, index, i)), serializeModel(blocks[i].model));
    EXPECT_EQ(index.entries[i].region.max, blocks[i].region.max);
  }
  EXPECT_EQ(index.box.max, blocks[3].region.max);

  // Abandoned (an error while encoding), it leaves nothing behind; committed short, it refuses.
  {
    BlockModelFileWriter writer(dir / "abandoned.mfa", {2, 1, 2});
    writer.append(blocks[0]);
  }
  {
    BlockModelFileWriter writer(dir / "short.mfa", {2, 1, 2});
    writer.append(blocks[0]);
    EXPECT_THROW(writer.commit(), Error);
  }
  size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);
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
