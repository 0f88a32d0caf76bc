// The built-in bitmap font: glyph placement, scaling, clipping, captions.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/image/BitmapFont.h"

namespace mfadvr {
namespace {

Image8 blank(int w, int h) {
  Image8 im;
  im.width = w;
  im.height = h;
  im.data.assign(static_cast<size_t>(w) * h * 3, 255);
  return im;
}

bool isSet(const Image8& im, int x, int y) {
  return im.data[3 * (static_cast<size_t>(y) * im.width + x)] == 0;
}

// The pixels a glyph sets, as a 5x7 string of '#' and '.'.
std::string pattern(char c) {
  Image8 im = blank(kGlyphWidth, kGlyphHeight);
  drawText(im, 0, 0, std::string(1, c), 1, {0, 0, 0});
  std::string out;
  for (int y = 0; y < kGlyphHeight; ++y)
    for (int x = 0; x < kGlyphWidth; ++x) out += isSet(im, x, y) ? '#' : '.';
  return out;
}

TEST(BitmapFont, GlyphsAreDistinctAndCoverLabels) {
  std::set<std::string> seen;
  int count = 0;
  for (int c = 32; c < 127; ++c) {
    if (!hasGlyph(static_cast<char>(c))) continue;
    ++count;
    const std::string p = pattern(static_cast<char>(c));
    EXPECT_TRUE(seen.insert(p).second) << "glyph '" << char(c) << "' repeats another";
    if (c != ' ') {
      EXPECT_NE(p.find('#'), std::string::npos) << char(c);
    }
  }
  EXPECT_GE(count, 10 + 26 + 26 + 20);
  for (char c : std::string("PSNR 31.20 dB SSIM 0.9876 MFA (p=3, 41x41x41 ctrl) truth trilinear"))
    EXPECT_TRUE(hasGlyph(c)) << c;
  EXPECT_FALSE(hasGlyph('\t'));
  EXPECT_EQ(pattern('\t'), pattern('\x01'));  // unknown characters draw the same box
  EXPECT_EQ(pattern('I'), ".###...#....#....#....#....#...###.");
}

TEST(BitmapFont, ScalesPlacesAndClips) {
  EXPECT_EQ(textWidth("", 3), 0);
  EXPECT_EQ(textWidth("ab", 1), 11);
  EXPECT_EQ(textWidth("ab", 3), 33);
  Image8 im = blank(20, 20);
  drawText(im, 2, 3, "|", 2, {0, 0, 0});
  // '|' is column 2 of the glyph: at scale 2, x = 2 + 4, 5 and rows 3 .. 3 + 13.
  EXPECT_TRUE(isSet(im, 6, 3));
  EXPECT_TRUE(isSet(im, 7, 16));
  EXPECT_FALSE(isSet(im, 5, 3));
  EXPECT_FALSE(isSet(im, 8, 3));
  EXPECT_FALSE(isSet(im, 6, 17));
  Image8 edge = blank(4, 4);
  drawText(edge, -3, -3, "W", 2, {0, 0, 0});  // clipped, not out of bounds
  EXPECT_THROW(drawText(edge, 0, 0, "x", 0, {0, 0, 0}), std::exception);
}

TEST(BitmapFont, CaptionAddsABandAndKeepsTheImage) {
  Image8 im = blank(200, 50);
  im.data[0] = 7;
  const Image8 out = withCaption(im, {"MFA", "PSNR 40.00 dB"}, 4);
  // "PSNR 40.00 dB" is 13 cells: 77 px at scale 1, so scale 2 fits 200 px and 3 does not.
  EXPECT_EQ(out.width, 200);
  EXPECT_EQ(out.height, 50 + 2 * (2 + 2 * kCellHeight + 2));
  EXPECT_EQ(out.data[0], 7);
  const Image8 narrow = withCaption(blank(20, 10), {"a long caption"}, 4);
  EXPECT_EQ(narrow.width, textWidth("a long caption", 1) + 4);  // widened, not clipped
}

}  // namespace
}  // namespace mfadvr
