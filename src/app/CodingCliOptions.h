#pragma once
// `encode`'s options for how the model is stored: the control-point coding and the size or
// quality budgets (core/encode/CodingChoice.h).
#include <CLI/CLI.hpp>
#include <string>

#include "core/encode/CodingChoice.h"

namespace mfadvr::app {

class CodingCliOptions {
 public:
  std::string coding, tolerance, bitsPerSample, psnr, rmsError;
  bool lossless = false;

  void addTo(CLI::App* sub, const std::string& group);
  // Throws CLI::ValidationError naming the option for malformed or contradicting values.
  CodingOptions parse() const;
  // `encode`'s default for a grid of `sampleType` samples: zfp for integer samples (the model
  // of an 8/16-bit scan no larger than the scan), the options as given otherwise.
  static void applyGridDefault(CodingOptions& options, const std::string& sampleType);
};

}  // namespace mfadvr::app
