// NIfTI: the declared-size check (io/DeclaredSizeCheck.h).
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

#include "core/util/Error.h"
#include "io/DeclaredSizeCheck.h"
#include "io/headers/HeaderText.h"

namespace mfadvr {

namespace fs = std::filesystem;
using namespace headers;

namespace {

template <typename T>
T readAt(const std::string& bytes, size_t at, bool swap) {
  T v{};
  if (at + sizeof(T) > bytes.size()) return v;
  unsigned char raw[sizeof(T)];
  std::copy_n(reinterpret_cast<const unsigned char*>(bytes.data()) + at, sizeof(T), raw);
  if (swap) std::reverse(raw, raw + sizeof(T));
  std::copy_n(raw, sizeof(T), reinterpret_cast<unsigned char*>(&v));
  return v;
}

}  // namespace

std::int64_t checkNiftiHeaderBytes(const std::string& header, const std::string& path,
                                   std::int64_t fileBytes, bool compressed,
                                   DeclaredPayload* payload) {
  if (header.size() < 348) return -1;  // the reader reports short headers
  bool swap = false;
  int version = 0;
  for (bool s : {false, true}) {
    const std::int32_t size = readAt<std::int32_t>(header, 0, s);
    if (size == 348) version = 1;
    if (size == 540) version = 2;
    if (version) {
      swap = s;
      break;
    }
  }
  // VTK's reader indexes its arrays with dim[0] and sizes samples from datatype without
  // checking them: a damaged header crashes it. So the fields it trusts are checked here.
  const auto fail = [&](const std::string& why) {
    throw Error("cannot read " + path + " as NIfTI: " + why +
                "; the header is damaged or not a NIfTI header");
  };
  // VTK's reader goes by the magic string, not by sizeof_hdr: a header with a wrong size would
  // reach it unchecked (fuzzing found its datatype lookup running off its table on one).
  if (version == 0)
    fail("sizeof_hdr is " + std::to_string(readAt<std::int32_t>(header, 0, false)) +
         ", not 348 (NIfTI-1, Analyze) or 540 (NIfTI-2)");
  // The magic must say the same as sizeof_hdr: VTK's reader takes a header for NIfTI-1 by its
  // magic at byte 344 whatever sizeof_hdr says (fuzzing found it dereferencing null on a file of
  // 473 bytes with sizeof_hdr 540 and NIfTI-1's magic).
  const auto magicAt = [&](size_t at, char digit) {
    return header.size() >= at + 4 && (header[at] == 'n') &&
           (header[at + 1] == '+' || header[at + 1] == 'i') && header[at + 2] == digit &&
           header[at + 3] == '\0';
  };
  const bool magic1 = magicAt(344, '1'), magic2 = magicAt(4, '2');
  if (version == 2 && !magic2)
    fail(std::string("sizeof_hdr is 540 (NIfTI-2), but the header lacks NIfTI-2's magic "
                     "(n+2 or ni2 at byte 4)") +
         (magic1 ? " and has NIfTI-1's" : ""));
  if (version == 1 && magic2)
    fail("sizeof_hdr is 348 (NIfTI-1), but the header has NIfTI-2's magic");
  if (version == 2 && header.size() < 540)
    fail("the header is cut off: the file holds " + std::to_string(header.size()) +
         " of its 540 bytes");
  std::vector<std::int64_t> dims;
  std::int64_t bitpix = 0, voxOffset = 0, datatype = 0, rank = 0;
  if (version == 1) {
    rank = readAt<std::int16_t>(header, 40, swap);
    if (rank < 1 || rank > 7) fail("dim[0] is " + std::to_string(rank) + ", not 1..7");
    for (int d = 1; d <= rank; ++d)
      dims.push_back(readAt<std::int16_t>(header, 40 + 2 * static_cast<size_t>(d), swap));
    datatype = readAt<std::int16_t>(header, 70, swap);
    bitpix = readAt<std::int16_t>(header, 72, swap);
    const float offset = readAt<float>(header, 108, swap);
    if (!(offset >= 0.0f && offset < 1e12f)) fail("vox_offset is not a valid offset");
    voxOffset = static_cast<std::int64_t>(offset);
  } else {
    rank = readAt<std::int64_t>(header, 16, swap);
    if (rank < 1 || rank > 7) fail("dim[0] is " + std::to_string(rank) + ", not 1..7");
    for (std::int64_t d = 1; d <= rank; ++d)
      dims.push_back(readAt<std::int64_t>(header, 16 + 8 * static_cast<size_t>(d), swap));
    datatype = readAt<std::int16_t>(header, 12, swap);
    bitpix = readAt<std::int16_t>(header, 14, swap);
    voxOffset = readAt<std::int64_t>(header, 168, swap);
    if (voxOffset < 0) fail("vox_offset is negative");
  }
  for (size_t d = 0; d < dims.size(); ++d)
    if (dims[d] < 1)
      fail("dim[" + std::to_string(d + 1) + "] is " + std::to_string(dims[d]) + ", not >= 1");
  // The NIfTI datatype codes and their bits per sample.
  static const std::pair<int, int> kTypes[] = {{2, 8},      {4, 16},     {8, 32},     {16, 32},
                                               {32, 64},    {64, 64},    {128, 24},   {256, 8},
                                               {512, 16},   {768, 32},   {1024, 64},  {1280, 64},
                                               {1536, 128}, {1792, 128}, {2048, 256}, {2304, 32}};
  int expectedBits = 0;
  for (const auto& [code, bits] : kTypes)
    if (code == datatype) expectedBits = bits;
  if (expectedBits == 0) fail("datatype " + std::to_string(datatype) + " is not a NIfTI type");
  if (bitpix != expectedBits)
    fail("bitpix is " + std::to_string(bitpix) + ", but datatype " + std::to_string(datatype) +
         " has " + std::to_string(expectedBits) + " bits");
  if (dims.empty() || bitpix <= 0 || bitpix % 8 != 0) return -1;
  if (std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d <= 0; })) return -1;
  // For a .hdr/.img pair, fileBytes is the .img's size (vox_offset is an offset into it).
  requireData(path, "NIfTI", dimsText(dims) + " samples of " + std::to_string(bitpix) + " bits",
              product(dims), bitpix / 8, compressed ? Encoding::Deflate : Encoding::Binary,
              fileBytes - (compressed ? 0 : voxOffset),
              compressed ? "the compressed file" : "the file after vox_offset");
  const std::int64_t data = times(product(dims), bitpix / 8);
  if (payload) {
    static const std::pair<int, const char*> kRawTypes[] = {
        {2, "uint8"},    {4, "int16"},  {8, "int32"},    {16, "float32"},
        {64, "float64"}, {256, "int8"}, {512, "uint16"}, {768, "uint32"}};
    for (const auto& [code, raw] : kRawTypes) {
      if (code != datatype) continue;
      payload->file = path;
      payload->gzipAt = compressed ? 0 : -1;
      payload->offset = voxOffset;
      payload->dtype = raw;
      // The header is stored in the file's byte order.
      payload->bigEndian = swap != (std::endian::native == std::endian::big);
      payload->sizes = dims;
    }
  }
  return data > std::numeric_limits<std::int64_t>::max() - voxOffset
             ? std::numeric_limits<std::int64_t>::max()
             : voxOffset + data;
}

DeclaredPayload checkNiftiDeclaredSize(const std::string& path) {
  // zlib reads plain files through gzopen too: the magic bytes, not the name, say which.
  const std::string magic = readHead(path, 2);
  const bool gz = magic.size() == 2 && magic[0] == '\x1f' && magic[1] == '\x8b';
  std::string header;
  if (gz) {
    gzFile in = gzopen(path.c_str(), "rb");
    if (!in) return {};
    header.resize(540);
    const int got = gzread(in, header.data(), 540);
    gzclose(in);
    header.resize(got > 0 ? static_cast<size_t>(got) : 0);
  } else {
    header = readHead(path, 540);
  }
  std::int64_t size = fileSize(path);
  const fs::path p(path);
  const std::string ext = lower(p.extension().string());
  if (ext == ".hdr" || ext == ".img") {
    // Analyze / NIfTI pair: the header in .hdr, the samples (from byte 0) in .img.
    fs::path hdr = p, img = p;
    hdr.replace_extension(p.extension().string() == ".IMG" ? ".HDR" : ".hdr");
    img.replace_extension(p.extension().string() == ".HDR" ? ".IMG" : ".img");
    header = readHead(hdr.string(), 540);
    size = fileSize(img.string());
    if (size < 0)
      throw Error("cannot read " + path + " as NIfTI: the image file " + img.string() +
                  " of the .hdr/.img pair does not exist");
    // vox_offset of a pair is an offset into the .img (usually 0).
    DeclaredPayload payload;
    checkNiftiHeaderBytes(header, img.string(), size, false, &payload);
    return payload;
  }
  DeclaredPayload payload;
  const std::int64_t expected = checkNiftiHeaderBytes(header, path, size, gz, &payload);
  // VTK's reader stops at the end of the deflate data and never looks at the gzip trailer.
  if (gz && expected > 0) requireCompleteGzip(path, "NIfTI", path, 0, expected);
  return payload;
}

}  // namespace mfadvr
