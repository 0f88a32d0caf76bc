#pragma once
// Parsing of the option values shared by several subcommands.
#include <array>
#include <string>

namespace mfadvr::app {

// "V" or "VX,VY,VZ" -> three values; throws CLI::ValidationError naming the option.
std::array<double, 3> parseTriple(const std::string& option, const std::string& text);
std::array<long, 3> parseIntTriple(const std::string& option, const std::string& text);

// True when progress lines should go to stderr (a terminal, and the user did not ask quiet).
bool wantProgress(bool quiet);

}  // namespace mfadvr::app
