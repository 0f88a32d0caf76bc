#pragma once
// Parsing of the option values shared by several subcommands.
#include <array>
#include <string>
#include <vector>

#include "core/encode/StructuredEncoder.h"
#include "io/VolumeLoader.h"

namespace CLI {
class App;
}

namespace mfadvr::app {

// "V" or "VX,VY,VZ" -> three values; throws CLI::ValidationError naming the option.
std::array<double, 3> parseTriple(const std::string& option, const std::string& text);
std::array<long, 3> parseIntTriple(const std::string& option, const std::string& text);
// Between minCount and maxCount comma-separated finite numbers.
std::vector<double> parseNumberList(const std::string& option, const std::string& text,
                                    size_t minCount, size_t maxCount);

// --degree and --ctrl texts -> fit options (validated by the encoder later).
StructuredFitOptions parseFitOptions(const std::string& degree, const std::string& ctrl);
// The texts of --field, --association and --component, which say which array of a file is
// encoded or rendered (the same three options on encode, render and view).
struct FieldOptionTexts {
  std::string name, association, component;
  void addTo(CLI::App* sub, const std::string& group);
  // Throws CLI::ValidationError naming the option for a bad association or component.
  FieldSelection parse() const;
};

// --spacing, --origin (empty: not given) and the field options -> volume load options.
VolumeLoadOptions parseVolumeLoadOptions(const std::string& spacing, const std::string& origin,
                                         const FieldOptionTexts& field);

// One progress line on stderr, redrawn in place ("  encoding: 40% (fit y)"); ends the line at 1.
void printProgress(const char* what, double fraction, const std::string& stage = "");

// True when progress lines should go to stderr (a terminal, and the user did not ask quiet).
bool wantProgress(bool quiet);

}  // namespace mfadvr::app
