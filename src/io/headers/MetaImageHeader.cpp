// MetaImage: the declared-size check (io/DeclaredSizeCheck.h).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "core/util/Error.h"
#include "io/DeclaredSizeCheck.h"
#include "io/headers/HeaderText.h"

namespace mfadvr {

namespace fs = std::filesystem;
using namespace headers;

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

// The raw sample type of an ElementType; "" for the 64-bit integers. MET_LONG is 4 bytes, as
// in metaTypeBytes (MetaIO's convention).
std::string metaRawType(const std::string& type) {
  if (type == "MET_FLOAT") return "float32";
  if (type == "MET_DOUBLE") return "float64";
  const std::int64_t bytes = metaTypeBytes(type);
  if (bytes < 1 || bytes > 4) return "";
  return (type.rfind("MET_U", 0) == 0 ? "uint" : "int") + std::to_string(8 * bytes);
}

// One "%d"-style conversion (flags, a width, d or i) and no other '%': MetaIO hands the pattern
// to sprintf with one int, so anything else (a "%s", two conversions) is undefined behaviour.
bool isSliceNumberPattern(const std::string& pattern) {
  const size_t at = pattern.find('%');
  if (at == std::string::npos) return false;
  size_t i = at + 1;
  while (i < pattern.size() && pattern[i] != '\0' && std::strchr("0-+ ", pattern[i])) ++i;
  size_t digits = 0;
  while (i < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[i]))) ++i, ++digits;
  if (digits > 2 || i >= pattern.size() || (pattern[i] != 'd' && pattern[i] != 'i')) return false;
  return pattern.find('%', i + 1) == std::string::npos;
}

std::optional<std::int64_t> parseInteger(const std::string& text) {
  std::int64_t v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || v < -1000000000 || v > 1000000000) return std::nullopt;
  return v;
}

// The files of a MetaImage file series, as MetaIO would open them, in slice order: a "LIST"
// (names on the lines after the header; `rest` is that text) or a sample-number pattern with
// its range. MetaIO skips a slice file it cannot open and leaves its samples unset, so every
// file is checked here; `perFile` gets the axes one file holds. Throws through `fail` for a
// series MetaIO would misread.
template <class Fail>
std::vector<std::string> seriesFiles(const std::string& dataFile, std::istream& rest,
                                     const std::vector<std::int64_t>& dims, size_t& perFile,
                                     const Fail& fail) {
  const std::vector<std::string> w = words(dataFile);
  const auto rank = dims.size();
  std::vector<std::string> files;
  if (w[0] == "LIST") {
    // "LIST nD": each file holds n axes (MetaIO falls back to NDims - 1 for 0 or > NDims).
    perFile = rank - 1;
    if (w.size() > 1) {
      const auto n = parseCount(w[1].substr(0, w[1].find_first_not_of("0123456789")));
      if (n > 0 && n <= static_cast<std::int64_t>(rank)) perFile = static_cast<size_t>(n);
    }
    std::int64_t count = 1;
    for (size_t a = perFile; a < rank; ++a) count = times(count, dims[a]);
    std::string line;
    // MetaIO reads a name per line, up to 254 characters, and ignores a last line without its
    // line end.
    while (static_cast<std::int64_t>(files.size()) < count && std::getline(rest, line) &&
           !rest.eof()) {
      const std::string name = trim(line);
      if (name.empty()) fail("its file list (ElementDataFile = LIST) has an empty line");
      if (line.size() > 253) fail("a name in its file list is longer than 253 characters");
      files.push_back(name);
    }
    if (static_cast<std::int64_t>(files.size()) < count)
      fail("ElementDataFile = LIST names " + std::to_string(files.size()) +
           " files, one per line after the header; DimSize needs " + grouped(count));
    return files;
  }
  // "pattern [first [last [step]]]": the slices' numbers, with MetaIO's defaults.
  if (w.size() > 4)
    fail("its file-series pattern '" + dataFile + "' is not 'pattern first last step'");
  if (!isSliceNumberPattern(w[0]))
    fail("its file-series pattern '" + w[0] +
         "' is not a name with one %d-style sample number (e.g. slice%03d.raw)");
  perFile = rank - 1;
  const std::int64_t slices = dims.back();
  std::int64_t first = 1, last = slices, step = 1;
  std::vector<std::int64_t> numbers;
  for (size_t i = 1; i < w.size(); ++i) {
    const auto v = parseInteger(w[i]);
    if (!v) fail("its file-series range '" + dataFile + "' holds '" + w[i] + "', not an integer");
    numbers.push_back(*v);
  }
  if (numbers.size() >= 1) first = numbers[0], last = first + slices - 1;
  if (numbers.size() >= 2) last = numbers[1], step = (last - first) / slices;
  if (numbers.size() >= 3) step = numbers[2];
  if (step <= 0)
    fail("its file-series range '" + dataFile + "' has a step of " + std::to_string(step) +
         " (give 'pattern first last step' with a positive step)");
  const std::int64_t count = last < first ? 0 : (last - first) / step + 1;
  if (count != slices)
    fail("its file series '" + dataFile + "' numbers " + std::to_string(count) +
         " files; DimSize needs one per slice, " + std::to_string(slices));
  for (std::int64_t i = first; i <= last; i += step) {
    char name[256];
    const int n = std::snprintf(name, sizeof name, w[0].c_str(), static_cast<int>(i));
    if (n < 0 || n >= static_cast<int>(sizeof name) - 1)
      fail("its file-series pattern '" + w[0] + "' makes names longer than 254 characters");
    files.emplace_back(name);
  }
  return files;
}

}  // namespace

DeclaredPayload checkMetaImageHeaderText(const std::string& header, const std::string& path,
                                         std::int64_t fileBytes,
                                         const DataFileSize& dataFileBytes) {
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
  bool compressed = false, binary = true, bigEndian = false;
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
    } else if (key == "BinaryDataByteOrderMSB" || key == "ElementByteOrderMSB") {
      bigEndian = lower(value) == "true";
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
  if (dataFile.empty() || dims.empty() || channels <= 0) return {};
  const std::int64_t typeBytes = metaTypeBytes(type);
  if (typeBytes == 0 || std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d < 0; }))
    return {};
  std::int64_t available = 0;
  std::string where;
  if (dataFile == "LOCAL") {
    available = fileBytes - headerBytes;
    where = "the file after its header";
  } else if (words(dataFile)[0].rfind("LIST", 0) == 0 || dataFile.find('%') != std::string::npos) {
    if (words(dataFile)[0] != "LIST" && dataFile.find('%') == std::string::npos)
      fail("its data file name '" + dataFile +
           "' begins with LIST, which MetaIO reads as a "
           "file list (ElementDataFile = LIST)");
    if (compressed || !binary)
      fail("its file series holds " + std::string(compressed ? "compressed" : "text") +
           " samples (file series of uncompressed binary samples only)");
    size_t perFile = 0;
    const std::vector<std::string> files = seriesFiles(dataFile, in, dims, perFile, fail);
    std::vector<std::int64_t> sliceDims(dims.begin(), dims.begin() + static_cast<long>(perFile));
    for (const std::string& name : files) {
      const std::int64_t size = dataFileBytes(name);
      if (size < 0)
        throw Error("cannot read " + path + " as MetaImage: '" + name +
                    "', a file of its series (ElementDataFile = " + dataFile + "), does not exist");
      requireData(path, "MetaImage", dimsText(sliceDims) + " " + type + " samples",
                  times(product(sliceDims), channels), typeBytes, Encoding::Binary,
                  size - std::max<std::int64_t>(0, headerSize), "its series file '" + name + "'");
    }
    return {};  // read by VTK's reader, slice file by slice file
  } else {
    const std::int64_t size = dataFileBytes(dataFile);
    if (size < 0)
      throw Error("cannot read " + path + " as MetaImage: its data file '" + dataFile +
                  "' (ElementDataFile = " + dataFile + ") does not exist");
    if (headerSize < 0) return {};
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
  if (enc != Encoding::ExactBinary || metaRawType(type).empty()) return {};
  DeclaredPayload payload;
  payload.file = dataFile == "LOCAL" ? path : dataFile;
  payload.offset = dataFile == "LOCAL" ? headerBytes : headerSize;
  payload.dtype = metaRawType(type);
  payload.bigEndian = bigEndian;
  payload.sizes = dims;
  payload.components = static_cast<int>(channels);
  return payload;
}

DeclaredPayload checkMetaImageDeclaredSize(const std::string& path) {
  return besideHeader(checkMetaImageHeaderText(readHead(path, kMaxHeaderBytes), path,
                                               fileSize(path), dataFilesBeside(path)),
                      path);
}

}  // namespace mfadvr
