#pragma once
// Parsing of the option values shared by several subcommands.
#include <array>
#include <string>
#include <vector>

namespace mfadvr::app {

// "V" or "VX,VY,VZ" -> three values; throws CLI::ValidationError naming the option.
std::array<double, 3> parseTriple(const std::string& option, const std::string& text);
std::array<long, 3> parseIntTriple(const std::string& option, const std::string& text);
// Between minCount and maxCount comma-separated finite numbers.
std::vector<double> parseNumberList(const std::string& option, const std::string& text,
                                    size_t minCount, size_t maxCount);

// True when progress lines should go to stderr (a terminal, and the user did not ask quiet).
bool wantProgress(bool quiet);

}  // namespace mfadvr::app
