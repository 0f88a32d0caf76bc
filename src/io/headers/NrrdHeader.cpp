// NRRD: the declared-size check (io/DeclaredSizeCheck.h).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
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

namespace {

// The words of a "space directions" or "space origin" value: "none" or a parenthesized vector,
// which may hold spaces ("(0.5, 0, 0)").
std::vector<std::string> vectorWords(const std::string& value) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < value.size()) {
    if (std::isspace(static_cast<unsigned char>(value[i]))) {
      ++i;
      continue;
    }
    size_t end = i;
    if (value[i] == '(') {
      end = value.find(')', i);
      end = end == std::string::npos ? value.size() : end + 1;
    } else {
      while (end < value.size() && !std::isspace(static_cast<unsigned char>(value[end]))) ++end;
    }
    out.push_back(value.substr(i, end - i));
    i = end;
  }
  return out;
}

// "(x,y,z)" as numbers; nullopt when it is not a parenthesized list of finite numbers.
std::optional<std::vector<double>> parseVector(const std::string& word) {
  if (word.size() < 2 || word.front() != '(' || word.back() != ')') return std::nullopt;
  std::vector<double> out;
  std::string item;
  std::istringstream in(word.substr(1, word.size() - 2));
  while (std::getline(in, item, ',')) {
    const std::string w = trim(item);
    double v = 0.0;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (w.empty() || r.ec != std::errc() || r.ptr != w.data() + w.size() || !std::isfinite(v))
      return std::nullopt;
    out.push_back(v);
  }
  if (out.empty()) return std::nullopt;
  return out;
}

// A number of "spacings" or "axis mins"; nan where the axis has none.
std::optional<double> parseAxisNumber(const std::string& w) {
  if (lower(w) == "nan") return std::numeric_limits<double>::quiet_NaN();
  double v = 0.0;
  const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
  if (r.ec != std::errc() || r.ptr != w.data() + w.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// An axis's sample step: its spacing, else the length of its space direction, else 1.
double axisStep(double spacing, const std::optional<std::vector<double>>& direction) {
  if (std::isnan(spacing) && direction) {
    double sum = 0.0;
    for (double c : *direction) sum += c * c;
    return std::sqrt(sum);
  }
  return std::isnan(spacing) ? 1.0 : spacing;
}

// NRRD's kinds of an axis of values at one place rather than of places (teem's nrrdKind).
bool isComponentKind(const std::string& kind) {
  static const std::set<std::string> kDomain = {"domain", "space", "time", "???", "none"};
  return kDomain.count(kind) == 0;
}

}  // namespace

NrrdDataLocation checkNrrdHeaderText(const std::string& header, const std::string& path,
                                     std::int64_t fileBytes, const DataFileSize& dataFileBytes) {
  // The header is checked here in full before anything reads its data: every field mfadvr acts
  // on is parsed and bounded, the rest are skipped.
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
  std::string type, encoding, dataFile, dimension, endian, space, spaceDimension, spaceOrigin,
      spaceDirections, labels;
  std::vector<std::int64_t> sizes;
  std::vector<std::string> spacings, kinds, axisMins;
  bool sizesGiven = false;
  std::set<std::string> fields;
  std::int64_t byteSkip = 0, lineSkip = 0;
  while (std::getline(in, line)) {
    headerBytes += static_cast<std::int64_t>(line.size()) + 1;
    if (trim(line).empty()) {
      ended = true;
      break;
    }
    if (hasControlCharacters(line))
      fail("the header holds control characters: it is not a NRRD text header");
    if (line[0] == '#') continue;
    const auto colon = line.find(": ");
    if (colon == std::string::npos) continue;  // key:=value pairs
    // Field names are case-sensitive.
    const std::string key = trim(line.substr(0, colon));
    // NRRD allows each field once.
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
    } else if (key == "line skip" || key == "lineskip") {
      lineSkip = parseCount(value);
      if (lineSkip < 0) fail("line skip '" + value + "' is not a count");
    } else if (key == "kinds") {
      kinds = words(value);
    } else if (key == "space") {
      space = value;
    } else if (key == "space dimension") {
      spaceDimension = value;
    } else if (key == "space origin") {
      spaceOrigin = value;
    } else if (key == "space directions") {
      spaceDirections = value;
    } else if (key == "axis mins" || key == "axismins") {
      axisMins = words(value);
    } else if (key == "labels") {
      labels = value;
    }
  }
  std::string missing;
  for (const auto& [name, value] :
       {std::pair{"type", type}, {"dimension", dimension}, {"encoding", encoding}})
    if (value.empty()) missing += std::string(missing.empty() ? "" : ", ") + name;
  if (!sizesGiven) missing += std::string(missing.empty() ? "" : ", ") + "sizes";
  if (!missing.empty()) fail("the header lacks the required field(s) " + missing);
  const std::int64_t typeBytes = nrrdTypeBytes(type);
  if (typeBytes == 0) fail("type '" + type + "' is not a NRRD scalar type");
  if (nrrdRawType(type).empty())
    fail("type '" + type +
         "' (64-bit integers) is not read: convert the samples to double or a 32-bit type "
         "(e.g. unu convert -t double)");
  const std::int64_t dims = parseCount(dimension);
  if (dims < 1 || dims > 16) fail("dimension '" + dimension + "' is not between 1 and 16");
  const size_t axes = static_cast<size_t>(dims);
  if (sizes.size() != axes ||
      std::any_of(sizes.begin(), sizes.end(), [](std::int64_t v) { return v < 1; }))
    fail("sizes must be " + std::to_string(dims) + " positive integers (dimension: " + dimension +
         ")");
  const auto perAxis = [&](const std::vector<std::string>& values, const char* name) {
    if (!values.empty() && values.size() != axes)
      fail(std::string(name) + " must give " + std::to_string(dims) +
           " values, one per axis (dimension: " + dimension + ")");
  };
  perAxis(spacings, "spacings");
  perAxis(kinds, "kinds");
  perAxis(axisMins, "axis mins");
  // "spacings" and "axis mins" as numbers per axis (nan where absent or given as nan).
  const auto numbersOf = [&](const std::vector<std::string>& values, const char* name) {
    std::vector<double> out(axes, std::numeric_limits<double>::quiet_NaN());
    for (size_t a = 0; a < values.size(); ++a) {
      const auto v = parseAxisNumber(values[a]);
      if (!v) fail(std::string(name) + " holds '" + values[a] + "', which is not a number");
      out[a] = *v;
    }
    return out;
  };
  const std::vector<double> spacingOf = numbersOf(spacings, "spacings");
  const std::vector<double> minOf = numbersOf(axisMins, "axis mins");
  // Space: its dimension from "space dimension" or the named space, the axes' directions and
  // the origin as vectors of that many numbers.
  std::int64_t spaceDims = -1;
  if (!spaceDimension.empty()) {
    spaceDims = parseCount(spaceDimension);
    if (spaceDims < 1 || spaceDims > 16)
      fail("space dimension '" + spaceDimension + "' is not between 1 and 16");
  } else if (!space.empty()) {
    spaceDims = lower(space).find("time") != std::string::npos ? 4 : 3;
  }
  std::vector<std::optional<std::vector<double>>> directions(axes);
  if (!spaceDirections.empty()) {
    const std::vector<std::string> w = vectorWords(spaceDirections);
    if (w.size() != axes)
      fail("space directions must give " + std::to_string(dims) +
           " vectors or 'none', one per axis (dimension: " + dimension + ")");
    for (size_t a = 0; a < axes; ++a) {
      if (w[a] == "none") continue;
      directions[a] = parseVector(w[a]);
      if (!directions[a] || (spaceDims > 0 && directions[a]->size() != size_t(spaceDims)))
        fail("space directions holds '" + w[a].substr(0, 60) +
             "', which is not 'none' or a vector (" +
             (spaceDims > 0 ? std::to_string(spaceDims) : std::string("as many")) +
             " numbers in parentheses, separated by commas)");
    }
  }
  std::vector<double> origin;
  if (!spaceOrigin.empty()) {
    const auto v = parseVector(trim(spaceOrigin));
    if (!v || (spaceDims > 0 && v->size() != size_t(spaceDims)))
      fail("space origin '" + spaceOrigin.substr(0, 60) + "' is not a vector (" +
           (spaceDims > 0 ? std::to_string(spaceDims) : std::string("as many")) +
           " numbers in parentheses, separated by commas)");
    origin = *v;
  }

  Encoding enc = Encoding::Unknown;
  if (encoding == "raw") enc = Encoding::ExactBinary;
  if (encoding == "gzip" || encoding == "gz") enc = Encoding::Deflate;
  if (encoding == "ascii" || encoding == "txt" || encoding == "text") enc = Encoding::Ascii;
  if (enc == Encoding::Unknown)
    fail("encoding '" + encoding + "' is not one mfadvr reads (raw, gzip, ascii)");
  if (!endian.empty() && endian != "little" && endian != "big")
    fail("endian '" + endian + "' is not little or big");
  if (!ended && dataFile.empty())
    fail("the header does not end with the blank line that separates it from the data");
  if (lineSkip != 0)
    fail("line skip " + std::to_string(lineSkip) +
         " is not supported: give the data's start as a byte skip");
  if (byteSkip < 0 && enc != Encoding::ExactBinary)
    fail("byte skip -1 (the data at the end of the file) is only defined for raw encoding");
  if (!dataFile.empty() && (dataFile.rfind("LIST", 0) == 0 || words(dataFile).size() != 1))
    fail("its data is split over several files (data file: " + dataFile.substr(0, 60) +
         "); mfadvr reads NRRD data from one file: join them first (e.g. unu join)");

  // The axes: spatial unless their kind is one of values at a place (a vector, a colour, a
  // list) or their direction is 'none'; such axes of one sample are dropped.
  NrrdGrid grid;
  std::vector<size_t> spatial;
  for (size_t a = 0; a < axes; ++a) {
    const std::string kind = kinds.empty() ? std::string() : kinds[a];
    const bool noDirection = !spaceDirections.empty() && !directions[a];
    const bool component = (!kind.empty() && isComponentKind(kind)) || noDirection;
    if (kind == "time" && sizes[a] > 1) {
      // Steps one whole volume after another; a time axis elsewhere interleaves them.
      if (a + 1 != axes) {
        std::string order;
        for (size_t b = 0; b < axes; ++b)
          if (b != a) order += std::to_string(b) + " ";
        fail("axis " + std::to_string(a) + " is a time axis of " + std::to_string(sizes[a]) +
             " samples that is not the last axis: mfadvr reads time series stored one volume "
             "after another (time the slowest axis); reorder the axes first (e.g. unu permute "
             "-p " +
             order + std::to_string(a) + ")");
      }
      const double step = axisStep(spacingOf[a], directions[a]);
      if (!(step > 0.0) || !std::isfinite(step))
        fail("the time axis " + std::to_string(a) + " has spacing " + std::to_string(step) +
             ": time steps must be positive");
      const double start = std::isnan(minOf[a]) ? 0.0 : minOf[a];
      if (!std::isfinite(start) || !std::isfinite(start + step * static_cast<double>(sizes[a] - 1)))
        fail("the time axis " + std::to_string(a) + " does not span finite times");
      grid.timeSteps = sizes[a];
      grid.timeAxis = static_cast<int>(a);
      grid.timeStep = step;
      grid.timeStart = start;
      continue;
    }
    if (component && sizes[a] > 1)
      fail("axis " + std::to_string(a) + " (" +
           (kind.empty() ? std::string("no space direction") : "kind " + kind) + ", " +
           std::to_string(sizes[a]) +
           " samples) holds several values per sample; mfadvr reads scalar volumes: take one "
           "(e.g. unu slice -a " +
           std::to_string(a) + " -p 0) or their magnitude first");
    if (component || kind == "time") continue;
    spatial.push_back(a);
  }
  // More than three: axes of one sample are not the volume's (a 4-D header of one time step).
  if (spatial.size() > 3)
    spatial.erase(
        std::remove_if(spatial.begin(), spatial.end(), [&](size_t a) { return sizes[a] == 1; }),
        spatial.end());
  if (spatial.size() != 3) {
    std::string k;
    for (const auto& w : kinds) k += (k.empty() ? "" : " ") + w;
    fail(std::to_string(spatial.size()) + " spatial axes (sizes " + dimsText(sizes) +
         (k.empty() ? std::string() : ", kinds " + k) + "): a volume has 3");
  }
  if (std::any_of(spatial.begin(), spatial.end(), [&](size_t a) { return sizes[a] < 2; }))
    fail("its spatial axes span " +
         dimsText({sizes[spatial[0]], sizes[spatial[1]], sizes[spatial[2]]}) +
         " samples: 2-D data (a volume needs at least 2 samples along every axis)");
  bool flipped = false;
  for (int i = 0; i < 3; ++i) {
    const size_t a = spatial[size_t(i)];
    grid.dims[i] = sizes[a];
    double step = axisStep(spacingOf[a], directions[a]);
    // A negative spacing flips its axis, which is not applied (as flipping directions).
    if (step < 0.0) {
      step = -step;
      flipped = true;
    }
    if (!(step > 0.0))
      fail("axis " + std::to_string(a) + " has spacing " + std::to_string(step) +
           ": sample spacings must be positive");
    grid.spacing[i] = step;
    if (i < static_cast<int>(origin.size()))
      grid.origin[i] = origin[size_t(i)];
    else if (origin.empty() && !std::isnan(minOf[a]))
      grid.origin[i] = minOf[a];
  }
  // Directions that are not along the axes, or flip them, are not applied (only their lengths).
  bool aligned = !flipped;
  for (int i = 0; i < 3; ++i) {
    const auto& d = directions[spatial[size_t(i)]];
    if (!d) continue;
    for (size_t c = 0; c < d->size(); ++c)
      if ((c == size_t(i) && !((*d)[c] > 0.0)) || (c != size_t(i) && (*d)[c] != 0.0))
        aligned = false;
  }
  if (!aligned)
    grid.notes.push_back(
        "the space directions rotate or flip the axes; the volume is placed in "
        "its index axes, spaced by the directions' lengths from the space origin");
  if (kinds.empty() && grid.dims[0] <= 4 && spaceDirections.empty())
    grid.notes.push_back("the first axis has " + std::to_string(grid.dims[0]) +
                         " samples and the header gives no kinds: read as a spatial axis (a "
                         "header with 'kinds: vector space space space' or the like says that "
                         "an axis holds components)");
  if (const auto q = labels.find('"'); q != std::string::npos) {
    const auto close = labels.find('"', q + 1);
    if (close != std::string::npos) grid.label = labels.substr(q + 1, close - q - 1);
  }
  grid.sampleType = nrrdRawType(type);
  grid.bigEndian = endian == "big";

  const std::int64_t samples = product(sizes);
  const std::int64_t bytes = times(samples, typeBytes);
  // Byte skip counts bytes of the file before raw and ascii data, bytes of the inflated stream
  // before gzip data.
  const std::int64_t fileSkip = enc == Encoding::Deflate ? 0 : std::max<std::int64_t>(byteSkip, 0);
  std::int64_t available = -1;
  std::string where;
  if (!dataFile.empty()) {
    const std::int64_t size = dataFileBytes(dataFile);
    if (size < 0)
      fail("its data file '" + dataFile + "' (\"data file:\" in the header) does not exist");
    available = size - fileSkip;
    where = "its data file '" + dataFile + "'";
  } else {
    available = fileBytes - headerBytes - fileSkip;
    where = "the file after its header";
  }
  // byte skip -1: the raw samples are the file's last bytes.
  requireData(path, "NRRD", dimsText(sizes) + " " + type + " samples in " + encoding + " encoding",
              samples, typeBytes, byteSkip < 0 ? Encoding::Binary : enc,
              std::max<std::int64_t>(0, available), where);
  const std::int64_t start = dataFile.empty() ? headerBytes : 0;
  DeclaredPayload raw;
  if (enc != Encoding::Ascii) {
    raw.file = dataFile.empty() ? path : dataFile;
    raw.gzipAt = enc == Encoding::Deflate ? start : -1;
    raw.offset = enc == Encoding::Deflate ? byteSkip
                 : byteSkip < 0           ? start + std::max<std::int64_t>(available, 0) - bytes
                                          : start + byteSkip;
    raw.dtype = grid.sampleType;
    raw.bigEndian = grid.bigEndian;
    raw.sizes = {grid.dims[0], grid.dims[1], grid.dims[2]};
  }
  NrrdDataLocation location;
  location.raw = raw;
  location.grid = grid;
  if (enc == Encoding::ExactBinary) return location;
  location.dataFile = dataFile;
  location.offset = start + fileSkip;
  location.values = samples;
  location.bytes =
      enc == Encoding::Deflate
          ? std::min(bytes, std::numeric_limits<std::int64_t>::max() - byteSkip) + byteSkip
          : bytes;
  location.gzip = enc == Encoding::Deflate;
  location.declared = dimsText(sizes) + " " + type + " samples";
  return location;
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

NrrdFile checkNrrdDeclaredSize(const std::string& path) {
  const NrrdDataLocation data = checkNrrdHeaderText(readHead(path, kMaxHeaderBytes), path,
                                                    fileSize(path), dataFilesBeside(path));
  NrrdFile out;
  out.grid = data.grid;
  out.payload = besideHeader(data.raw, path);
  if (data.values <= 0) return out;
  fs::path file(path);
  if (!data.dataFile.empty()) {
    file = fs::path(data.dataFile);
    if (!file.is_absolute()) file = fs::path(path).parent_path() / file;
  }
  if (data.gzip) {
    requireCompleteGzip(path, "NRRD", file.string(), data.offset, data.bytes);
    return out;
  }
  // Values missing from ASCII data are an error, not zeros: count them first. A cut inside the
  // last value leaves the count right, so the data must also end with white space (every
  // writer ends it with a line break).
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
  out.asciiFile = file.string();
  out.asciiOffset = data.offset;
  return out;
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
