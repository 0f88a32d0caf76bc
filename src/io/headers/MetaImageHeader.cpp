// MetaImage: the declared-size check (io/DeclaredSizeCheck.h).
#include <algorithm>
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
  } else {
    if (dataFile == "LIST" || dataFile.find(' ') != std::string::npos ||
        dataFile.find('%') != std::string::npos)
      return {};
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
