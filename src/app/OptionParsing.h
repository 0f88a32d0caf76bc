#pragma once
// Parsing of the option values shared by several subcommands.
#include <array>
#include <chrono>
#include <cstdint>
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

// Progress lines of long work over an amount of data, with its rate and the time left since
// this object was made: "  encoding: 40% (block 3 of 8, 85.2 MB/s, 12 s left)".
class ThroughputProgress {
 public:
  // `bytes`: the data that the fractions given to operator() are parts of.
  explicit ThroughputProgress(const char* what, double bytes = 0)
      : what_(what), bytes_(bytes), start_(std::chrono::steady_clock::now()) {}
  void operator()(double fraction, const std::string& stage = "") const {
    print(fraction, bytes_, stage);
  }
  // For work that counts its bytes: `done` of `total`.
  void bytes(std::int64_t done, std::int64_t total) const {
    if (total > 0) print(double(done) / double(total), double(total), "");
  }

 private:
  void print(double fraction, double bytes, const std::string& stage) const;
  const char* what_;
  double bytes_;
  std::chrono::steady_clock::time_point start_;
};

// True when progress lines should go to stderr (a terminal, and the user did not ask quiet).
bool wantProgress(bool quiet);

}  // namespace mfadvr::app
