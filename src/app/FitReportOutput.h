#pragma once
// The fit report as people read it and as programs read it.
#include <nlohmann/json.hpp>
#include <string>

#include "core/encode/FitReport.h"

namespace mfadvr::app {

std::string formatFitReport(const FitReport& r, const std::string& modelPath);
nlohmann::json fitReportJson(const FitReport& r, const std::string& modelPath);

// "1,234,567"
std::string groupDigits(std::int64_t v);
// Bytes per sample, with the digits that matter: "45", "3.2", "0.046".
std::string bytesPerSampleText(double v);

}  // namespace mfadvr::app
