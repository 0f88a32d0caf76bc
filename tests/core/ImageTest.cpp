// Image, toImage8 and the float NRRD output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "TestSupport.h"
#include "core/image/FloatImageFile.h"
#include "core/image/Image.h"

namespace mfadvr {
namespace {

TEST(Image, ConstructsZeroFilledAndAddressesPixelsTopRowFirst) {
  Image im(3, 2);
  EXPECT_EQ(im.width, 3);
  EXPECT_EQ(im.height, 2);
  ASSERT_EQ(im.rgba.size(), 24u);
  for (float v : im.rgba) EXPECT_EQ(v, 0.0f);
  im.pixel(2, 1)[3] = 0.5f;
  EXPECT_EQ(im.rgba[4 * (1 * 3 + 2) + 3], 0.5f);
  const Image& c = im;
  EXPECT_EQ(c.pixel(2, 1)[3], 0.5f);
}

TEST(Image, RejectsEmptyNegativeAndAbsurdSizes) {
  test::expectError([] { Image(0, 5); }, {"invalid image size", "0 x 5"});
  test::expectError([] { Image(5, -1); }, {"invalid image size"});
  test::expectError([] { Image(100000, 100000); }, {"invalid image size"});
}

TEST(Image, ToImage8RoundsToNearestAndClamps) {
  Image im(4, 2);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // 0.5 * 255 = 127.5 rounds up; 1.49 and 1.51 (in units of 1/255) round to 1 and 2.
  const float values[8][4] = {{0.0f, 0.5f, 1.0f, 0.25f},
                              {-0.5f, 2.0f, 1.49f / 255, 1.51f / 255},
                              {nan, inf, -inf, 1.0f},
                              {0.2f, 0.4f, 0.6f, 0.8f},
                              {254.49f / 255, 254.51f / 255, 0.999f, 0.001f},
                              {0, 0, 0, 0},
                              {1, 1, 1, 1},
                              {0.1f, 0.1f, 0.1f, -1.0f}};
  for (int i = 0; i < 8; ++i) std::memcpy(im.rgba.data() + 4 * i, values[i], sizeof values[i]);
  const Image8 rgb = toImage8(im);
  EXPECT_EQ(rgb.width, 4);
  EXPECT_EQ(rgb.height, 2);
  EXPECT_EQ(rgb.channels, 3);
  ASSERT_EQ(rgb.data.size(), 24u);
  const std::uint8_t expected[8][4] = {{0, 128, 255, 64},    {0, 255, 1, 2},     {0, 255, 0, 255},
                                       {51, 102, 153, 204},  {254, 255, 255, 0}, {0, 0, 0, 0},
                                       {255, 255, 255, 255}, {26, 26, 26, 0}};
  for (int i = 0; i < 8; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb.data[3 * i + c], expected[i][c]) << i << " " << c;
  const Image8 rgba = toImage8(im, true);
  EXPECT_EQ(rgba.channels, 4);
  ASSERT_EQ(rgba.data.size(), 32u);
  for (int i = 0; i < 8; ++i)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(rgba.data[4 * i + c], expected[i][c]) << i << " " << c;
}

TEST(Image, CheckImage8RejectsInconsistentImages) {
  Image8 im{2, 2, 3, std::vector<std::uint8_t>(12)};
  EXPECT_NO_THROW(checkImage8(im, "x"));
  im.channels = 1;
  test::expectError([&] { checkImage8(im, "x"); }, {"x", "channels"});
  im.channels = 4;
  test::expectError([&] { checkImage8(im, "x"); }, {"bytes of pixel data"});
  im.width = 0;
  test::expectError([&] { checkImage8(im, "x"); }, {"invalid image size"});
}

TEST(ImageFloatFile, WritesNrrdHeaderAndExactlySixteenBytesPerPixel) {
  const auto dir = test::scratchDir();
  Image im(5, 3);
  for (size_t i = 0; i < im.rgba.size(); ++i) im.rgba[i] = 0.25f * static_cast<float>(i) - 3.0f;
  const std::string path = (dir / "image.nrrd").string();
  writeFloatImage(path, im);

  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  const std::string bytes = s.str();
  const size_t end = bytes.find("\n\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = bytes.substr(0, end + 1);
  EXPECT_EQ(header.rfind("NRRD0004\n", 0), 0u);
  for (const char* line : {"\ntype: float\n", "\ndimension: 3\n", "\nsizes: 4 5 3\n",
                           "\nencoding: raw\n", "\nendian: little\n", "linear RGBA"})
    EXPECT_NE(header.find(line), std::string::npos) << line;
  ASSERT_EQ(bytes.size() - (end + 2), 16u * 5 * 3);
  std::vector<float> back(im.rgba.size());
  std::memcpy(back.data(), bytes.data() + end + 2, back.size() * sizeof(float));
  EXPECT_EQ(back, im.rgba);  // little-endian host
}

TEST(ImageFloatFile, FailsCleanlyOnAMissingFolderOrInconsistentImage) {
  const auto dir = test::scratchDir();
  const std::string path = (dir / "no-such-folder" / "image.nrrd").string();
  test::expectError([&] { writeFloatImage(path, Image(2, 2)); }, {"cannot write", path});
  Image bad(2, 2);
  bad.rgba.pop_back();
  test::expectError([&] { writeFloatImage((dir / "bad.nrrd").string(), bad); },
                    {"inconsistent image"});
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace mfadvr
