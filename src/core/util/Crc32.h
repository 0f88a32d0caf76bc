#pragma once
// CRC-32 (zlib's polynomial) of any number of bytes: the checksum of the model files.
#include <cstddef>
#include <cstdint>

namespace mfadvr {

std::uint32_t crc32Of(const std::uint8_t* data, size_t n);
// The CRC-32 of bytes that follow those whose CRC-32 is `crc` (0 for none): a checksum computed
// piece by piece equals crc32Of of the whole.
std::uint32_t crc32Continue(std::uint32_t crc, const std::uint8_t* data, size_t n);

}  // namespace mfadvr
