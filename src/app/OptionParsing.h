#pragma once
// Parsing of the option values shared by several subcommands.
#include <array>
#include <string>
#include <vector>

#include "core/encode/StructuredEncoder.h"
#include "io/VolumeLoader.h"

namespace mfadvr::app {

// "V" or "VX,VY,VZ" -> three values; throws CLI::ValidationError naming the option.
std::array<double, 3> parseTriple(const std::string& option, const std::string& text);
std::array<long, 3> parseIntTriple(const std::string& option, const std::string& text);
// Between minCount and maxCount comma-separated finite numbers.
std::vector<double> parseNumberList(const std::string& option, const std::string& text,
                                    size_t minCount, size_t maxCount);

// --degree and --ctrl texts -> fit options (validated by the encoder later).
StructuredFitOptions parseFitOptions(const std::string& degree, const std::string& ctrl);
// --spacing, --origin (empty: not given) and --field -> volume load options.
VolumeLoadOptions parseVolumeLoadOptions(const std::string& spacing, const std::string& origin,
                                         const std::string& field);

// One progress line on stderr, redrawn in place ("  encoding: 40% (fit y)"); ends the line at 1.
void printProgress(const char* what, double fraction, const std::string& stage = "");

// True when progress lines should go to stderr (a terminal, and the user did not ask quiet).
bool wantProgress(bool quiet);

}  // namespace mfadvr::app
