#include "app/OptionParsing.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <vector>

namespace mfadvr::app {
namespace {

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return parts;
}

}  // namespace

std::array<double, 3> parseTriple(const std::string& option, const std::string& text) {
  const auto parts = splitCommas(text);
  if (parts.size() != 1 && parts.size() != 3)
    throw CLI::ValidationError(option, "expected one value or three comma-separated values, got '" +
                                           text + "'");
  std::array<double, 3> out{};
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string& s = parts[i];
    double v = 0.0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v))
      throw CLI::ValidationError(option, "'" + s + "' is not a finite number");
    out[i] = v;
  }
  if (parts.size() == 1) out[1] = out[2] = out[0];
  return out;
}

std::array<long, 3> parseIntTriple(const std::string& option, const std::string& text) {
  const auto parts = splitCommas(text);
  if (parts.size() != 1 && parts.size() != 3)
    throw CLI::ValidationError(option, "expected one integer or three comma-separated integers, got '" +
                                           text + "'");
  std::array<long, 3> out{};
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string& s = parts[i];
    long v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size())
      throw CLI::ValidationError(option, "'" + s + "' is not an integer");
    out[i] = v;
  }
  if (parts.size() == 1) out[1] = out[2] = out[0];
  return out;
}

bool wantProgress(bool quiet) { return !quiet && isatty(STDERR_FILENO); }

}  // namespace mfadvr::app
