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

template <class T>
T parseValue(const std::string& option, const std::string& s) {
  T v{};
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  bool ok = !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
  if constexpr (std::is_floating_point_v<T>) ok = ok && std::isfinite(v);
  if (!ok)
    throw CLI::ValidationError(
        option,
        "'" + s + "' is not " + (std::is_floating_point_v<T> ? "a finite number" : "an integer"));
  return v;
}

// One value (repeated on all axes) or three comma-separated values of type T.
template <class T>
std::array<T, 3> parseValues(const std::string& option, const std::string& text, const char* what) {
  const auto parts = splitCommas(text);
  if (parts.size() != 1 && parts.size() != 3)
    throw CLI::ValidationError(option, std::string("expected one ") + what +
                                           " or three comma-separated " + what + "s, got '" + text +
                                           "'");
  std::array<T, 3> out{};
  for (size_t i = 0; i < parts.size(); ++i) out[i] = parseValue<T>(option, parts[i]);
  if (parts.size() == 1) out[1] = out[2] = out[0];
  return out;
}

}  // namespace

std::vector<double> parseNumberList(const std::string& option, const std::string& text,
                                    size_t minCount, size_t maxCount) {
  const auto parts = splitCommas(text);
  if (parts.size() < minCount || parts.size() > maxCount) {
    const std::string count = minCount == maxCount
                                  ? std::to_string(minCount)
                                  : std::to_string(minCount) + " to " + std::to_string(maxCount);
    throw CLI::ValidationError(option, "expected " + count + " comma-separated numbers, got '" +
                                           text + "'");
  }
  std::vector<double> out;
  for (const auto& p : parts) out.push_back(parseValue<double>(option, p));
  return out;
}

std::array<double, 3> parseTriple(const std::string& option, const std::string& text) {
  return parseValues<double>(option, text, "number");
}

std::array<long, 3> parseIntTriple(const std::string& option, const std::string& text) {
  return parseValues<long>(option, text, "integer");
}

bool wantProgress(bool quiet) {
  return !quiet && isatty(STDERR_FILENO);
}

}  // namespace mfadvr::app
