#pragma once
// Provenance as JSON: the one mapping used by the .mfa header and by `mfadvr info --json`.
#include <nlohmann/json.hpp>

#include "core/model/Model.h"

namespace mfadvr {

nlohmann::json provenanceToJson(const Provenance& p);

}  // namespace mfadvr
