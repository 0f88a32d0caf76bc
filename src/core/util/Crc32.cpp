#include "core/util/Crc32.h"

#include <zlib.h>

#include <algorithm>

namespace mfadvr {

std::uint32_t crc32Continue(std::uint32_t crc, const std::uint8_t* data, size_t n) {
  uLong c = crc;
  while (n > 0) {  // zlib takes uInt lengths
    const uInt chunk = static_cast<uInt>(std::min<size_t>(n, 1u << 30));
    c = crc32(c, data, chunk);
    data += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

std::uint32_t crc32Of(const std::uint8_t* data, size_t n) {
  return crc32Continue(static_cast<std::uint32_t>(crc32(0L, Z_NULL, 0)), data, n);
}

}  // namespace mfadvr
