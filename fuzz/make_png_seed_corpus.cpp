// Writes seed PNGs for fuzz_png: every colour type and the bit depths and options that take
// different paths through the reader (palette with tRNS, 1-bit gray, 16-bit, interlaced), so that
// mutations start from each of them. Written with libpng directly, since mfadvr itself only writes
// 8-bit RGB(A).
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image/PngFile.h"

namespace {

bool writeSeed(const std::filesystem::path& path, int w, int h, int colorType, int bitDepth,
               int interlace) {
  const int channels = colorType == PNG_COLOR_TYPE_RGB          ? 3
                       : colorType == PNG_COLOR_TYPE_RGB_ALPHA  ? 4
                       : colorType == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
                                                                : 1;
  const size_t rowBytes = (static_cast<size_t>(w) * channels * bitDepth + 7) / 8;
  std::vector<std::uint8_t> pixels(rowBytes * h);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<std::uint8_t>(i * 37 + 11);
  std::vector<png_bytep> rows(h);
  for (int y = 0; y < h; ++y) rows[y] = pixels.data() + y * rowBytes;
  png_color palette[4] = {{0, 0, 0}, {255, 0, 0}, {0, 255, 0}, {0, 0, 255}};
  png_byte alpha[2] = {0, 128};

  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return false;
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, w, h, bitDepth, colorType, interlace, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (colorType == PNG_COLOR_TYPE_PALETTE) {
    png_set_PLTE(png, info, palette, 4);
    png_set_tRNS(png, info, alpha, 2, nullptr);
  }
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fclose(f) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::filesystem::path dir = argv[1];
  std::filesystem::create_directories(dir);
  struct Kind {
    const char* name;
    int colorType, bitDepth, interlace;
  };
  const Kind kinds[] = {{"rgb8", PNG_COLOR_TYPE_RGB, 8, PNG_INTERLACE_NONE},
                        {"rgba8", PNG_COLOR_TYPE_RGB_ALPHA, 8, PNG_INTERLACE_NONE},
                        {"gray1", PNG_COLOR_TYPE_GRAY, 1, PNG_INTERLACE_NONE},
                        {"graya16", PNG_COLOR_TYPE_GRAY_ALPHA, 16, PNG_INTERLACE_NONE},
                        {"palette2", PNG_COLOR_TYPE_PALETTE, 2, PNG_INTERLACE_NONE},
                        {"rgb16-interlaced", PNG_COLOR_TYPE_RGB, 16, PNG_INTERLACE_ADAM7}};
  for (const Kind& k : kinds)
    if (!writeSeed(dir / (std::string(k.name) + ".png"), 7, 5, k.colorType, k.bitDepth,
                   k.interlace))
      return 1;
  // And one through mfadvr's own writer.
  mfadvr::Image8 im{3, 2, 4, std::vector<std::uint8_t>(24, 200)};
  mfadvr::writePng((dir / "mfadvr.png").string(), im);
  return 0;
}
