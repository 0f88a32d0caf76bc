#include "app/FitReportOutput.h"

#include <cstdio>
#include <sstream>

namespace mfadvr::app {

std::string groupDigits(std::int64_t v) {
  std::string digits = std::to_string(v < 0 ? -v : v), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return v < 0 ? "-" + out : out;
}

namespace {
std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
}  // namespace

std::string formatFitReport(const FitReport& r, const std::string& modelPath) {
  std::ostringstream o;
  o << "source          " << r.source << "\n";
  o << "samples         " << r.samples[0] << " x " << r.samples[1] << " x " << r.samples[2] << "  ("
    << groupDigits(r.inputBytes) << " bytes)\n";
  o << "value range     " << fmt("%.6g", r.valueMin) << " .. " << fmt("%.6g", r.valueMax) << "\n";
  o << "degree          " << r.degree[0] << " " << r.degree[1] << " " << r.degree[2] << "\n";
  o << "control points  " << r.controlCounts[0] << " x " << r.controlCounts[1] << " x "
    << r.controlCounts[2] << "\n";
  o << "fit time        " << fmt("%.3f", r.seconds) << " s\n";
  o << "max error       " << fmt("%.4g", r.maxError) << "  (" << fmt("%.3e", r.maxRelativeError())
    << " of the value range)\n";
  o << "rms error       " << fmt("%.4g", r.rmsError) << "  (" << fmt("%.3e", r.rmsRelativeError())
    << " of the value range)\n";
  o << "model size      " << groupDigits(r.modelBytes) << " bytes"
    << (modelPath.empty() ? std::string("  (not written: no -o)") : "  -> " + modelPath) << "\n";
  o << "compression     " << fmt("%.2f", r.compressionRatio())
    << " : 1  (input bytes / model bytes)\n";
  return o.str();
}

nlohmann::json fitReportJson(const FitReport& r, const std::string& modelPath) {
  return {{"source", r.source},
          {"samples", r.samples},
          {"value_min", r.valueMin},
          {"value_max", r.valueMax},
          {"degree", r.degree},
          {"control_counts", r.controlCounts},
          {"fit_seconds", r.seconds},
          {"max_error", r.maxError},
          {"rms_error", r.rmsError},
          {"max_relative_error", r.maxRelativeError()},
          {"rms_relative_error", r.rmsRelativeError()},
          {"input_bytes", r.inputBytes},
          {"model_bytes", r.modelBytes},
          {"compression_ratio", r.compressionRatio()},
          {"model", modelPath.empty() ? nlohmann::json(nullptr) : nlohmann::json(modelPath)}};
}

}  // namespace mfadvr::app
