#include "core/util/PointList.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

bool isSeparator(char c) {
  return c == ',' || c == ' ' || c == '\t' || c == '\r';
}

// Splits a line into tokens at commas and whitespace.
std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSeparator(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !isSeparator(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool parseNumber(std::string_view t, double& v) {
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  return !t.empty() && r.ec == std::errc() && r.ptr == t.data() + t.size();
}

// What a table of numbers looks like, for its error messages.
struct TableShape {
  size_t columns;
  const char* expected;   // "three numbers 'x y z'"
  const char* notFinite;  // "coordinates must be finite"
  const char* empty;      // "no points"
  // Data to encode: a last line without its line break is taken for a cut-off file (a text
  // list declares no count, so this is the one sign of truncation it can give).
  bool requireFinalLineBreak = false;
};

struct Table {
  std::vector<std::string> header;  // the header's names; empty when there is none
  std::vector<double> numbers;      // row-major, shape.columns per row
};

// The one line-by-line reader behind both list formats.
Table parseTable(std::string_view text, std::string_view name, const TableShape& shape) {
  Table table;
  std::vector<double> row(shape.columns);
  size_t lineNo = 0, pos = 0;
  bool seenContent = false;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    ++lineNo;
    const auto tok = tokens(line);
    if (tok.empty() || tok.front().front() == '#') continue;
    bool numeric = tok.size() == shape.columns;
    for (size_t i = 0; numeric && i < shape.columns; ++i) numeric = parseNumber(tok[i], row[i]);
    if (!seenContent) {
      seenContent = true;
      double ignored;
      bool anyNumber = false;
      for (const auto& t : tok) anyNumber = anyNumber || parseNumber(t, ignored);
      if (!numeric && !anyNumber) {  // header line such as "x,y,z"
        for (const auto& t : tok) table.header.emplace_back(t);
        continue;
      }
    }
    const std::string where = std::string(name) + " line " + std::to_string(lineNo);
    if (!numeric)
      throw Error(where + ": expected " + shape.expected + " (comma or space separated), got '" +
                  std::string(line.substr(0, 80)) + "'");
    for (double v : row)
      if (!std::isfinite(v)) throw Error(where + ": " + shape.notFinite);
    table.numbers.insert(table.numbers.end(), row.begin(), row.end());
  }
  if (table.numbers.empty()) throw Error(std::string(name) + ": " + shape.empty);
  if (shape.requireFinalLineBreak && !text.empty() && text.back() != '\n') {
    throw Error(std::string(name) + " line " + std::to_string(lineNo) +
                ": the last line does not end with a line break, so the file may be cut off "
                "inside it; if the file is complete, end it with a line break");
  }
  return table;
}

}  // namespace

std::vector<Vec3d> parsePointList(std::string_view text, std::string_view name) {
  const Table t = parseTable(
      text, name, {3, "three numbers 'x y z'", "coordinates must be finite", "no points"});
  std::vector<Vec3d> points;
  points.reserve(t.numbers.size() / 3);
  for (size_t i = 0; i < t.numbers.size(); i += 3)
    points.emplace_back(t.numbers[i], t.numbers[i + 1], t.numbers[i + 2]);
  return points;
}

PointTimes parsePointTimeList(std::string_view text, std::string_view name) {
  const Table t = parseTable(
      text, name,
      {4, "four numbers 'x y z t'", "coordinates and times must be finite", "no points"});
  PointTimes out;
  out.points.reserve(t.numbers.size() / 4);
  out.times.reserve(t.numbers.size() / 4);
  for (size_t i = 0; i < t.numbers.size(); i += 4) {
    out.points.emplace_back(t.numbers[i], t.numbers[i + 1], t.numbers[i + 2]);
    out.times.push_back(t.numbers[i + 3]);
  }
  return out;
}

ScatteredData parsePointValueList(std::string_view text, std::string_view name) {
  const Table t =
      parseTable(text, name,
                 {4, "four numbers 'x y z value'", "coordinates and values must be finite",
                  "no points with values", true});
  ScatteredData data;
  const size_t n = t.numbers.size() / 4;
  data.points.reserve(n);
  data.values.reserve(n);
  for (size_t i = 0; i < t.numbers.size(); i += 4) {
    data.points.emplace_back(t.numbers[i], t.numbers[i + 1], t.numbers[i + 2]);
    data.values.push_back(t.numbers[i + 3]);
  }
  data.source = std::string(name);
  data.fieldName = t.header.size() == 4 ? t.header[3] : std::string("value");
  data.fieldAssociation = "point data";
  data.kind = "point cloud";
  data.sampleType = "text";
  data.inputBytes = static_cast<std::int64_t>(n * sizeof(double));
  return data;
}

}  // namespace mfadvr
