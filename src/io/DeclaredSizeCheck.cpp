#include "io/DeclaredSizeCheck.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
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

DataFileSize dataFilesBeside(const std::string& path) {
  return [dir = fs::path(path).parent_path()](const std::string& name) {
    const fs::path p(name);
    return fileSize((p.is_absolute() ? p : dir / p).string());
  };
}

enum class Encoding { Binary, Ascii, Hex, Deflate, Unknown };

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
  throw Error(path + ": the " + format + " header declares " + declared + " (" + need + "), but " +
              where + " holds only " + grouped(available) +
              " bytes; the file is truncated or its header is wrong");
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

NrrdAsciiData checkNrrdHeaderText(const std::string& header, const std::string& path,
                                  std::int64_t fileBytes, const DataFileSize& dataFileBytes) {
  if (header.rfind("NRRD", 0) != 0) return {};  // the reader says what is wrong
  std::istringstream in(header);
  std::string line;
  std::getline(in, line);
  std::int64_t headerBytes = static_cast<std::int64_t>(line.size()) + 1;
  bool ended = false;
  std::string type, encoding = "raw", dataFile;
  std::vector<std::int64_t> sizes;
  std::int64_t byteSkip = 0;
  bool skipped = false;
  while (std::getline(in, line)) {
    headerBytes += static_cast<std::int64_t>(line.size()) + 1;
    if (trim(line).empty()) {
      ended = true;
      break;
    }
    if (line[0] == '#') continue;
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;  // key:=value pairs and oddities
    const std::string key = lower(trim(line.substr(0, colon)));
    const std::string value = trim(line.substr(colon + 2));
    if (key == "type") {
      type = lower(value);
    } else if (key == "sizes") {
      sizes.clear();
      for (const auto& w : words(value)) sizes.push_back(parseCount(w));
    } else if (key == "encoding") {
      encoding = lower(value);
    } else if (key == "data file" || key == "datafile") {
      dataFile = value;
    } else if (key == "byte skip" || key == "byteskip") {
      byteSkip = parseCount(value);
      skipped = true;
    } else if (key == "line skip" || key == "lineskip") {
      skipped = true;
    }
  }
  const std::int64_t typeBytes = nrrdTypeBytes(type);
  if (sizes.empty() || typeBytes == 0) return {};
  if (std::any_of(sizes.begin(), sizes.end(), [](std::int64_t s) { return s < 0; })) return {};
  Encoding enc = Encoding::Unknown;
  if (encoding == "raw") enc = Encoding::Binary;
  if (encoding == "gzip" || encoding == "gz") enc = Encoding::Deflate;
  if (encoding == "ascii" || encoding == "txt" || encoding == "text") enc = Encoding::Ascii;
  if (encoding == "hex") enc = Encoding::Hex;
  // Skips make the data start somewhere the header does not say exactly (-1: at the end).
  if (skipped && (byteSkip < 0 || enc != Encoding::Binary)) return {};

  std::int64_t available = -1;
  std::string where;
  if (!dataFile.empty()) {
    // "LIST" and "%d"-pattern forms name several files: left to the reader.
    if (dataFile.rfind("LIST", 0) == 0 || dataFile.find(' ') != std::string::npos) return {};
    const std::int64_t size = dataFileBytes(dataFile);
    if (size < 0)
      throw Error("cannot read " + path + " as NRRD: its data file '" + dataFile +
                  "' (\"data file:\" in the header) does not exist");
    available = size - byteSkip;
    where = "its data file '" + dataFile + "'";
  } else {
    if (!ended) return {};  // the reader reports a header without data
    available = fileBytes - headerBytes - byteSkip;
    where = "the file after its header";
  }
  requireData(path, "NRRD", dimsText(sizes) + " " + type + " samples in " + encoding + " encoding",
              product(sizes), typeBytes, enc, std::max<std::int64_t>(0, available), where);
  if (enc != Encoding::Ascii) return {};
  return {dataFile, dataFile.empty() ? headerBytes : 0, product(sizes),
          dimsText(sizes) + " " + type + " samples"};
}

namespace {

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
      const char c = buffer[i];
      const bool separator = std::isspace(static_cast<unsigned char>(c)) || c == ',';
      if (!separator && !inValue) ++count;
      inValue = !separator;
    }
  }
  return count;
}

}  // namespace

void checkNrrdDeclaredSize(const std::string& path) {
  const NrrdAsciiData ascii = checkNrrdHeaderText(readHead(path, kMaxHeaderBytes), path,
                                                  fileSize(path), dataFilesBeside(path));
  if (ascii.values <= 0) return;
  // VTK's reader fills values missing from ASCII data with zeros: count them first.
  fs::path data(path);
  if (!ascii.dataFile.empty()) {
    data = fs::path(ascii.dataFile);
    if (!data.is_absolute()) data = fs::path(path).parent_path() / data;
  }
  const std::int64_t found = countValues(data.string(), ascii.offset, ascii.values);
  if (found < ascii.values) {
    throw Error("cannot read " + path + " as NRRD: the header declares " + ascii.declared + " (" +
                grouped(ascii.values) + " values in ascii encoding), but the data holds " +
                grouped(found) + "; the file is truncated or its header is wrong");
  }
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
  std::istringstream in(header);
  std::string line;
  std::int64_t headerBytes = 0;
  std::vector<std::int64_t> dims;
  std::string type, dataFile;
  std::int64_t channels = 1, headerSize = 0;
  bool compressed = false, binary = true;
  while (std::getline(in, line)) {
    headerBytes += static_cast<std::int64_t>(line.size()) + 1;
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = trim(line.substr(0, eq));
    const std::string value = trim(line.substr(eq + 1));
    if (key == "DimSize") {
      dims.clear();
      for (const auto& w : words(value)) dims.push_back(parseCount(w));
    } else if (key == "ElementType") {
      type = value;
    } else if (key == "ElementNumberOfChannels") {
      channels = parseCount(value);
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
  const Encoding enc = compressed ? Encoding::Deflate : binary ? Encoding::Binary : Encoding::Ascii;
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

}  // namespace

void checkLegacyVtkHeaderText(const std::string& header, const std::string& path,
                              std::int64_t fileBytes) {
  if (header.rfind("# vtk DataFile", 0) != 0) return;
  std::istringstream in(header);
  std::string line;
  std::int64_t offset = 0;
  int lineNumber = 0;
  bool binary = false;
  std::vector<std::int64_t> dims;
  std::int64_t pointData = -1;
  while (std::getline(in, line) && offset < static_cast<std::int64_t>(header.size())) {
    offset += static_cast<std::int64_t>(line.size()) + 1;
    ++lineNumber;
    if (lineNumber == 3) binary = lower(trim(line)) == "binary";
    if (lineNumber < 4) continue;
    const auto w = words(line);
    if (w.empty()) continue;
    const std::string key = lower(w[0]);
    const Encoding enc = binary ? Encoding::Binary : Encoding::Ascii;
    if (key == "dimensions" && w.size() >= 4) {
      dims = {parseCount(w[1]), parseCount(w[2]), parseCount(w[3])};
      if (std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d < 0; })) return;
      // Structured points need a value per point: at least one byte each.
      requireData(path, "legacy VTK", dimsText(dims) + " points", product(dims), 1,
                  Encoding::Binary, fileBytes - offset, "the file after its header");
    } else if (key == "point_data" && w.size() >= 2) {
      pointData = parseCount(w[1]);
    } else if (key == "points" && w.size() >= 3) {
      // The first data block: three coordinates per point, right after this line.
      const std::int64_t n = parseCount(w[1]), bytes = legacyTypeBytes(w[2]);
      if (n < 0 || bytes == 0) return;
      requireData(path, "legacy VTK", grouped(n) + " points of type " + w[2], times(n, 3), bytes,
                  enc, fileBytes - offset, "the file after the POINTS line");
      return;  // binary data follows: lines no longer mean anything
    } else if (key == "scalars" && w.size() >= 3 && pointData >= 0) {
      // Structured points: POINT_DATA n, SCALARS name type [components], LOOKUP_TABLE name.
      const std::int64_t bytes = legacyTypeBytes(w[2]);
      const std::int64_t components = w.size() >= 4 ? parseCount(w[3]) : 1;
      if (bytes == 0 || components <= 0) return;
      std::string next;
      if (!std::getline(in, next)) return;
      offset += static_cast<std::int64_t>(next.size()) + 1;
      if (lower(words(next).empty() ? "" : words(next)[0]) != "lookup_table") return;
      requireData(path, "legacy VTK",
                  grouped(pointData) + " point values of type " + w[2] +
                      (components > 1 ? " x " + std::to_string(components) : ""),
                  times(pointData, components), bytes, enc, fileBytes - offset,
                  "the file after the SCALARS block's header");
      return;
    }
  }
}

void checkLegacyVtkDeclaredSize(const std::string& path) {
  checkLegacyVtkHeaderText(readHead(path, 4096), path, fileSize(path));
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
    points = product(dims);
    declared = "an extent of " + dimsText(dims) + " points";
  } else {
    const auto n = attributeCounts(head, "NumberOfPoints");
    if (n.size() != 1 || n[0] < 0) return;
    points = n[0];
    declared = grouped(points) + " points";
  }
  // At least one byte per point (a scalar or a coordinate), whatever the array types.
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

void checkNiftiHeaderBytes(const std::string& header, const std::string& path,
                           std::int64_t fileBytes, bool compressed) {
  if (header.size() < 348) return;  // the reader reports short headers
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
  if (version == 0 || (version == 2 && header.size() < 540)) return;
  std::vector<std::int64_t> dims;
  std::int64_t bitpix = 0, voxOffset = 0;
  if (version == 1) {
    const int n = readAt<std::int16_t>(header, 40, swap);
    for (int d = 1; d <= std::min(n, 3); ++d)
      dims.push_back(readAt<std::int16_t>(header, 40 + 2 * d, swap));
    bitpix = readAt<std::int16_t>(header, 72, swap);
    const float offset = readAt<float>(header, 108, swap);
    voxOffset = offset >= 0.0f && offset < 1e12f ? static_cast<std::int64_t>(offset) : 0;
  } else {
    const std::int64_t n = readAt<std::int64_t>(header, 16, swap);
    for (std::int64_t d = 1; d <= std::min<std::int64_t>(n, 3); ++d)
      dims.push_back(readAt<std::int64_t>(header, 16 + 8 * static_cast<size_t>(d), swap));
    bitpix = readAt<std::int16_t>(header, 14, swap);
    voxOffset = std::max<std::int64_t>(0, readAt<std::int64_t>(header, 168, swap));
  }
  if (dims.empty() || bitpix <= 0 || bitpix % 8 != 0) return;
  if (std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d <= 0; })) return;
  // For a .hdr/.img pair, fileBytes is the .img's size (vox_offset is an offset into it).
  requireData(path, "NIfTI", dimsText(dims) + " samples of " + std::to_string(bitpix) + " bits",
              product(dims), bitpix / 8, compressed ? Encoding::Deflate : Encoding::Binary,
              fileBytes - (compressed ? 0 : voxOffset),
              compressed ? "the compressed file" : "the file after vox_offset");
}

void checkNiftiDeclaredSize(const std::string& path) {
  std::string lowerPath = lower(path);
  const bool gz = lowerPath.size() > 3 && lowerPath.compare(lowerPath.size() - 3, 3, ".gz") == 0;
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
  checkNiftiHeaderBytes(header, path, size, gz);
}

}  // namespace mfadvr
