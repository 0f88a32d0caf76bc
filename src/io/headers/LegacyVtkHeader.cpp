// legacy VTK: the declared-size check (io/DeclaredSizeCheck.h).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdlib>
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

// The raw sample type of a legacy type name; "" for bits and 64-bit integers. "char" is
// VTK_CHAR, signed on the platforms VTK's reader runs on here.
std::string legacyRawType(const std::string& type) {
  static const std::pair<const char*, const char*> kTypes[] = {
      {"char", "int8"},           {"signed_char", "int8"},      {"unsigned_char", "uint8"},
      {"short", "int16"},         {"unsigned_short", "uint16"}, {"int", "int32"},
      {"unsigned_int", "uint32"}, {"float", "float32"},         {"double", "float64"}};
  const std::string t = lower(type);
  for (const auto& [name, raw] : kTypes)
    if (t == name) return raw;
  return "";
}

// The keyword VTK's legacy reader takes a word for: it compares keywords in any case and by
// prefix only ("CELLSxyz" is CELLS, its counts then read from what follows: found by fuzzing).
// Words that start with no keyword of the geometry blocks are returned in lower case.
std::string legacyKeyword(const std::string& word) {
  const std::string w = lower(word);
  for (const char* keyword :
       {"dataset",       "points",   "cells",      "cell_types",    "offsets",
        "connectivity",  "field",    "dimensions", "spacing",       "origin",
        "aspect_ratio",  "extent",   "metadata",   "x_coordinates", "y_coordinates",
        "z_coordinates", "vertices", "lines",      "polygons",      "triangle_strips"})
    if (w.rfind(keyword, 0) == 0) return keyword;
  return w;
}

// What VTK's legacy reader reads before the dataset: the version line ('# vtk DataFile
// Version x.y', any version), one title line (any text, also empty), then the first word after
// it, ASCII or BINARY in any case: VTK skips blank lines (and spaces, CR line ends) before it.
// Leaves `in` at the start of the line after that word.
struct LegacyPreamble {
  bool valid = false;  // a legacy header with a known file type
  bool binary = false;
  std::string version;  // "3.0", "5.1", ...
  // Words after ASCII or BINARY on its line: VTK's reader reads words, not lines, so they would
  // be the dataset's first keywords.
  bool moreOnTypeLine = false;
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
  p.moreOnTypeLine = !words(line).empty();
  p.binary = type == "binary";
  p.valid = static_cast<bool>(in);
  return p;
}

}  // namespace

DeclaredPayload checkLegacyVtkHeaderText(const std::string& header, const std::string& path,
                                         std::int64_t fileBytes) {
  std::istringstream in(header);
  const LegacyPreamble preamble = readLegacyPreamble(in);
  if (!preamble.valid) return {};
  const Encoding enc = preamble.binary ? Encoding::Binary : Encoding::Ascii;
  // Bytes of the header consumed so far (the stream ends at the header's last byte).
  const auto consumed = [&]() -> std::int64_t {
    const auto at = in.tellg();
    return at < 0 ? static_cast<std::int64_t>(header.size()) : static_cast<std::int64_t>(at);
  };
  std::string line;
  std::vector<std::int64_t> dims;
  std::int64_t pointData = -1;
  bool cellData = false;
  std::string dataset;
  while (std::getline(in, line)) {
    const auto w = words(line);
    if (w.empty()) continue;
    const std::string key = lower(w[0]);
    if (key == "dataset" && w.size() >= 2) {
      dataset = lower(w[1]);
    } else if (key == "dimensions" && w.size() >= 4 && dataset == "structured_points") {
      dims = {parseCount(w[1]), parseCount(w[2]), parseCount(w[3])};
      if (std::any_of(dims.begin(), dims.end(), [](std::int64_t d) { return d < 0; })) return {};
      // A field of structured points has a value per point or per cell: at least one byte per
      // cell (an axis of one point has one cell). Other grids list their points or
      // coordinates, which the POINTS check and VTK's reader check.
      std::vector<std::int64_t> cells;
      for (std::int64_t d : dims) cells.push_back(std::max<std::int64_t>(d - 1, 1));
      requireData(
          path, "legacy VTK", dimsText(dims) + " points (" + grouped(product(cells)) + " cells)",
          product(cells), 1, Encoding::Binary, fileBytes - consumed(), "the file after its header");
    } else if (key == "cell_data") {
      cellData = true;
    } else if (key == "point_data" && w.size() >= 2) {
      pointData = parseCount(w[1]);
    } else if (key == "points" && w.size() >= 3) {
      // The first data block: three coordinates per point, right after this line.
      const std::int64_t n = parseCount(w[1]), bytes = legacyTypeBytes(w[2]);
      if (n < 0 || bytes == 0) return {};
      requireData(path, "legacy VTK", grouped(n) + " points of type " + w[2], times(n, 3), bytes,
                  enc, fileBytes - consumed(), "the file after the POINTS line");
      return {};  // binary data follows: lines no longer mean anything
    } else if (key == "scalars" && w.size() >= 3 && pointData >= 0) {
      // Structured points: POINT_DATA n, SCALARS name type [components], LOOKUP_TABLE name;
      // VTK reads the values from the line after LOOKUP_TABLE's.
      const std::int64_t bytes = legacyTypeBytes(w[2]);
      const std::int64_t components = w.size() >= 4 ? parseCount(w[3]) : 1;
      if (bytes == 0 || components <= 0) return {};
      std::string next;
      while (std::getline(in, next) && words(next).empty()) {
      }
      if (!in || lower(words(next)[0]) != "lookup_table") return {};
      requireData(path, "legacy VTK",
                  grouped(pointData) + " point values of type " + w[2] +
                      (components > 1 ? " x " + std::to_string(components) : ""),
                  times(pointData, components), bytes, enc, fileBytes - consumed(),
                  "the file after the SCALARS block's header");
      // The samples of the first point-data array of structured points, if it holds them.
      const std::string dtype = legacyRawType(w[2]);
      if (!preamble.binary || cellData || in.eof() || dataset != "structured_points" ||
          dims.size() != 3 || dtype.empty() || product(dims) != pointData)
        return {};
      DeclaredPayload payload;
      payload.file = path;
      payload.offset = consumed();
      payload.dtype = dtype;
      payload.bigEndian = true;  // legacy binary data is big-endian
      payload.sizes = dims;
      payload.components = static_cast<int>(components);
      payload.arrayName = w[1];
      return payload;
    }
  }
  return {};
}

namespace {

// Walks the dataset's blocks of a legacy file before its point or cell data (POINTS, CELLS /
// OFFSETS / CONNECTIVITY, CELL_TYPES, FIELD, X/Y/Z_COORDINATES; the structured points'
// DIMENSIONS, SPACING, ORIGIN, ASPECT_RATIO, EXTENT), skipping their data, and checks what VTK's
// readers trust: they dereference null for a CELLS block whose size cannot hold its cells, and for
// a dataset's FIELD block that they could not read. Stops at the first other keyword.
void checkLegacyCells(std::istream& in, const std::string& path) {
  const auto fail = [&](const std::string& why) {
    throw Error("cannot read " + path + " as legacy VTK: " + why +
                "; the file is damaged or its header is wrong");
  };
  const LegacyPreamble preamble = readLegacyPreamble(in);
  if (!preamble.valid) return;
  // The walk goes line by line where VTK's reader reads words: every keyword line must hold its
  // keyword's words and nothing else (found by fuzzing: a FIELD block on the DATASET line).
  if (preamble.moreOnTypeLine) fail("the ASCII or BINARY line holds more words");
  const bool binary = preamble.binary;
  const bool newCells = preamble.version.rfind("5.", 0) == 0;  // 5.x: offsets + connectivity
  std::string line;
  const auto skip = [&](std::int64_t values, std::int64_t bytes) {
    if (values < 0 || bytes <= 0) return false;
    if (binary) {
      in.ignore(static_cast<std::streamsize>(std::min<std::int64_t>(
          times(values, bytes), std::numeric_limits<std::streamsize>::max())));
    } else {
      // Every value is a number: VTK's reader goes on after a word it cannot read as one, and
      // takes a keyword inside the data ("0 0 CELLS 2 0") for the next block (found by fuzzing).
      std::string token;
      for (std::int64_t v = 0; v < values && in >> token; ++v) {
        char* end = nullptr;
        std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0')
          fail("the data holds '" + token.substr(0, 20) + "' where value " + std::to_string(v + 1) +
               " of a block of " + std::to_string(values) + " numbers belongs");
      }
    }
    return static_cast<bool>(in);
  };
  // The cells of a CELLS n size block: each a point count, then that many point ids, n cells in
  // exactly `size` integers. VTK's reader walks the block by the counts and reads past its end
  // when they add up to more (found by a valgrind replay of a fuzzing corpus: an invalid read in
  // vtkCellArray::AppendLegacyFormat).
  const auto walkCells = [&](const std::string& name, std::int64_t cellCount, std::int64_t size) {
    std::int64_t read = 0;  // integers of the block read so far
    const auto next = [&](std::int64_t& value) {
      if (binary) {
        unsigned char b[4];
        if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
        value =
            static_cast<std::int32_t>((std::uint32_t(b[0]) << 24) | (std::uint32_t(b[1]) << 16) |
                                      (std::uint32_t(b[2]) << 8) | std::uint32_t(b[3]));
      } else {
        std::string token;
        if (!(in >> token)) return false;
        char* end = nullptr;
        errno = 0;
        value = std::strtoll(token.c_str(), &end, 10);
        if (end == token.c_str() || *end != '\0' || errno == ERANGE)
          fail("the " + name + " block holds '" + token.substr(0, 20) + "' where integer " +
               std::to_string(read + 1) + " of " + std::to_string(size) + " belongs");
      }
      ++read;
      return true;
    };
    for (std::int64_t c = 0; c < cellCount; ++c) {
      if (read == size)
        fail("the " + name + " block's " + grouped(size) + " integers end after cell " +
             std::to_string(c) + " of " + grouped(cellCount));
      std::int64_t points = 0;
      if (!next(points)) return false;
      if (points < 0 || points > size - read)
        fail("cell " + std::to_string(c + 1) + " of " + name + " declares " +
             std::to_string(points) + " points, but its block of " + grouped(size) +
             " integers has " + grouped(size - read) + " left");
      for (std::int64_t i = 0; i < points; ++i) {
        std::int64_t id = 0;
        if (!next(id)) return false;
      }
    }
    if (read != size)
      fail("the " + grouped(cellCount) + " cells of " + name + " take " + grouped(read) +
           " of its " + grouped(size) + " integers");
    return true;
  };
  // VTK's reader reads at most 255 characters a word and takes the rest as the next word.
  const auto checkWordLengths = [&](const std::vector<std::string>& w) {
    for (const std::string& word : w)
      if (word.size() > 255)
        fail("a line holds a word of " + std::to_string(word.size()) +
             " characters, more than VTK's reader reads as one");
  };
  // A METADATA block (after an array) runs to the next empty line.
  const auto skipMetadata = [&] {
    while (std::getline(in, line) && !words(line).empty()) {
    }
  };
  // FIELD name arrays, then per array "name components tuples type" and its values, or
  // NULL_ARRAY. VTK's readers set a dataset's field data without checking that it was read (found
  // by fuzzing: a null dereference in the structured points reader), so every array must be
  // what VTK can read. Arrays of strings or other non-numeric types are refused here.
  const auto checkField = [&](const std::vector<std::string>& w) {
    if (w.size() != 3)
      fail("the FIELD line has " + std::to_string(w.size() - 1) + " fields, not 2");
    // VTK reads the counts as int: a larger one fails its read and leaves the block unread.
    constexpr std::int64_t kIntMax = std::numeric_limits<int>::max();
    const std::int64_t arrays = parseCount(w[2]);
    if (arrays < 0 || arrays > kIntMax) fail("FIELD '" + w[2] + "' is not an array count");
    for (std::int64_t i = 0; i < arrays;) {
      std::string header;
      while (std::getline(in, header) && words(header).empty()) {
      }
      if (!in)
        fail("the FIELD block ends before its array " + std::to_string(i + 1) + " of " +
             std::to_string(arrays));
      const auto a = words(header);
      if (legacyKeyword(a[0]) == "metadata") {
        skipMetadata();
        continue;
      }
      ++i;
      if (a.size() == 1 && a[0] == "NULL_ARRAY") continue;
      if (a.size() != 4)
        fail("FIELD array " + std::to_string(i) + "'s line has " + std::to_string(a.size()) +
             " fields, not 4 (name, components, tuples, type)");
      checkWordLengths(a);
      const std::int64_t components = parseCount(a[1]), tuples = parseCount(a[2]);
      const std::int64_t bytes = legacyTypeBytes(a[3]);
      if (components < 1 || components > kIntMax || tuples < 0 || tuples > kIntMax || bytes == 0)
        fail("FIELD array '" + a[0].substr(0, 40) + "' declares '" + a[1] + " " + a[2] + " " +
             a[3].substr(0, 20) + "', not a component count, a tuple count and a numeric type");
      if (!skip(times(components, tuples), bytes))
        fail("the values of FIELD array '" + a[0].substr(0, 40) + "' are cut off");
    }
  };
  // The structured points' keywords and how many numbers follow each on its line.
  const auto structuredValues = [](const std::string& key) {
    return key == "extent" ? 6
           : (key == "dimensions" || key == "spacing" || key == "origin" || key == "aspect_ratio")
               ? 3
               : 0;
  };
  std::int64_t cells = -1;
  // Keyword lines are few in a valid file; the bound only keeps a malformed one's walk short.
  for (int guard = 0; guard < 4096 && std::getline(in, line); ++guard) {
    const auto w = words(line);
    if (w.empty()) continue;
    const std::string key = legacyKeyword(w[0]);
    checkWordLengths(w);
    if (key == "dataset") {
      if (w.size() != 2)
        fail("the DATASET line has " + std::to_string(w.size() - 1) + " fields, not 1");
      continue;
    }
    if (key == "field") {
      checkField(w);
      continue;
    }
    if (key == "metadata") {
      skipMetadata();
      continue;
    }
    // VTK reads these values across line ends too: they must be on the keyword's line, so that
    // the walk stays where VTK's reader is.
    if (const int n = structuredValues(key)) {
      if (static_cast<int>(w.size()) != n + 1)
        fail("the " + w[0].substr(0, key.size()) + " line has " + std::to_string(w.size() - 1) +
             " fields, not " + std::to_string(n));
      // Each a number as a whole: VTK reads the number at a word's start and takes the rest of
      // the word for the next keyword (found by fuzzing: "DIMENSIONS 10 4 3field" read a FIELD
      // block that was not there).
      for (size_t i = 1; i < w.size(); ++i) {
        char* end = nullptr;
        std::strtod(w[i].c_str(), &end);
        if (end == w[i].c_str() || *end != '\0')
          fail("the " + w[0].substr(0, key.size()) + " line holds '" + w[i].substr(0, 20) +
               "', which is not a number");
      }
      continue;
    }
    // A keyword line is text; VTK's stream reads stop early at some other bytes (0xff) and
    // leave counts unset (found by fuzzing: an allocation of 0xf5f5... bytes).
    // Poly data's cell blocks have the layout of CELLS.
    const bool cellBlock = key == "cells" || key == "vertices" || key == "lines" ||
                           key == "polygons" || key == "triangle_strips";
    const bool geometry = key == "points" || cellBlock || key == "cell_types";
    if (geometry && (hasControlCharacters(line) ||
                     std::any_of(line.begin(), line.end(),
                                 [](char c) { return static_cast<unsigned char>(c) >= 0x80; })))
      fail("the " + w[0].substr(0, key.size()) + " line holds bytes that are not text");
    // VTK reads a keyword's counts across line ends: a short line takes its numbers from the
    // data that follows.
    if ((key == "points" || cellBlock) && w.size() != 3)
      fail("the " + w[0].substr(0, key.size()) + " line has " + std::to_string(w.size() - 1) +
           " fields, not 2");
    if (key == "cell_types" && w.size() != 2)
      fail("the CELL_TYPES line has " + std::to_string(w.size() - 1) + " fields, not 1");
    if (key.size() == 13 && key.compare(1, 12, "_coordinates") == 0) {
      // A rectilinear grid's coordinates along one axis: a count and a type, then the values.
      if (w.size() != 3 || parseCount(w[1]) < 0 || legacyTypeBytes(w[2]) == 0)
        fail("the " + w[0].substr(0, key.size()) + " line is not a count and a VTK data type");
      if (!skip(parseCount(w[1]), legacyTypeBytes(w[2]))) return;
    } else if (key == "points" && w.size() >= 3) {
      if (parseCount(w[1]) < 0 || legacyTypeBytes(w[2]) == 0)
        fail("POINTS '" + w[1] + " " + w[2] + "' is not a count and a VTK data type");
      if (!skip(times(parseCount(w[1]), 3), legacyTypeBytes(w[2]))) return;
    } else if (cellBlock && w.size() >= 3) {
      const std::string name = w[0].substr(0, key.size());
      const std::int64_t a = parseCount(w[1]), b = parseCount(w[2]);
      if (a < 0 || b < 0) fail(name + " '" + w[1] + " " + w[2] + "' are not counts");
      if (newCells) {
        // CELLS offsets connectivity: cells + 1 offsets, at least one point per cell.
        if (a > 0 && b < a - 1)
          fail(name + " declares " + grouped(a) + " offsets but only " + grouped(b) +
               " connectivity entries");
        if (key == "cells") cells = a > 0 ? a - 1 : 0;
      } else {
        // CELLS n size: each cell is its point count and at least one point.
        if (b < times(a, 2))
          fail(name + " declares " + grouped(a) + " cells in " + grouped(b) +
               " integers, fewer than 2 per cell");
        if (key == "cells") cells = a;
        if (!walkCells(name, a, b)) return;
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

DeclaredPayload checkLegacyVtkDeclaredSize(const std::string& path) {
  DeclaredPayload payload = checkLegacyVtkHeaderText(readHead(path, 4096), path, fileSize(path));
  std::ifstream in(path, std::ios::binary);
  checkLegacyCells(in, path);
  return payload;
}

}  // namespace mfadvr
