#pragma once
// Small NIfTI-1 and DICOM files written byte by byte from the formats' definitions (shared by
// the reader tests and the truncation tests).
#include <cstdint>
#include <cstring>
#include <string>

#include "../GzipBytes.h"  // tests/: also built by the fuzz targets, which see tests/io only

namespace mfadvr::test {

// The stored volume: 5 x 4 x 3 int16 samples, index order (i fastest), value 100 k + 10 j + i.
constexpr int kNi = 5, kNj = 4, kNk = 3;
inline std::int16_t stored(int i, int j, int k) {
  return static_cast<std::int16_t>(100 * k + 10 * j + i);
}

template <typename T>
void put(std::string& bytes, size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));  // little-endian hosts only (x86, ARM)
}

// ---- NIfTI-1 -------------------------------------------------------------------------------

struct NiftiHeader {
  float pixdim[3] = {0.5f, 0.25f, 2.0f};
  float slope = 0.0f, intercept = 0.0f;
  short qformCode = 0, sformCode = 0;
  float quatern[3] = {0, 0, 0};  // b, c, d
  float qoffset[3] = {0, 0, 0};
  float srow[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  int timePoints = 1;
};

// A single-file NIfTI-1 image (".nii"): the 348-byte header, 4 bytes of (no) extensions, data.
inline std::string niftiBytes(const NiftiHeader& h) {
  std::string bytes(352, '\0');
  put<std::int32_t>(bytes, 0, 348);  // sizeof_hdr
  const std::int16_t dim[8] = {static_cast<std::int16_t>(h.timePoints > 1 ? 4 : 3),
                               kNi,
                               kNj,
                               kNk,
                               static_cast<std::int16_t>(h.timePoints),
                               1,
                               1,
                               1};
  for (int d = 0; d < 8; ++d) put<std::int16_t>(bytes, 40 + 2 * d, dim[d]);
  put<std::int16_t>(bytes, 70, 4);   // datatype: DT_INT16
  put<std::int16_t>(bytes, 72, 16);  // bitpix
  const float pixdim[8] = {1.0f, h.pixdim[0], h.pixdim[1], h.pixdim[2], 1.0f, 1.0f, 1.0f, 1.0f};
  for (int d = 0; d < 8; ++d) put<float>(bytes, 76 + 4 * d, pixdim[d]);
  put<float>(bytes, 108, 352.0f);  // vox_offset
  put<float>(bytes, 112, h.slope);
  put<float>(bytes, 116, h.intercept);
  put<char>(bytes, 123, 10);  // xyzt_units: mm, s
  put<std::int16_t>(bytes, 252, h.qformCode);
  put<std::int16_t>(bytes, 254, h.sformCode);
  for (int a = 0; a < 3; ++a) {
    put<float>(bytes, 256 + 4 * a, h.quatern[a]);
    put<float>(bytes, 268 + 4 * a, h.qoffset[a]);
    for (int c = 0; c < 4; ++c) put<float>(bytes, 280 + 16 * a + 4 * c, h.srow[a][c]);
  }
  std::memcpy(bytes.data() + 344, "n+1\0", 4);
  for (int t = 0; t < h.timePoints; ++t)
    for (int k = 0; k < kNk; ++k)
      for (int j = 0; j < kNj; ++j)
        for (int i = 0; i < kNi; ++i) {
          const std::int16_t v = static_cast<std::int16_t>(stored(i, j, k) + 1000 * t);
          bytes.append(reinterpret_cast<const char*>(&v), 2);
        }
  return bytes;
}

// ---- DICOM (explicit VR little endian, one slice per file) ----------------------------------

inline void element(std::string& out, std::uint16_t group, std::uint16_t tag, const char vr[2],
                    std::string value) {
  if (value.size() % 2) value += (std::string(vr, 2) == "UI") ? '\0' : ' ';
  out.append(reinterpret_cast<const char*>(&group), 2);
  out.append(reinterpret_cast<const char*>(&tag), 2);
  out.append(vr, 2);
  const std::string v(vr, 2);
  if (v == "OB" || v == "OW") {
    out.append(2, '\0');
    const std::uint32_t n = static_cast<std::uint32_t>(value.size());
    out.append(reinterpret_cast<const char*>(&n), 4);
  } else {
    const std::uint16_t n = static_cast<std::uint16_t>(value.size());
    out.append(reinterpret_cast<const char*>(&n), 2);
  }
  out += value;
}

inline std::string us(std::uint16_t v) {
  return std::string(reinterpret_cast<const char*>(&v), 2);
}

// Slice k of a CT series: rows x columns = kNj x kNi, pixel spacing 0.25 (rows) \ 0.5
// (columns), 2 mm apart along z, rescaled as stored - 1024.
inline std::string dicomSlice(int k) {
  std::string meta;
  element(meta, 0x0002, 0x0001, "OB", std::string("\0\1", 2));
  element(meta, 0x0002, 0x0002, "UI", "1.2.840.10008.5.1.4.1.1.2");
  element(meta, 0x0002, 0x0003, "UI", "1.2.826.0.1.3680043.2.1125.1." + std::to_string(k + 1));
  element(meta, 0x0002, 0x0010, "UI", "1.2.840.10008.1.2.1");
  std::string out(128, '\0');
  out += "DICM";
  std::uint32_t metaLength = static_cast<std::uint32_t>(meta.size());
  element(out, 0x0002, 0x0000, "UL", std::string(reinterpret_cast<const char*>(&metaLength), 4));
  out += meta;
  element(out, 0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2");
  element(out, 0x0008, 0x0060, "CS", "CT");
  element(out, 0x0018, 0x0050, "DS", "2");
  element(out, 0x0020, 0x000D, "UI", "1.2.826.0.1.3680043.2.1125.7");
  element(out, 0x0020, 0x000E, "UI", "1.2.826.0.1.3680043.2.1125.8");
  element(out, 0x0020, 0x0013, "IS", std::to_string(k + 1));
  element(out, 0x0020, 0x0032, "DS", "-10\\-20\\" + std::to_string(2 * k - 30));
  element(out, 0x0020, 0x0037, "DS", "1\\0\\0\\0\\1\\0");
  element(out, 0x0028, 0x0002, "US", us(1));
  element(out, 0x0028, 0x0004, "CS", "MONOCHROME2");
  element(out, 0x0028, 0x0010, "US", us(kNj));
  element(out, 0x0028, 0x0011, "US", us(kNi));
  element(out, 0x0028, 0x0030, "DS", "0.25\\0.5");
  element(out, 0x0028, 0x0100, "US", us(16));
  element(out, 0x0028, 0x0101, "US", us(16));
  element(out, 0x0028, 0x0102, "US", us(15));
  element(out, 0x0028, 0x0103, "US", us(1));
  element(out, 0x0028, 0x1052, "DS", "-1024");
  element(out, 0x0028, 0x1053, "DS", "1");
  std::string pixels;
  for (int j = 0; j < kNj; ++j)
    for (int i = 0; i < kNi; ++i) {
      const std::int16_t v = stored(i, j, k);
      pixels.append(reinterpret_cast<const char*>(&v), 2);
    }
  element(out, 0x7FE0, 0x0010, "OW", pixels);
  return out;
}

}  // namespace mfadvr::test
