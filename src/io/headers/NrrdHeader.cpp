// NRRD: the declared-size check (io/DeclaredSizeCheck.h).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

#include "core/util/Error.h"
#include "io/DeclaredSizeCheck.h"
#include "io/headers/HeaderText.h"

namespace mfadvr {

namespace fs = std::filesystem;
using namespace headers;

namespace {

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

// The raw sample type of a NRRD type; "" for the 64-bit integers. Every spelling of a type
// has its width in nrrdTypeBytes; the unsigned ones start with 'u' or say "unsigned".
std::string nrrdRawType(const std::string& type) {
  if (type == "float") return "float32";
  if (type == "double") return "float64";
  const std::int64_t bytes = nrrdTypeBytes(type);
  if (bytes < 1 || bytes > 4) return "";
  const bool isUnsigned = type[0] == 'u' || type.find("unsigned") != std::string::npos;
  return (isUnsigned ? "uint" : "int") + std::to_string(8 * bytes);
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
  std::string type, encoding, dataFile, dimension, endian;
  std::vector<std::int64_t> sizes;
  std::vector<std::string> spacings;
  bool sizesGiven = false;
  std::set<std::string> fields;
  std::int64_t byteSkip = 0, lineSkip = 0;
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
    // NRRD allows each field once; VTK's reader acts on every occurrence in turn (a second
    // "dimension:" with a huge value ends the program, found by fuzzing), while this check
    // reads the last.
    if (!fields.insert(key).second)
      fail("the field '" + key + "' appears twice (NRRD allows each field once)");
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
    } else if (key == "endian") {
      endian = value;
    } else if (key == "encoding") {
      encoding = value;
    } else if (key == "data file" || key == "datafile") {
      dataFile = value;
    } else if (key == "byte skip" || key == "byteskip") {
      byteSkip = value == "-1" ? -1 : parseCount(value);
      if (byteSkip < -1) fail("byte skip '" + value + "' is not a count (or -1)");
      skipped = true;
    } else if (key == "line skip" || key == "lineskip") {
      lineSkip = parseCount(value);
      if (lineSkip < 0) fail("line skip '" + value + "' is not a count");
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
  // The samples, when they lie in one file (byte skip counts in the inflated data of gzip).
  DeclaredPayload raw;
  if (lineSkip == 0 && !nrrdRawType(type).empty() && enc != Encoding::Ascii) {
    raw.file = dataFile.empty() ? path : dataFile;
    const std::int64_t start = dataFile.empty() ? headerBytes : 0;
    raw.gzipAt = enc == Encoding::Deflate ? start : -1;
    raw.offset = enc == Encoding::Deflate ? byteSkip : start + byteSkip;
    raw.dtype = nrrdRawType(type);
    raw.bigEndian = endian == "big";
    raw.sizes = sizes;
  }
  if (enc != Encoding::Ascii && enc != Encoding::Deflate) {
    NrrdDataLocation location;
    location.raw = raw;
    return location;
  }
  return {dataFile,
          dataFile.empty() ? headerBytes : 0,
          product(sizes),
          times(product(sizes), typeBytes),
          enc == Encoding::Deflate,
          dimsText(sizes) + " " + type + " samples",
          raw};
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

NrrdAsciiData checkNrrdDeclaredSize(const std::string& path, DeclaredPayload* payload) {
  const NrrdDataLocation data = checkNrrdHeaderText(readHead(path, kMaxHeaderBytes), path,
                                                    fileSize(path), dataFilesBeside(path));
  if (payload) *payload = besideHeader(data.raw, path);
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

}  // namespace mfadvr
