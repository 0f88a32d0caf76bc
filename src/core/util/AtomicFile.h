#pragma once
// Writes a whole file so that readers see either the old file or the complete new one.
#include <filesystem>
#include <string_view>

namespace mfadvr {

// Throws mfadvr::Error (naming the path and the system's reason) on failure and leaves no
// temporary file behind.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace mfadvr
