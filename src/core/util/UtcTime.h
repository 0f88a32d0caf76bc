#pragma once
#include <string>

namespace mfadvr {

// The current time in UTC as ISO 8601 ("2026-11-21T12:00:00Z"), for provenance records.
std::string utcNow();

}  // namespace mfadvr
