// libpng reports errors by longjmp. Every function here that calls setjmp keeps only trivially
// destructible locals in its own frame and touches C++ objects only through pointers to objects
// owned by its caller, so that a longjmp back into it skips no destructor and reads no
// indeterminate local. Callbacks never let a C++ exception cross libpng's C frames.
#include "core/image/PngFile.h"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstring>
#include <fstream>
#include <iterator>
#include <new>
#include <vector>

#include "core/util/AtomicFile.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// What the libpng callbacks share with the calling code.
struct PngContext {
  char message[256] = "";
  // Reading: the whole file in memory.
  const std::uint8_t* input = nullptr;
  size_t inputSize = 0;
  size_t inputPos = 0;
  // Writing: the encoded bytes.
  std::string* output = nullptr;
};

PngContext& contextOf(png_structp png) {
  return *static_cast<PngContext*>(png_get_error_ptr(png));
}

[[noreturn]] void onError(png_structp png, png_const_charp message) {
  PngContext& ctx = contextOf(png);
  std::strncpy(ctx.message, message ? message : "libpng error", sizeof ctx.message - 1);
  ctx.message[sizeof ctx.message - 1] = '\0';
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}  // benign (e.g. bad ancillary chunk CRC)

void readFromMemory(png_structp png, png_bytep out, size_t length) {
  PngContext& ctx = *static_cast<PngContext*>(png_get_io_ptr(png));
  if (length > ctx.inputSize - ctx.inputPos) png_error(png, "file is truncated");
  std::memcpy(out, ctx.input + ctx.inputPos, length);
  ctx.inputPos += length;
}

void writeToMemory(png_structp png, png_bytep data, size_t length) {
  PngContext& ctx = *static_cast<PngContext*>(png_get_io_ptr(png));
  bool failed = false;
  try {
    ctx.output->append(reinterpret_cast<const char*>(data), length);
  } catch (...) {
    failed = true;
  }
  if (failed) png_error(png, "out of memory");  // outside the handler: never longjmp out of one
}

void flushNothing(png_structp) {}

// The decoded image goes into `*out` (owned by the caller); `rows` likewise.
bool decodeWithLibpng(PngContext* ctx, Image8* out, std::vector<png_bytep>* rows) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, ctx, onError, onWarning);
  if (!png) {
    std::strcpy(ctx->message, "cannot initialize libpng");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    std::strcpy(ctx->message, "cannot initialize libpng");
    return false;
  }
  // png and info are not modified after setjmp, so their values are reliable after a longjmp.
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, ctx, readFromMemory);
  png_set_user_limits(png, 1u << 20, 1u << 20);
  png_read_info(png, info);

  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  const int colorType = png_get_color_type(png, info);
  const int bitDepth = png_get_bit_depth(png, info);
  if (static_cast<std::int64_t>(width) > kMaxImagePixels / static_cast<std::int64_t>(height))
    png_error(png, "image too large");
  // Deflate expands at most about 1032:1, so a file this short cannot hold this many pixels:
  // refuse before allocating memory for them (a damaged header must not cost gigabytes).
  const std::uint64_t rawBytes =
      (static_cast<std::uint64_t>(width) * bitDepth * png_get_channels(png, info) + 7) / 8 * height;
  if (rawBytes > 1100 * static_cast<std::uint64_t>(ctx->inputSize) + 65536)
    png_error(png, "file is truncated (too little image data for its size)");

  if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (bitDepth == 16) png_set_scale_16(png);
  if (colorType == PNG_COLOR_TYPE_GRAY || colorType == PNG_COLOR_TYPE_GRAY_ALPHA)
    png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);

  const int channels = png_get_channels(png, info);
  if ((channels != 3 && channels != 4) || png_get_bit_depth(png, info) != 8)
    png_error(png, "unexpected pixel layout after conversion");
  if (png_get_rowbytes(png, info) != static_cast<size_t>(channels) * width)
    png_error(png, "unexpected row size after conversion");
  out->width = static_cast<int>(width);
  out->height = static_cast<int>(height);
  out->channels = channels;
  bool outOfMemory = false;
  try {
    out->data.resize(static_cast<size_t>(channels) * width * height);
    rows->resize(height);
  } catch (const std::bad_alloc&) {
    outOfMemory = true;
  }
  if (outOfMemory) png_error(png, "out of memory");  // outside the handler, as in writeToMemory
  for (png_uint_32 y = 0; y < height; ++y)
    (*rows)[y] = out->data.data() + static_cast<size_t>(y) * channels * width;
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

bool encodeWithLibpng(PngContext* ctx, const Image8* image, std::vector<png_bytep>* rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, ctx, onError, onWarning);
  if (!png) {
    std::strcpy(ctx->message, "cannot initialize libpng");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::strcpy(ctx->message, "cannot initialize libpng");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, ctx, writeToMemory, flushNothing);
  png_set_IHDR(png, info, image->width, image->height, 8,
               image->channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows->data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::string encodePng(const Image8& image) {
  checkImage8(image, "PNG image");
  std::string bytes;
  std::vector<png_bytep> rows(image.height);
  const size_t stride = static_cast<size_t>(image.channels) * image.width;
  for (int y = 0; y < image.height; ++y)
    // libpng does not write through row pointers; its API just lacks const.
    rows[y] = const_cast<png_bytep>(image.data.data() + y * stride);
  PngContext ctx;
  ctx.output = &bytes;
  if (!encodeWithLibpng(&ctx, &image, &rows))
    throw Error(std::string("cannot encode PNG: ") + ctx.message);
  return bytes;
}

Image8 decodePng(std::span<const std::uint8_t> bytes, const std::string& name) {
  if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0)
    throw Error(name + ": not a PNG file");
  PngContext ctx;
  ctx.input = bytes.data();
  ctx.inputSize = bytes.size();
  Image8 image;
  std::vector<png_bytep> rows;
  if (!decodeWithLibpng(&ctx, &image, &rows))
    throw Error(name + ": damaged PNG file: " + ctx.message);
  return image;
}

void writePng(const std::string& path, const Image8& image) {
  writeFileAtomically(path, encodePng(image));
}

Image8 readPng(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path + ": " + std::strerror(errno));
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  if (in.bad()) throw Error("cannot read " + path);
  return decodePng(bytes, path);
}

}  // namespace mfadvr
