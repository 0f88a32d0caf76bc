#include "app/OptionParsing.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

#include "core/util/Error.h"

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
    throw CLI::ValidationError(
        option, "expected " + count + " comma-separated numbers, got '" + text + "'");
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

StructuredFitOptions parseFitOptions(const std::string& degree, const std::string& ctrl) {
  StructuredFitOptions fit;
  const auto p = parseIntTriple("--degree", degree);
  for (int a = 0; a < 3; ++a) {
    if (p[a] < -1000 || p[a] > 1000) throw CLI::ValidationError("--degree", "degree out of range");
    fit.degree[a] = static_cast<int>(p[a]);  // the encoder explains the valid range
  }
  if (!ctrl.empty()) {
    const auto n = parseIntTriple("--ctrl", ctrl);
    for (int a = 0; a < 3; ++a) {
      if (n[a] < 1) throw CLI::ValidationError("--ctrl", "counts must be positive");
      fit.controlCounts[a] = n[a];
    }
  }
  return fit;
}

void FieldOptionTexts::addTo(CLI::App* sub, const std::string& group) {
  sub->add_option("--field", name,
                  "Array to read (default: the active scalars, else the first one-component "
                  "point-data array, else the same from the cell data)")
      ->group(group);
  sub->add_option("--association", association,
                  "point | cell | auto: read the --field from the point data or the cell data "
                  "(grids: cell data is sampled at the cell centres; meshes: averaged to the "
                  "points); default auto, points first")
      ->group(group);
  sub->add_option("--component", component,
                  "N | magnitude: the component of a vector or multi-component array to use "
                  "(0 = x), or the magnitude of its components")
      ->group(group);
}

FieldSelection FieldOptionTexts::parse() const {
  FieldSelection selection;
  selection.name = name;
  try {
    if (!association.empty()) selection.association = parseFieldAssociation(association);
  } catch (const Error& e) {
    throw CLI::ValidationError("--association", e.what());
  }
  try {
    if (!component.empty()) selection.component = parseFieldComponent(component);
  } catch (const Error& e) {
    throw CLI::ValidationError("--component", e.what());
  }
  return selection;
}

VolumeLoadOptions parseVolumeLoadOptions(const std::string& spacing, const std::string& origin,
                                         const FieldOptionTexts& field) {
  VolumeLoadOptions load;
  if (!spacing.empty()) {
    const auto s = parseTriple("--spacing", spacing);
    load.spacing = Vec3d(s[0], s[1], s[2]);
  }
  if (!origin.empty()) {
    const auto s = parseTriple("--origin", origin);
    load.origin = Vec3d(s[0], s[1], s[2]);
  }
  load.field = field.parse();
  return load;
}

void printProgress(const char* what, double fraction, const std::string& stage) {
  std::cerr << "\r  " << what << ": " << static_cast<int>(fraction * 100) << "%"
            << (stage.empty() ? "" : " (" + stage + ")") << "   " << (fraction >= 1.0 ? "\n" : "")
            << std::flush;
}

void ThroughputProgress::print(double fraction, double bytes, const std::string& stage) const {
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string line = stage;
  if (fraction > 0.0 && t > 0.0) {
    char rate[96];
    std::snprintf(rate, sizeof rate, "%s%.1f MB/s, %.0f s left", stage.empty() ? "" : ", ",
                  fraction * bytes / 1e6 / t, t * (1.0 - fraction) / fraction);
    line += rate;
  }
  printProgress(what_, fraction, line);
}

bool wantProgress(bool quiet) {
  return !quiet && isatty(STDERR_FILENO);
}

}  // namespace mfadvr::app
