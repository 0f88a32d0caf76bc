#pragma once
// The encoding options shared by `encode` and `render` (which encodes a non-model input on the
// fly): degree, control points, adaptive bound, smoothing and domain mask.
#include <CLI/CLI.hpp>
#include <string>

#include "core/encode/Encoder.h"

namespace mfadvr::app {

struct EncodeCliOptions {
  std::string degree = "3", ctrl, smooth, maxError, maxCtrl, maskRes;
  int maxRounds = 30;
  bool noMask = false;

  // Registers the options on `sub` under `group`.
  void addTo(CLI::App* sub, const std::string& group);
  // Throws CLI::ValidationError naming the option for malformed values.
  EncodeOptions parse() const;
};

}  // namespace mfadvr::app
