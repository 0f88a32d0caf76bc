#pragma once
// `mfadvr info --json`'s description of one model (also the Python module's Model.info).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model/Model.h"

namespace mfadvr::app {

// Degree, control counts, knots, box, value range, mask, coding and provenance; with a `path`,
// also the file, its size and its format `version`.
nlohmann::json modelInfoJson(const Model& m, const std::string& path, std::uint32_t version);

}  // namespace mfadvr::app
