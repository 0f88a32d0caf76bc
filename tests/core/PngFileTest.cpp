// PNG writing and reading: bit-exact round trips, the conversions of other PNG kinds to 8-bit
// RGB(A), and clean errors (never a crash) for damaged, truncated or missing files.
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <fstream>
#include <random>
#include <sstream>

#include "TestSupport.h"
#include "core/image/PngFile.h"

namespace mfadvr {
namespace {

Image8 randomImage(int w, int h, int channels, unsigned seed) {
  std::mt19937 rng(seed);
  Image8 im{w, h, channels, std::vector<std::uint8_t>(static_cast<size_t>(w) * h * channels)};
  for (auto& v : im.data) v = static_cast<std::uint8_t>(rng() & 0xff);
  return im;
}

std::vector<std::uint8_t> bytesOf(const std::string& s) {
  return {s.begin(), s.end()};
}

void writeBytes(const std::filesystem::path& p, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(p, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

// Writes a PNG of any kind with libpng directly, for the reader's conversions. `rows` holds the
// packed rows as libpng expects them (16-bit samples big-endian).
struct RawPng {
  RawPng(int w, int h, int type, int depth, int interlaceType = PNG_INTERLACE_NONE)
      : width(w), height(h), colorType(type), bitDepth(depth), interlace(interlaceType) {}
  int width, height, colorType, bitDepth, interlace;
  std::vector<std::vector<std::uint8_t>> rows;
  std::vector<png_color> palette;
  std::vector<std::uint8_t> paletteAlpha;
};

void writeRawPng(const std::filesystem::path& path, RawPng& p) {
  FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  std::vector<png_bytep> rows;
  for (auto& r : p.rows) rows.push_back(r.data());
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    FAIL() << "libpng failed to write the test file";
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, p.width, p.height, p.bitDepth, p.colorType, p.interlace,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (!p.palette.empty())
    png_set_PLTE(png, info, p.palette.data(), static_cast<int>(p.palette.size()));
  if (!p.paletteAlpha.empty())
    png_set_tRNS(png, info, p.paletteAlpha.data(), static_cast<int>(p.paletteAlpha.size()),
                 nullptr);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
}

TEST(PngFile, RoundTripsRgbAndRgbaBitExactly) {
  const auto dir = test::scratchDir();
  for (int channels : {3, 4}) {
    const Image8 im = randomImage(37, 23, channels, 7 + channels);
    const std::string path = (dir / ("im" + std::to_string(channels) + ".png")).string();
    writePng(path, im);
    const Image8 back = readPng(path);
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 23);
    EXPECT_EQ(back.channels, channels);
    EXPECT_EQ(back.data, im.data);
  }
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
}

TEST(PngFile, ExpandsGrayPaletteSixteenBitAndInterlacedToEightBit) {
  const auto dir = test::scratchDir();
  {  // 1-bit gray: 0 -> 0, 1 -> 255.
    RawPng p{3, 1, PNG_COLOR_TYPE_GRAY, 1};
    p.rows = {{0b10100000}};
    writeRawPng(dir / "g1.png", p);
    const Image8 im = readPng((dir / "g1.png").string());
    EXPECT_EQ(im.channels, 3);
    EXPECT_EQ(im.data, (std::vector<std::uint8_t>{255, 255, 255, 0, 0, 0, 255, 255, 255}));
  }
  {  // 16-bit gray + alpha, scaled with rounding: 0x8080 -> 128, 0xffff -> 255, 0x0101 -> 1.
    RawPng p{2, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 16};
    p.rows = {{0x80, 0x80, 0xff, 0xff, 0x01, 0x01, 0x00, 0x00}};
    writeRawPng(dir / "ga16.png", p);
    const Image8 im = readPng((dir / "ga16.png").string());
    EXPECT_EQ(im.channels, 4);
    EXPECT_EQ(im.data, (std::vector<std::uint8_t>{128, 128, 128, 255, 1, 1, 1, 0}));
  }
  {  // 4-bit palette with transparency for the first entry only.
    RawPng p{2, 2, PNG_COLOR_TYPE_PALETTE, 4};
    p.palette = {{10, 20, 30}, {40, 50, 60}};
    p.paletteAlpha = {7};
    p.rows = {{0x01}, {0x10}};
    writeRawPng(dir / "pal.png", p);
    const Image8 im = readPng((dir / "pal.png").string());
    EXPECT_EQ(im.channels, 4);
    EXPECT_EQ(im.data, (std::vector<std::uint8_t>{10, 20, 30, 7, 40, 50, 60, 255,  //
                                                  40, 50, 60, 255, 10, 20, 30, 7}));
  }
  {  // Interlaced 16-bit RGB.
    RawPng p{9, 9, PNG_COLOR_TYPE_RGB, 16, PNG_INTERLACE_ADAM7};
    std::vector<std::uint8_t> expected;
    for (int y = 0; y < 9; ++y) {
      std::vector<std::uint8_t> row;
      for (int x = 0; x < 9; ++x)
        for (int c = 0; c < 3; ++c) {
          const std::uint8_t v = static_cast<std::uint8_t>(x * 20 + y * 3 + c);
          row.push_back(v);
          row.push_back(v);  // v * 257 scales back to exactly v
          expected.push_back(v);
        }
      p.rows.push_back(row);
    }
    writeRawPng(dir / "rgb16i.png", p);
    const Image8 im = readPng((dir / "rgb16i.png").string());
    EXPECT_EQ(im.width, 9);
    EXPECT_EQ(im.channels, 3);
    EXPECT_EQ(im.data, expected);
  }
}

TEST(PngFile, EveryTruncationIsAnError) {
  const std::vector<std::uint8_t> bytes = bytesOf(encodePng(randomImage(8, 5, 4, 1)));
  for (size_t n = 0; n < bytes.size(); ++n)
    test::expectError([&] { decodePng(std::span<const std::uint8_t>(bytes.data(), n), "cut.png"); },
                      {"cut.png"});
  const auto dir = test::scratchDir();
  writeBytes(dir / "cut.png", std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 20));
  test::expectError([&] { readPng((dir / "cut.png").string()); }, {"cut.png", "damaged PNG"});
}

TEST(PngFile, RandomAndCorruptedBytesGiveErrorsNotCrashes) {
  const auto dir = test::scratchDir();
  std::mt19937 rng(42);
  std::vector<std::uint8_t> noise(300);
  for (auto& v : noise) v = static_cast<std::uint8_t>(rng());
  writeBytes(dir / "noise.png", noise);
  test::expectError([&] { readPng((dir / "noise.png").string()); }, {"noise.png", "not a PNG"});

  // The PNG signature followed by noise.
  const std::vector<std::uint8_t> valid = bytesOf(encodePng(randomImage(6, 6, 3, 2)));
  std::vector<std::uint8_t> signed_(valid.begin(), valid.begin() + 8);
  signed_.insert(signed_.end(), noise.begin(), noise.end());
  test::expectError([&] { decodePng(signed_, "x"); }, {"damaged PNG"});

  // Single-byte corruptions anywhere: each either still decodes (an ancillary byte) or fails
  // with an Error.
  for (size_t i = 0; i < valid.size(); ++i) {
    std::vector<std::uint8_t> bad = valid;
    bad[i] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    try {
      const Image8 im = decodePng(bad, "x");
      EXPECT_EQ(im.data.size(), static_cast<size_t>(im.width) * im.height * im.channels);
    } catch (const Error&) {
    }
  }
}

TEST(PngFile, HugeDeclaredSizeWithLittleDataFailsWithoutAllocating) {
  // A valid 1x1 PNG whose IHDR claims 16000 x 16000 (CRC fixed up so that the header parses):
  // within the pixel limit, but far more pixels than its few bytes of image data can hold.
  std::vector<std::uint8_t> bytes = bytesOf(encodePng(randomImage(1, 1, 3, 3)));
  const std::uint8_t big[4] = {0x00, 0x00, 0x3e, 0x80};  // 16000 big-endian
  std::copy(big, big + 4, bytes.begin() + 16);
  std::copy(big, big + 4, bytes.begin() + 20);
  const uLong crc = crc32(0, bytes.data() + 12, 17);  // chunk type + 13 data bytes
  for (int i = 0; i < 4; ++i) bytes[29 + i] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
  test::expectError([&] { decodePng(bytes, "big.png"); }, {"big.png", "truncated"});
}

TEST(PngFile, HighlyCompressibleImagesStillRead) {
  // All zeros compress close to deflate's limit (about 1000:1): the reader's guard against
  // headers that claim more pixels than the data can hold must not reject them.
  const Image8 black{2000, 1500, 4, std::vector<std::uint8_t>(2000u * 1500 * 4, 0)};
  const std::string bytes = encodePng(black);
  const Image8 back = decodePng(bytesOf(bytes), "black.png");
  EXPECT_EQ(back.width, 2000);
  EXPECT_EQ(back.data, black.data);
}

TEST(PngFile, MissingFileIsAnError) {
  const auto dir = test::scratchDir();
  const std::string path = (dir / "absent.png").string();
  test::expectError([&] { readPng(path); }, {"cannot open", path});
}

TEST(PngFile, WriteIntoMissingFolderFailsAndLeavesNoFile) {
  const auto dir = test::scratchDir();
  const std::string path = (dir / "no-such-folder" / "out.png").string();
  test::expectError([&] { writePng(path, randomImage(4, 4, 3, 5)); }, {"cannot write", path});
  EXPECT_FALSE(std::filesystem::exists(path));
  Image8 bad = randomImage(4, 4, 3, 5);
  bad.data.pop_back();
  test::expectError([&] { writePng((dir / "bad.png").string(), bad); }, {"bytes of pixel data"});
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace mfadvr
