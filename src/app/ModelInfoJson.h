#pragma once
// `mfadvr info --json`'s description of one model (also the Python module's Model.info).
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model/DomainBox.h"
#include "core/model/Model.h"
#include "core/model/TimeVaryingModel.h"

namespace mfadvr::app {

// Degree, control counts, knots, box, value range, mask, coding and provenance; with a `path`,
// also the file, its size and its format `version`.
nlohmann::json modelInfoJson(const Model& m, const std::string& path, std::uint32_t version);

// The time axis of a time-varying model (null without one): degree, control count, range, the
// steps' times and whether they are evenly spaced.
nlohmann::json timeAxisJson(const TimeVaryingModel& m);

// A multi-block model's description (`info --json` of a multi-block file, without the file's
// keys): format "mfadvr-blocks", the block grid, box, value range, the control points of all
// blocks, and `entries`, each block's blockEntryJson in file order (x fastest).
nlohmann::json blockModelsInfoJson(const Index3& blocks, const DomainBox& box, double valueMin,
                                   double valueMax, nlohmann::json entries);
// One block: its model's modelInfoJson and "region" [xmin, xmax, ymin, ymax, zmin, zmax].
nlohmann::json blockEntryJson(const Model& m, const DomainBox& region);

}  // namespace mfadvr::app
