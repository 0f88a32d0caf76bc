#pragma once
// CRC-32 (zlib's polynomial) of any number of bytes: the checksum of the model files.
#include <cstddef>
#include <cstdint>

namespace mfadvr {

std::uint32_t crc32Of(const std::uint8_t* data, size_t n);

}  // namespace mfadvr
