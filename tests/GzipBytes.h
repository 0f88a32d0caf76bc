#pragma once
// Bytes compressed as one gzip stream, as NRRD's gzip encoding and .nii.gz files store samples
// (for tests that write such files).
#include <zlib.h>

#include <string>

namespace mfadvr::test {

// `raw` compressed as a gzip stream (header, deflate data, CRC and size trailer).
inline std::string gzipBytes(const std::string& raw) {
  std::string out(compressBound(static_cast<uLong>(raw.size())) + 64, '\0');
  z_stream z{};
  deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);  // 15 + 16: gzip wrapper
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
  z.avail_in = static_cast<uInt>(raw.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

}  // namespace mfadvr::test
