#pragma once
// Fixed-size values to and from the bytes of the little-endian file formats (.mfa models and
// multi-block files); the formats' readers check sizes before reading.
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

namespace mfadvr {

template <class T>
void appendBytes(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <class T>
T readBytesAt(std::span<const std::uint8_t> b, size_t offset) {
  T v;
  std::memcpy(&v, b.data() + offset, sizeof(T));
  return v;
}

}  // namespace mfadvr
