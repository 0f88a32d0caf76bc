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

}  // namespace

std::vector<Vec3d> parsePointList(std::string_view text, std::string_view name) {
  std::vector<Vec3d> points;
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
    double xyz[3];
    bool numeric = tok.size() == 3;
    for (size_t i = 0; numeric && i < 3; ++i) numeric = parseNumber(tok[i], xyz[i]);
    if (!seenContent) {
      seenContent = true;
      double ignored;
      bool anyNumber = false;
      for (const auto& t : tok) anyNumber = anyNumber || parseNumber(t, ignored);
      if (!numeric && !anyNumber) continue;  // header line such as "x,y,z"
    }
    const std::string where = std::string(name) + " line " + std::to_string(lineNo);
    if (!numeric)
      throw Error(where + ": expected three numbers 'x y z' (comma or space separated), got '" +
                  std::string(line.substr(0, 80)) + "'");
    if (!(std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2])))
      throw Error(where + ": coordinates must be finite");
    points.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
  if (points.empty()) throw Error(std::string(name) + ": no points");
  return points;
}

}  // namespace mfadvr
