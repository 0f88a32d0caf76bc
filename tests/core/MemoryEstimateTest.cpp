// Memory figures used to refuse work before it starts: the byte counts a user may give
// (MFADVR_MEMORY_LIMIT) and what rendering a model will hold.
#include <gtest/gtest.h>

#include <vector>

#include "core/render/RenderMemory.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr {
namespace {

TEST(MemoryBudget, ByteCountsWithUnits) {
  EXPECT_EQ(parseByteCount("8G"), 8'000'000'000);
  EXPECT_EQ(parseByteCount("512m"), 512'000'000);
  EXPECT_EQ(parseByteCount("100K"), 100'000);
  EXPECT_EQ(parseByteCount("1.5e9"), 1'500'000'000);
  EXPECT_EQ(parseByteCount("2T"), 2'000'000'000'000);
  EXPECT_EQ(parseByteCount("4096"), 4096);
  EXPECT_EQ(parseByteCount("8GB"), 8'000'000'000);  // as --memory-limit took it
  EXPECT_EQ(parseByteCount("512mb"), 512'000'000);
  EXPECT_EQ(parseByteCount("4096B"), 4096);
  for (const char* bad : {"", "G", "B", "-1", "0", "8X", "8BB", "8GBB", " 8G", "1e30", "nan"})
    EXPECT_THROW(parseByteCount(bad), Error) << bad;
}

TEST(RenderMemory, ControlPointsAndFlags) {
  ModelFileSummary f32;
  f32.degree = {3, 3, 3};
  f32.controlCounts = {512, 512, 512};
  f32.fileBytes = 4ull * 512 * 512 * 512 + 4096;
  // float32 control points (4 B) and a flag per cell with its pyramid (~1.1 B): 5.1 B per
  // control point (docs/benchmarks.md compares this with measured peaks).
  const double perPoint = static_cast<double>(modelRenderBytes(f32)) / (512.0 * 512 * 512);
  EXPECT_GT(perPoint, 4.9);
  EXPECT_LT(perPoint, 5.2);
  // A zfp-coded model keeps its coded bytes besides the decoded points.
  ModelFileSummary zfp = f32;
  zfp.coder = ControlCoder::kZfp;
  zfp.fileBytes = 1'000'000;
  EXPECT_EQ(modelRenderBytes(zfp) - modelRenderBytes(f32), 1'000'000);
  // Maximum and minimum intensity renders hold two bytes of bounds per cell and their pyramids.
  const double cells = 509.0 * 509 * 509;
  const double bounds = static_cast<double>(modelRenderBytes(f32, true) - modelRenderBytes(f32));
  EXPECT_GT(bounds, 2.0 * cells);
  EXPECT_LT(bounds, 2.0 * cells * 8.0 / 7.0 + 2.0);
  // A scene adds the largest file once (it is read whole before it is decoded).
  // Headers that claim the most control points a file may name do not wrap around.
  ModelFileSummary huge = f32;
  huge.controlCounts = {1 << 20, 1 << 20, 1 << 20};
  huge.degree = {1, 1, 1};
  const std::vector<ModelFileSummary> hugeScene(4, huge);
  EXPECT_GT(sceneRenderBytes(hugeScene), std::int64_t{1} << 61);
  const std::vector<ModelFileSummary> scene{f32, zfp};
  EXPECT_EQ(sceneRenderBytes(scene), modelRenderBytes(f32) + modelRenderBytes(zfp) +
                                         static_cast<std::int64_t>(f32.fileBytes));
  // A file whose control points are used where they are read holds no second copy.
  ModelFileSummary inPlace = f32;
  inPlace.readInPlace = true;
  const std::vector<ModelFileSummary> alone{inPlace};
  EXPECT_EQ(sceneRenderBytes(alone), modelRenderBytes(inPlace));
  const std::vector<ModelFileSummary> mixed{inPlace, zfp};
  EXPECT_EQ(sceneRenderBytes(mixed), modelRenderBytes(inPlace) + modelRenderBytes(zfp) +
                                         static_cast<std::int64_t>(zfp.fileBytes));
}

}  // namespace
}  // namespace mfadvr
