#include "io/DeclaredSizeCheck.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;

// Deflate cannot expand data more than about 1032 times.
constexpr std::int64_t kMaxDeflateRatio = 1032;
// Headers are small; a "header" longer than this is not one.
constexpr size_t kMaxHeaderBytes = 1 << 16;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

// Header text holds no control characters but tabs and carriage returns; VTK's readers loop
// forever or corrupt memory on some of the others.
bool hasControlCharacters(const std::string& line) {
  return std::any_of(line.begin(), line.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r';
  });
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

// A non-negative integer that fits, or -1.
std::int64_t parseCount(const std::string& text) {
  std::int64_t v = -1;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || v < 0) return -1;
  return v;
}

// Product of counts, saturating at int64 max (an absurd header must not wrap around).
std::int64_t product(const std::vector<std::int64_t>& counts) {
  std::int64_t p = 1;
  for (std::int64_t c : counts) {
    if (c == 0) return 0;
    if (p > std::numeric_limits<std::int64_t>::max() / c)
      return std::numeric_limits<std::int64_t>::max();
    p *= c;
  }
  return p;
}

std::int64_t times(std::int64_t a, std::int64_t b) {
  return product({a, b});
}

std::string grouped(std::int64_t v) {
  std::string digits = std::to_string(v), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string dimsText(const std::vector<std::int64_t>& counts) {
  std::string out;
  for (size_t i = 0; i < counts.size(); ++i) out += (i ? " x " : "") + std::to_string(counts[i]);
  return out;
}

std::int64_t fileSize(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  return ec ? -1 : static_cast<std::int64_t>(size);
}

std::string readHead(const std::string& path, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string out(bytes, '\0');
  in.read(out.data(), static_cast<std::streamsize>(bytes));
  out.resize(static_cast<size_t>(in.gcount()));
  return out;
}

std::string readTail(const std::string& path, std::int64_t size, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  const std::int64_t start = std::max<std::int64_t>(0, size - static_cast<std::int64_t>(bytes));
  in.seekg(start);
  std::string out(static_cast<size_t>(size - start), '\0');
  in.read(out.data(), static_cast<std::streamsize>(out.size()));
  out.resize(static_cast<size_t>(in.gcount()));
  return out;
}

// Whether the gzip data of `path` from byte `offset` on is complete and inflates to at least
// `expected` bytes. The last 4 bytes of a gzip stream hold the uncompressed size (mod 2^32):
// when they match, the stream ends where it should (the common, cheap case). Otherwise, e.g.
// for several concatenated gzip members, the data is inflated to find out; zlib checks each
// member's CRC on the way.
void requireCompleteGzip(const std::string& path, const std::string& format,
                         const std::string& file, std::int64_t offset, std::int64_t expected) {
  const std::int64_t size = fileSize(file);
  if (size < 0) return;
  if (size - offset >= 18) {
    const std::string tail = readTail(file, size, 4);
    const std::uint32_t isize =
        std::uint32_t(std::uint8_t(tail[0])) | std::uint32_t(std::uint8_t(tail[1])) << 8 |
        std::uint32_t(std::uint8_t(tail[2])) << 16 | std::uint32_t(std::uint8_t(tail[3])) << 24;
    if (isize == static_cast<std::uint32_t>(expected)) return;
  }
  std::ifstream in(file, std::ios::binary);
  in.seekg(offset);
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) return;  // gzip or zlib header
  std::vector<char> input(1 << 16);
  std::vector<unsigned char> output(1 << 16);
  const auto refill = [&] {
    in.read(input.data(), static_cast<std::streamsize>(input.size()));
    z.next_in = reinterpret_cast<Bytef*>(input.data());
    z.avail_in = static_cast<uInt>(in.gcount());
  };
  std::int64_t total = 0;
  int status = Z_OK;
  for (;;) {
    if (z.avail_in == 0) refill();
    if (z.avail_in == 0) break;  // out of input before the stream's end: cut off
    z.next_out = output.data();
    z.avail_out = static_cast<uInt>(output.size());
    status = inflate(&z, Z_NO_FLUSH);
    total += static_cast<std::int64_t>(output.size() - z.avail_out);
    if (status == Z_STREAM_END) {
      if (z.avail_in == 0) refill();
      if (z.avail_in == 0) break;  // the clean end
      inflateReset(&z);            // another gzip member follows
      status = Z_OK;
    } else if (status != Z_OK && status != Z_BUF_ERROR) {
      break;
    }
  }
  const std::string message = z.msg ? z.msg : "the stream ends early";
  inflateEnd(&z);
  if (status != Z_STREAM_END) {
    throw Error("cannot read " + path + " as " + format +
                ": its gzip data is cut off or corrupt (" + message + " after " + grouped(total) +
                " bytes)");
  }
  if (total < expected) {
    throw Error("cannot read " + path + " as " + format + ": its gzip data inflates to " +
                grouped(total) + " bytes, but the header declares " + grouped(expected));
  }
}

DataFileSize dataFilesBeside(const std::string& path) {
  return [dir = fs::path(path).parent_path()](const std::string& name) {
    const fs::path p(name);
    return fileSize((p.is_absolute() ? p : dir / p).string());
  };
}

// Binary: at least the declared bytes (more data may follow); ExactBinary: exactly them (a
// header then its raw data, nothing else: a different size means a wrong header).
enum class Encoding { Binary, ExactBinary, Ascii, Hex, Deflate, Unknown };

// What the declared samples need, against what the file holds: throws when they cannot fit.
void requireData(const std::string& path, const std::string& format, const std::string& declared,
                 std::int64_t samples, std::int64_t sampleBytes, Encoding encoding,
                 std::int64_t available, const std::string& where) {
  if (available < 0) return;
  const std::int64_t bytes = times(samples, sampleBytes);
  std::string need;
  bool fits = true;
  switch (encoding) {
    case Encoding::Binary:
      fits = bytes <= available;
      need = grouped(bytes) + " bytes";
      break;
    case Encoding::ExactBinary:
      fits = bytes == available;
      need = grouped(bytes) + " bytes";
      break;
    case Encoding::Hex:
      fits = times(bytes, 2) <= available;
      need = grouped(times(bytes, 2)) + " hex digits";
      break;
    case Encoding::Ascii:
      // n values need at least n digits and n - 1 separators.
      fits = samples <= 0 || times(samples, 2) - 1 <= available;
      need = "at least " + grouped(std::max<std::int64_t>(0, times(samples, 2) - 1)) +
             " characters of text";
      break;
    case Encoding::Deflate:
      fits = bytes <= times(available, kMaxDeflateRatio);
      need =
          grouped(bytes) + " bytes, more than " + grouped(available) + " compressed bytes can hold";
      break;
    case Encoding::Unknown:
      return;
  }
  if (fits) return;
  throw Error("cannot read " + path + " as " + format + ": the header declares " + declared + " (" +
              need + "), but " + where + " holds " + (available < bytes ? "only " : "") +
              grouped(available) + " bytes; the file is " +
              (available < bytes ? "truncated" : "longer than declared") +
              " or its header is wrong");
}

// ---- NRRD -------------------------------------------------------------------------------------

std::int64_t nrrdTypeBytes(const std::string& type) {
  static const std::pair<const char*, int> kTypes[] = {{"signed char", 1},
                                                       {"int8", 1},
                                                       {"int8_t", 1},
                                                       {"uchar", 1},
                                                       {"unsigned char", 1},
                                                       {"uint8", 1},
                                                       {"uint8_t", 1},
                                                       {"short", 2},
                                                       {"short int", 2},
                                                       {"signed short", 2},
                                                       {"signed short int", 2},
                                                       {"int16", 2},
                                                       {"int16_t", 2},
                                                       {"ushort", 2},
                                                       {"unsigned short", 2},
                                                       {"unsigned short int", 2},
                                                       {"uint16", 2},
                                                       {"uint16_t", 2},
                                                       {"int", 4},
                                                       {"signed int", 4},
                                                       {"int32", 4},
                                                       {"int32_t", 4},
                                                       {"uint", 4},
                                                       {"unsigned int", 4},
                                                       {"uint32", 4},
                                                       {"uint32_t", 4},
                                                       {"longlong", 8},
                                                       {"long long", 8},
                                                       {"long long int", 8},
                                                       {"signed long long", 8},
                                                       {"signed long long int", 8},
                                                       {"int64", 8},
                                                       {"int64_t", 8},
                                                       {"ulonglong", 8},
                                                       {"unsigned long long", 8},
                                                       {"unsigned long long int", 8},
                                                       {"uint64", 8},
                                                       {"uint64_t", 8},
                                                       {"float", 4},
                                                       {"double", 8}};
  for (const auto& [name, bytes] : kTypes)
    if (type == name) return bytes;
  return 0;
}

}  // namespace

NrrdDataLocation checkNrrdHeaderText(const std::string& header, const std::string& path,
                                     std::int64_t fileBytes, const DataFileSize& dataFileBytes) {
  // VTK's reader loops forever on a magic line without its line break and crashes on headers
  // without the basic fields, so the header is checked here in full before it runs.
  const auto fail = [&](const std::string& why) {
    throw Error("cannot read " + path + " as NRRD: " + why);
  };
  const auto firstBreak = header.find('\n');
  if (header.compare(0, 7, "NRRD000") != 0 || header.size() < 9 || header[7] < '1' ||
      header[7] > '5' || firstBreak == std::string::npos ||
      trim(header.substr(0, firstBreak)).size() != 8)
    fail("the first line is not a NRRD magic line (NRRD0001 .. NRRD0005, then a line break)");
  std::istringstream in(header);
  std::string line;
  std::getline(in, line);
  std::int64_t headerBytes = static_cast<std::int64_t>(line.size()) + 1;
  bool ended = false;
  std::string type, encoding, dataFile, dimension;
  std::vector<std::int64_t> sizes;
  std::vector<std::string> spacings;
  bool sizesGiven = false;
  std::int64_t byteSkip = 0;
  bool skipped = false;
  while (std::getline(in, line)) {
    headerBytes += static_cast<std::int64_t>(line.size()) + 1;
    if (trim(line).empty()) {
      ended = true;
      break;
    }
    // VTK's reader loops forever on some control characters (a NUL) in the header.
    if (hasControlCharacters(line))
      fail("the header holds control characters: it is not a NRRD text header");
    if (line[0] == '#') continue;
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;  // key:=value pairs
    // Field names are case-sensitive (VTK's reader, too, knows only these spellings).
    const std::string key = trim(line.substr(0, colon));
    const std::string value = trim(line.substr(colon + 2));
    if (key == "type") {
      type = value;
    } else if (key == "spacings") {
      spacings = words(value);
    } else if (key == "dimension") {
      dimension = value;
    } else if (key == "sizes") {
      sizesGiven = true;
      sizes.clear();
      for (const auto& w : words(value)) sizes.push_back(parseCount(w));
    } else if (key == "encoding") {
      encoding = value;
    } else if (key == "data file" || key == "datafile") {
      dataFile = value;
    } else if (key == "byte skip" || key == "byteskip") {
      byteSkip = value == "-1" ? -1 : parseCount(value);
      if (byteSkip < -1) fail("byte skip '" + value + "' is not a count (or -1)");
      skipped = true;
    } else if (key == "line skip" || key == "lineskip") {
      if (parseCount(value) < 0) fail("line skip '" + value + "' is not a count");
      skipped = true;
    }
  }
  std::string missing;
  for (const auto& [name, value] :
       {std::pair{"type", type}, {"dimension", dimension}, {"encoding", encoding}})
    if (value.empty()) missing += std::string(missing.empty() ? "" : ", ") + name;
  if (!sizesGiven) missing += std::string(missing.empty() ? "" : ", ") + "sizes";
  if (!missing.empty()) fail("the header lacks the required field(s) " + missing);
  const std::int64_t typeBytes = nrrdTypeBytes(type);
  if (typeBytes == 0) fail("type '" + type + "' is not a scalar type VTK's NRRD reader reads");
  const std::int64_t dims = parseCount(dimension);
  if (dims < 1 || dims > 16) fail("dimension '" + dimension + "' is not between 1 and 16");
  if (static_cast<std::int64_t>(sizes.size()) != dims ||
      std::any_of(sizes.begin(), sizes.end(), [](std::int64_t v) { return v < 1; }))
    fail("sizes must be " + std::to_string(dims) + " positive integers (dimension: " + dimension +
         ")");
  // VTK's reader crashes on spacings it cannot parse.
  if (!spacings.empty()) {
    if (static_cast<std::int64_t>(spacings.size()) != dims)
      fail("spacings must be " + std::to_string(dims) + " numbers (dimension: " + dimension + ")");
    for (const std::string& w : spacings) {
      double v = 0.0;
      const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
      if (lower(w) != "nan" && (r.ec != std::errc() || r.ptr != w.data() + w.size()))
        fail("spacings holds '" + w + "', which is not a number");
    }
  }
  Encoding enc = Encoding::Unknown;
  if (encoding == "raw") enc = Encoding::ExactBinary;
  if (encoding == "gzip" || encoding == "gz") enc = Encoding::Deflate;
  if (encoding == "ascii" || encoding == "txt" || encoding == "text") enc = Encoding::Ascii;
  if (enc == Encoding::Unknown)
    fail("encoding '" + encoding + "' is not one VTK's NRRD reader reads (raw, gzip, ascii)");
  if (!ended && dataFile.empty())
    fail("the header does not end with the blank line that separates it from the data");
  // Skips make the data start somewhere the header does not say exactly (-1: at the end).
  if (skipped && (byteSkip < 0 || enc != Encoding::ExactBinary)) return {};

  std::int64_t available = -1;
  std::string where;
  if (!dataFile.empty()) {
    // "LIST" and "%d"-pattern forms name several files: left to the reader.
    if (dataFile.rfind("LIST", 0) == 0 || dataFile.find(' ') != std::string::npos) return {};
    const std::int64_t size = dataFileBytes(dataFile);
    if (size < 0)
      fail("its data file '" + dataFile + "' (\"data file:\" in the header) does not exist");
    available = size - byteSkip;
    where = "its data file '" + dataFile + "'";
  } else {
    available = fileBytes - headerBytes - byteSkip;
    where = "the file after its header";
  }
  requireData(path, "NRRD", dimsText(sizes) + " " + type + " samples in " + encoding + " encoding",
              product(sizes), typeBytes, enc, std::max<std::int64_t>(0, available), where);
  if (enc != Encoding::Ascii && enc != Encoding::Deflate) return {};
  return {dataFile,
          dataFile.empty() ? headerBytes : 0,
          product(sizes),
          times(product(sizes), typeBytes),
          enc == Encoding::Deflate,
          dimsText(sizes) + " " + type + " samples"};
}

namespace {

// What separates the values of ASCII data (NRRD allows commas besides white space).
bool asciiSeparator(char c) {
  return std::isspace(static_cast<unsigned char>(c)) || c == ',';
}

// Whitespace- or comma-separated values in `path` from byte `offset` on, counting at most
// `limit`.
std::int64_t countValues(const std::string& path, std::int64_t offset, std::int64_t limit) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(offset);
  std::vector<char> buffer(1 << 20);
  std::int64_t count = 0;
  bool inValue = false;
  while (in && count < limit) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const size_t got = static_cast<size_t>(in.gcount());
    for (size_t i = 0; i < got; ++i) {
      const bool separator = asciiSeparator(buffer[i]);
      if (!separator && !inValue) ++count;
      inValue = !separator;
    }
  }
  return count;
}

}  // namespace

NrrdAsciiData checkNrrdDeclaredSize(const std::string& path) {
  const NrrdDataLocation data = checkNrrdHeaderText(readHead(path, kMaxHeaderBytes), path,
                                                    fileSize(path), dataFilesBeside(path));
  if (data.values <= 0) return {};
  fs::path file(path);
  if (!data.dataFile.empty()) {
    file = fs::path(data.dataFile);
    if (!file.is_absolute()) file = fs::path(path).parent_path() / file;
  }
  if (data.gzip) {
    // VTK's reader stops at the end of the deflate data and never looks at the gzip trailer.
    requireCompleteGzip(path, "NRRD", file.string(), data.offset, data.bytes);
    return {};
  }
  // VTK's reader fills values missing from ASCII data with zeros: count them first. A cut
  // inside the last value leaves the count right, so the data must also end with white space
  // (every writer ends it with a line break).
  const std::int64_t size = fileSize(file.string());
  const std::string last = size > 0 ? readTail(file.string(), size, 1) : std::string();
  if (last.empty() || !std::isspace(static_cast<unsigned char>(last[0]))) {
    throw Error("cannot read " + path +
                " as NRRD: its ascii data does not end with a line break, so it may be cut off "
                "inside its last value; if the file is complete, end it with a line break");
  }
  const std::int64_t found = countValues(file.string(), data.offset, data.values);
  if (found < data.values) {
    throw Error("cannot read " + path + " as NRRD: the header declares " + data.declared + " (" +
                grouped(data.values) + " values in ascii encoding), but the data holds " +
                grouped(found) + "; the file is truncated or its header is wrong");
  }
  return {file.string(), data.offset};
}

std::vector<double> readAsciiValues(const std::string& path, std::int64_t offset,
                                    std::int64_t count) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(offset);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw Error("cannot read " + path);
  std::vector<double> values;
  values.reserve(static_cast<size_t>(count));
  const char* p = text.data();
  const char* end = p + text.size();
  while (static_cast<std::int64_t>(values.size()) < count) {
    while (p < end && asciiSeparator(*p)) ++p;
    if (p == end) break;
    const char* token = p;
    while (p < end && !asciiSeparator(*p)) ++p;
    double v = 0.0;
    const auto [stop, ec] = std::from_chars(token + (*token == '+'), p, v);
    if (ec != std::errc() || stop != p) {
      throw Error("cannot read " + path + ": '" +
                  std::string(token, std::min<size_t>(p - token, 40)) +
                  "' in its ascii data (value " + grouped(std::int64_t(values.size()) + 1) +
                  ") is not a number");
    }
    values.push_back(v);
  }
  if (static_cast<std::int64_t>(values.size()) < count) {
    throw Error("cannot read " + path + ": its ascii data holds " + grouped(values.size()) +
                " values, " + grouped(count) + " expected");
  }
  return values;
}

// ---- MetaImage --------------------------------------------------------------------------------

namespace {

std::int64_t metaTypeBytes(const std::string& type) {
  static const std::pair<const char*, int> kTypes[] = {
      {"MET_CHAR", 1},      {"MET_UCHAR", 1},      {"MET_SHORT", 2}, {"MET_USHORT", 2},
      {"MET_INT", 4},       {"MET_UINT", 4},       {"MET_LONG", 4},  {"MET_ULONG", 4},
      {"MET_LONG_LONG", 8}, {"MET_ULONG_LONG", 8}, {"MET_FLOAT", 4}, {"MET_DOUBLE", 8}};
  for (const auto& [name, bytes] : kTypes)
    if (type == name) return bytes;
  return 0;
}

}  // namespace

void checkMetaImageHeaderText(const std::string& header, const std::string& path,
                              std::int64_t fileBytes, const DataFileSize& dataFileBytes) {
  // VTK's MetaIO corrupts its heap on some damaged headers (a missing NDims in a cut header):
  // the header is checked line by line before it runs.
  const auto fail = [&](const std::string& why) {
    throw Error("cannot read " + path + " as MetaImage: " + why +
                " (expected 'Key = Value' lines with NDims, DimSize, ElementType and, last, "
                "ElementDataFile)");
  };
  std::istringstream in(header);
  std::string line;
  std::int64_t headerBytes = 0;
  std::vector<std::int64_t> dims;
  std::string type, dataFile, ndims;
  std::int64_t channels = 1, headerSize = 0;
  bool compressed = false, binary = true;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    headerBytes += static_cast<std::int64_t>(line.size()) + 1;
    if (hasControlCharacters(line))
      fail("header line " + std::to_string(lineNumber) + " holds control characters");
    if (trim(line).empty()) continue;
    const auto eq = line.find('=');
    if (eq == std::string::npos)
      fail("header line " + std::to_string(lineNumber) + " is not 'Key = Value'");
    const std::string key = trim(line.substr(0, eq));
    const std::string value = trim(line.substr(eq + 1));
    if (key == "NDims") {
      ndims = value;
    } else if (key == "DimSize") {
      dims.clear();
      for (const auto& w : words(value)) dims.push_back(parseCount(w));
    } else if (key == "ElementType") {
      type = value;
    } else if (key == "ElementNumberOfChannels") {
      channels = parseCount(value);
      if (channels < 1 || channels > 64)
        fail("ElementNumberOfChannels '" + value + "' is not 1..64");
    } else if (key == "CompressedData") {
      compressed = lower(value) == "true";
    } else if (key == "BinaryData") {
      binary = lower(value) != "false";
    } else if (key == "HeaderSize") {
      headerSize = parseCount(value);  // -1 (data at the end) parses as invalid: skip below
    } else if (key == "ElementDataFile") {
      dataFile = value;
      break;  // the last header line
    }
  }
  if (dataFile.empty()) fail("the header has no ElementDataFile line");
  const std::int64_t rank = parseCount(ndims);
  if (rank < 1 || rank > 10) fail("NDims '" + ndims + "' is not 1..10");
  if (static_cast<std::int64_t>(dims.size()) != rank ||
      std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d < 1; }))
    fail("DimSize must be " + ndims + " positive integers (NDims = " + ndims + ")");
  if (metaTypeBytes(type) == 0) fail("ElementType '" + type + "' is not a MET_ scalar type");
  if (dataFile.empty() || dims.empty() || channels <= 0) return;
  const std::int64_t typeBytes = metaTypeBytes(type);
  if (typeBytes == 0 || std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d < 0; }))
    return;
  std::int64_t available = 0;
  std::string where;
  if (dataFile == "LOCAL") {
    available = fileBytes - headerBytes;
    where = "the file after its header";
  } else {
    if (dataFile == "LIST" || dataFile.find(' ') != std::string::npos ||
        dataFile.find('%') != std::string::npos)
      return;
    const std::int64_t size = dataFileBytes(dataFile);
    if (size < 0)
      throw Error("cannot read " + path + " as MetaImage: its data file '" + dataFile +
                  "' (ElementDataFile = " + dataFile + ") does not exist");
    if (headerSize < 0) return;
    available = size - headerSize;
    where = "its data file '" + dataFile + "'";
  }
  const Encoding enc = compressed ? Encoding::Deflate
                       : binary   ? Encoding::ExactBinary
                                  : Encoding::Ascii;
  requireData(path, "MetaImage",
              dimsText(dims) + " " + type + " samples" +
                  (channels > 1 ? " of " + std::to_string(channels) + " channels" : "") +
                  (compressed ? ", compressed" : ""),
              times(product(dims), channels), typeBytes, enc, std::max<std::int64_t>(0, available),
              where);
}

void checkMetaImageDeclaredSize(const std::string& path) {
  checkMetaImageHeaderText(readHead(path, kMaxHeaderBytes), path, fileSize(path),
                           dataFilesBeside(path));
}

// ---- legacy VTK -------------------------------------------------------------------------------

namespace {

std::int64_t legacyTypeBytes(const std::string& type) {
  static const std::pair<const char*, int> kTypes[] = {
      {"bit", 0},       {"char", 1},           {"signed_char", 1},  {"unsigned_char", 1},
      {"short", 2},     {"unsigned_short", 2}, {"int", 4},          {"unsigned_int", 4},
      {"long", 8},      {"unsigned_long", 8},  {"vtktypeint64", 8}, {"vtktypeuint64", 8},
      {"vtkidtype", 8}, {"float", 4},          {"double", 8}};
  const std::string t = lower(type);
  for (const auto& [name, bytes] : kTypes)
    if (t == name) return bytes;
  return 0;
}

// What VTK's legacy reader reads before the dataset: the version line ('# vtk DataFile
// Version x.y', any version), one title line (any text, also empty), then the first word after
// it, ASCII or BINARY in any case: VTK skips blank lines (and spaces, CR line ends) before it.
// Leaves `in` at the start of the line after that word.
struct LegacyPreamble {
  bool valid = false;  // a legacy header with a known file type
  bool binary = false;
  std::string version;  // "3.0", "5.1", ...
};

LegacyPreamble readLegacyPreamble(std::istream& in) {
  LegacyPreamble p;
  std::string line;
  if (!std::getline(in, line) || line.rfind("# vtk DataFile", 0) != 0) return p;
  const auto at = line.find("Version");
  if (at != std::string::npos) p.version = trim(line.substr(at + 7));
  if (!std::getline(in, line)) return p;  // the title
  std::string type;
  if (!(in >> type)) return p;
  type = lower(type);
  if (type != "ascii" && type != "binary") return p;
  std::getline(in, line);  // the rest of the file type's line
  p.binary = type == "binary";
  p.valid = static_cast<bool>(in);
  return p;
}

}  // namespace

void checkLegacyVtkHeaderText(const std::string& header, const std::string& path,
                              std::int64_t fileBytes) {
  std::istringstream in(header);
  const LegacyPreamble preamble = readLegacyPreamble(in);
  if (!preamble.valid) return;
  const Encoding enc = preamble.binary ? Encoding::Binary : Encoding::Ascii;
  // Bytes of the header consumed so far (the stream ends at the header's last byte).
  const auto consumed = [&]() -> std::int64_t {
    const auto at = in.tellg();
    return at < 0 ? static_cast<std::int64_t>(header.size()) : static_cast<std::int64_t>(at);
  };
  std::string line;
  std::vector<std::int64_t> dims;
  std::int64_t pointData = -1;
  std::string dataset;
  while (std::getline(in, line)) {
    const auto w = words(line);
    if (w.empty()) continue;
    const std::string key = lower(w[0]);
    if (key == "dataset" && w.size() >= 2) {
      dataset = lower(w[1]);
    } else if (key == "dimensions" && w.size() >= 4 && dataset == "structured_points") {
      dims = {parseCount(w[1]), parseCount(w[2]), parseCount(w[3])};
      if (std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d < 0; })) return;
      // A field of structured points has a value per point or per cell: at least one byte per
      // cell (an axis of one point has one cell). Other grids list their points or
      // coordinates, which the POINTS check and VTK's reader check.
      std::vector<std::int64_t> cells;
      for (std::int64_t d : dims) cells.push_back(std::max<std::int64_t>(d - 1, 1));
      requireData(
          path, "legacy VTK", dimsText(dims) + " points (" + grouped(product(cells)) + " cells)",
          product(cells), 1, Encoding::Binary, fileBytes - consumed(), "the file after its header");
    } else if (key == "point_data" && w.size() >= 2) {
      pointData = parseCount(w[1]);
    } else if (key == "points" && w.size() >= 3) {
      // The first data block: three coordinates per point, right after this line.
      const std::int64_t n = parseCount(w[1]), bytes = legacyTypeBytes(w[2]);
      if (n < 0 || bytes == 0) return;
      requireData(path, "legacy VTK", grouped(n) + " points of type " + w[2], times(n, 3), bytes,
                  enc, fileBytes - consumed(), "the file after the POINTS line");
      return;  // binary data follows: lines no longer mean anything
    } else if (key == "scalars" && w.size() >= 3 && pointData >= 0) {
      // Structured points: POINT_DATA n, SCALARS name type [components], LOOKUP_TABLE name;
      // VTK reads the values from the line after LOOKUP_TABLE's.
      const std::int64_t bytes = legacyTypeBytes(w[2]);
      const std::int64_t components = w.size() >= 4 ? parseCount(w[3]) : 1;
      if (bytes == 0 || components <= 0) return;
      std::string next;
      while (std::getline(in, next) && words(next).empty()) {
      }
      if (!in || lower(words(next)[0]) != "lookup_table") return;
      requireData(path, "legacy VTK",
                  grouped(pointData) + " point values of type " + w[2] +
                      (components > 1 ? " x " + std::to_string(components) : ""),
                  times(pointData, components), bytes, enc, fileBytes - consumed(),
                  "the file after the SCALARS block's header");
      return;
    }
  }
}

namespace {

// Walks the geometry blocks of a legacy file (POINTS, CELLS / OFFSETS / CONNECTIVITY,
// CELL_TYPES), skipping their data, and checks the counts VTK's reader trusts: it dereferences
// null for a CELLS block whose size cannot hold its cells. Stops at the first other keyword.
void checkLegacyCells(std::istream& in, const std::string& path) {
  const auto fail = [&](const std::string& why) {
    throw Error("cannot read " + path + " as legacy VTK: " + why +
                "; the file is damaged or its header is wrong");
  };
  const LegacyPreamble preamble = readLegacyPreamble(in);
  if (!preamble.valid) return;
  const bool binary = preamble.binary;
  const bool newCells = preamble.version.rfind("5.", 0) == 0;  // 5.x: offsets + connectivity
  std::string line;
  const auto skip = [&](std::int64_t values, std::int64_t bytes) {
    if (values < 0 || bytes <= 0) return false;
    if (binary) {
      in.ignore(static_cast<std::streamsize>(std::min<std::int64_t>(
          times(values, bytes), std::numeric_limits<std::streamsize>::max())));
    } else {
      std::string token;
      for (std::int64_t v = 0; v < values && in >> token; ++v) {
      }
    }
    return static_cast<bool>(in);
  };
  std::int64_t cells = -1;
  for (int guard = 0; guard < 16 && std::getline(in, line); ++guard) {
    const auto w = words(line);
    if (w.empty()) continue;
    const std::string key = lower(w[0]);  // VTK reads keywords in any case
    if (key == "dataset") continue;
    // VTK reads a keyword's counts across line ends: a short line takes its numbers from the
    // data that follows.
    if ((key == "points" || key == "cells") && w.size() != 3)
      fail("the " + w[0] + " line has " + std::to_string(w.size() - 1) + " fields, not 2");
    if (key == "cell_types" && w.size() != 2)
      fail("the CELL_TYPES line has " + std::to_string(w.size() - 1) + " fields, not 1");
    if (key == "points" && w.size() >= 3) {
      if (parseCount(w[1]) < 0 || legacyTypeBytes(w[2]) == 0)
        fail("POINTS '" + w[1] + " " + w[2] + "' is not a count and a VTK data type");
      if (!skip(times(parseCount(w[1]), 3), legacyTypeBytes(w[2]))) return;
    } else if (key == "cells" && w.size() >= 3) {
      const std::int64_t a = parseCount(w[1]), b = parseCount(w[2]);
      if (a < 0 || b < 0) fail("CELLS '" + w[1] + " " + w[2] + "' are not counts");
      if (newCells) {
        // CELLS offsets connectivity: cells + 1 offsets, at least one point per cell.
        if (a > 0 && b < a - 1)
          fail("CELLS declares " + grouped(a) + " offsets but only " + grouped(b) +
               " connectivity entries");
        cells = a > 0 ? a - 1 : 0;
      } else {
        // CELLS n size: each cell is its point count and at least one point.
        if (b < times(a, 2))
          fail("CELLS declares " + grouped(a) + " cells in " + grouped(b) +
               " integers, fewer than 2 per cell");
        cells = a;
        if (!skip(b, 4)) return;
      }
    } else if ((key == "offsets" || key == "connectivity") && w.size() >= 2) {
      return;  // their lengths are CELLS' counts; VTK checks the rest
    } else if (key == "cell_types" && w.size() >= 2) {
      const std::int64_t n = parseCount(w[1]);
      if (cells >= 0 && n != cells)
        fail("CELL_TYPES declares " + w[1] + " types for " + grouped(cells) + " cells");
      return;
    } else {
      return;
    }
  }
}

}  // namespace

void checkLegacyVtkDeclaredSize(const std::string& path) {
  checkLegacyVtkHeaderText(readHead(path, 4096), path, fileSize(path));
  std::ifstream in(path, std::ios::binary);
  checkLegacyCells(in, path);
}

// ---- VTK XML ----------------------------------------------------------------------------------

namespace {

// The integers of attribute `name` in the first element that has it, or empty.
std::vector<std::int64_t> attributeCounts(const std::string& text, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const auto at = text.find(key);
  if (at == std::string::npos) return {};
  const auto end = text.find('"', at + key.size());
  if (end == std::string::npos) return {};
  std::vector<std::int64_t> out;
  for (const auto& w : words(text.substr(at + key.size(), end - at - key.size()))) {
    std::int64_t v = 0;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (r.ec != std::errc() || r.ptr != w.data() + w.size()) return {};
    out.push_back(v);
  }
  return out;
}

}  // namespace

void checkXmlVtkText(const std::string& head, const std::string& tail, const std::string& path,
                     std::int64_t fileBytes) {
  if (head.find("<VTKFile") == std::string::npos) return;
  // Composite data (a list of data sets in other files, or AMR levels): VTK's single-data-set
  // readers only say they cannot find their element.
  for (const char* composite : {"vtkMultiBlockDataSet", "vtkOverlappingAMR", "vtkNonOverlappingAMR",
                                "vtkHierarchicalBoxDataSet", "vtkPartitionedDataSet",
                                "vtkPartitionedDataSetCollection", "vtkMultiPieceDataSet"}) {
    if (head.find("type=\"" + std::string(composite) + "\"") != std::string::npos) {
      throw Error("cannot read " + path + ": the file holds a " + composite +
                  ", a composite of several data sets (multi-block), not a data set; mfadvr "
                  "reads one data set per file: encode the block files it lists, or extract a "
                  "block in ParaView (Extract Block) and save it");
    }
  }
  if (trim(tail).size() < 10 || trim(tail).substr(trim(tail).size() - 10) != "</VTKFile>") {
    throw Error("cannot read " + path + " as VTK XML: the file (" + grouped(fileBytes) +
                " bytes) does not end with </VTKFile>, so it is cut off or not well-formed");
  }
  // Compressed and base64 data can be smaller than the raw samples, but not by more than the
  // deflate limit.
  const Encoding enc =
      head.find("compressor=") != std::string::npos ? Encoding::Deflate : Encoding::Binary;
  std::int64_t points = -1;
  std::string declared;
  const auto extent = attributeCounts(head, "WholeExtent");
  if (extent.size() == 6) {
    std::vector<std::int64_t> dims;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t lo = extent[2 * a], hi = extent[2 * a + 1];
      if (hi < lo || hi - lo >= std::numeric_limits<std::int64_t>::max() / 2) return;
      dims.push_back(hi - lo + 1);
    }
    // A field of the image has a value per point or per cell: at least one byte per cell.
    std::vector<std::int64_t> cells;
    for (std::int64_t d : dims) cells.push_back(std::max<std::int64_t>(d - 1, 1));
    points = product(cells);
    declared = "an extent of " + dimsText(dims) + " points (" + grouped(points) + " cells)";
  } else {
    const auto n = attributeCounts(head, "NumberOfPoints");
    if (n.size() != 1 || n[0] < 0) return;
    points = n[0];
    declared = grouped(points) + " points";
  }
  // At least one byte per cell of an image, per point (a coordinate) of other data sets,
  // whatever the array types.
  requireData(path, "VTK XML", declared, points, 1, enc, fileBytes, "the file");
}

void checkXmlVtkDeclaredSize(const std::string& path) {
  const std::int64_t size = fileSize(path);
  if (size < 0) return;
  checkXmlVtkText(readHead(path, 8192), readTail(path, size, 256), path, size);
}

// ---- NIfTI ------------------------------------------------------------------------------------

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
                                   std::int64_t fileBytes, bool compressed) {
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
  if (version == 0 || (version == 2 && header.size() < 540)) return -1;
  // VTK's reader indexes its arrays with dim[0] and sizes samples from datatype without
  // checking them: a damaged header crashes it. So the fields it trusts are checked here.
  const auto fail = [&](const std::string& why) {
    throw Error("cannot read " + path + " as NIfTI: " + why +
                "; the header is damaged or not a NIfTI header");
  };
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
  return data > std::numeric_limits<std::int64_t>::max() - voxOffset
             ? std::numeric_limits<std::int64_t>::max()
             : voxOffset + data;
}

void checkNiftiDeclaredSize(const std::string& path) {
  // zlib reads plain files through gzopen too: the magic bytes, not the name, say which.
  const std::string magic = readHead(path, 2);
  const bool gz = magic.size() == 2 && magic[0] == '\x1f' && magic[1] == '\x8b';
  std::string header;
  if (gz) {
    gzFile in = gzopen(path.c_str(), "rb");
    if (!in) return;
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
    checkNiftiHeaderBytes(header, img.string(), size, false);
    return;
  }
  const std::int64_t expected = checkNiftiHeaderBytes(header, path, size, gz);
  // VTK's reader stops at the end of the deflate data and never looks at the gzip trailer.
  if (gz && expected > 0) requireCompleteGzip(path, "NIfTI", path, 0, expected);
}

// ---- DICOM ------------------------------------------------------------------------------------

namespace {

// The elements of one DICOM Part-10 file, walked without reading the pixel data.
struct DicomWalk {
  std::int64_t rows = -1, columns = -1, bitsAllocated = -1, samplesPerPixel = 1;
  std::int64_t pixelBytes = -1;  // length of (7FE0,0010); -1: not reached
  std::string problem;           // why the walk stopped early ("" when it did not)
};

DicomWalk walkDicom(std::istream& in, std::int64_t size) {
  DicomWalk w;
  std::int64_t pos = 132;
  bool explicitVr = true, littleEndian = true, inMeta = true;
  auto readBytes = [&](std::int64_t at, size_t n, unsigned char* out) {
    in.clear();
    in.seekg(at);
    in.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n));
    return static_cast<size_t>(in.gcount()) == n;
  };
  bool le = true;  // of the element being read: the meta group is always little endian
  auto u16 = [&](const unsigned char* b) {
    return le ? std::uint32_t(b[0] | b[1] << 8) : std::uint32_t(b[1] | b[0] << 8);
  };
  auto u32 = [&](const unsigned char* b) {
    return le ? std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                    std::uint32_t(b[3]) << 24
              : std::uint32_t(b[3]) | std::uint32_t(b[2]) << 8 | std::uint32_t(b[1]) << 16 |
                    std::uint32_t(b[0]) << 24;
  };
  for (int guard = 0; pos < size && guard < 100000; ++guard) {
    unsigned char tag[12];
    if (pos + 8 > size || !readBytes(pos, 8, tag)) {
      w.problem = "an element header is cut off at byte " + grouped(pos);
      return w;
    }
    le = inMeta || littleEndian;
    const std::uint32_t group = u16(tag);
    if (inMeta && group != 0x0002) {
      inMeta = false;
      continue;  // read this element again, with the data set's encoding
    }
    const std::uint32_t element = u16(tag + 2);
    std::int64_t length = 0, header = 8;
    const bool explicitHere = inMeta || explicitVr;
    if (explicitHere && std::isupper(tag[4]) && std::isupper(tag[5])) {
      const std::string vr(reinterpret_cast<char*>(tag + 4), 2);
      static const char* kLong[] = {"OB", "OW", "OF", "SQ", "UT", "UN", "OD",
                                    "OL", "UC", "UR", "OV", "SV", "UV"};
      if (std::any_of(std::begin(kLong), std::end(kLong), [&](const char* v) { return vr == v; })) {
        if (!readBytes(pos, 12, tag)) {
          w.problem = "an element header is cut off at byte " + grouped(pos);
          return w;
        }
        length = u32(tag + 8);
        header = 12;
      } else {
        length = u16(tag + 6);
      }
    } else {
      length = u32(tag + 4);
    }
    if (length == 0xFFFFFFFFll) return w;  // undefined length (sequences, encapsulated data)
    const std::int64_t valueAt = pos + header;
    if (group == 0x7FE0 && element == 0x0010) {
      w.pixelBytes = length;
      if (valueAt + length > size)
        w.problem = "its pixel data declares " + grouped(length) + " bytes, but " +
                    grouped(std::max<std::int64_t>(0, size - valueAt)) + " follow";
      return w;
    }
    if (valueAt + length > size) {
      char name[16];
      std::snprintf(name, sizeof name, "(%04X,%04X)", group, element);
      w.problem = std::string("element ") + name + " declares " + grouped(length) +
                  " bytes, past the end of the file";
      return w;
    }
    unsigned char value[64] = {};
    const size_t small = static_cast<size_t>(std::min<std::int64_t>(length, 64));
    if (small > 0 && !readBytes(valueAt, small, value)) return w;
    if (group == 0x0002 && element == 0x0010) {
      std::string ts(reinterpret_cast<char*>(value), small);
      ts = ts.substr(0, ts.find_first_of(std::string("\0 ", 2)));
      explicitVr = ts != "1.2.840.10008.1.2";
      littleEndian = ts != "1.2.840.10008.1.2.2";
    } else if (group == 0x0028 && length == 2) {
      if (element == 0x0010) w.rows = u16(value);
      if (element == 0x0011) w.columns = u16(value);
      if (element == 0x0100) w.bitsAllocated = u16(value);
      if (element == 0x0002) w.samplesPerPixel = u16(value);
    }
    pos = valueAt + length;
  }
  return w;
}

}  // namespace

void checkDicomFile(std::istream& in, std::int64_t size, const std::string& path) {
  const DicomWalk w = walkDicom(in, size);
  if (!w.problem.empty())
    throw Error("cannot read " + path + " as DICOM: " + w.problem +
                "; the file is truncated or corrupt");
  if (w.pixelBytes < 0) {
    throw Error("cannot read " + path +
                " as DICOM: no pixel data (7FE0,0010) before the end of "
                "the file; it is truncated or holds no image");
  }
  if (w.rows > 0 && w.columns > 0 && w.bitsAllocated > 0) {
    const std::int64_t need =
        times(times(w.rows, w.columns), times(w.samplesPerPixel, (w.bitsAllocated + 7) / 8));
    if (w.pixelBytes < need) {
      throw Error("cannot read " + path + " as DICOM: " + std::to_string(w.rows) + " x " +
                  std::to_string(w.columns) + " pixels of " + std::to_string(w.bitsAllocated) +
                  " bits need " + grouped(need) + " bytes, but its pixel data has " +
                  grouped(w.pixelBytes));
    }
  }
}

int checkDicomSeries(const std::string& directory) {
  int files = 0;
  std::error_code ec;
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(directory, ec))
    if (entry.is_regular_file(ec)) paths.push_back(entry.path());
  if (ec) throw Error("cannot read " + directory + " as a DICOM series: " + ec.message());
  std::sort(paths.begin(), paths.end());
  for (const fs::path& p : paths) {
    std::ifstream in(p, std::ios::binary);
    char magic[132] = {};
    if (!in.read(magic, sizeof magic) || std::string(magic + 128, 4) != "DICM") continue;
    ++files;
    checkDicomFile(in, fileSize(p.string()), p.string());
  }
  // VTK's reader says little (and twice) about a folder without DICOM files.
  if (files == 0) {
    throw Error("cannot read " + directory + " as a DICOM series: none of its " +
                std::to_string(paths.size()) +
                " files is a DICOM file ('DICM' after a 128-byte preamble); a volume input "
                "that is a directory must hold the slices of one DICOM series");
  }
  return files;
}

}  // namespace mfadvr
