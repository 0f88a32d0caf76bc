// NIfTI (.nii, .nii.gz) and DICOM series (a directory of slices), read through VTK's readers:
// small files written here byte by byte from the formats' definitions, so that the tests pin
// the formats (header fields, calibration, orientation) rather than VTK's writers.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

#include "TestSupport.h"
#include "core/util/Error.h"
#include "io/VolumeLoader.h"

namespace mfadvr {
namespace {

using test::expectError;
namespace fs = std::filesystem;

// The stored volume: 5 x 4 x 3 int16 samples, index order (i fastest), value 100 k + 10 j + i.
constexpr int kNi = 5, kNj = 4, kNk = 3;
std::int16_t stored(int i, int j, int k) {
  return static_cast<std::int16_t>(100 * k + 10 * j + i);
}

template <typename T>
void put(std::string& bytes, size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));  // little-endian hosts only (x86, ARM)
}

bool containsNote(const StructuredGrid& g, const std::string& part) {
  return std::any_of(g.notes.begin(), g.notes.end(),
                     [&](const std::string& n) { return n.find(part) != std::string::npos; });
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
std::string niftiBytes(const NiftiHeader& h) {
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

std::string writeNifti(const std::string& name, const NiftiHeader& h) {
  const fs::path path = test::scratchDir() / name;
  const std::string bytes = niftiBytes(h);
  if (name.ends_with(".gz")) {
    gzFile out = gzopen(path.c_str(), "wb");
    gzwrite(out, bytes.data(), static_cast<unsigned>(bytes.size()));
    gzclose(out);
  } else {
    std::ofstream(path, std::ios::binary) << bytes;
  }
  return path.string();
}

TEST(NiftiReader, ReadsVoxelsWithPixdimSpacingAndCalibration) {
  NiftiHeader h;
  h.slope = 2.0f;
  h.intercept = -1024.0f;
  for (const char* name : {"plain.nii", "plain.nii.gz", "PLAIN.NII.GZ"}) {
    const StructuredGrid g = loadStructuredVolume(writeNifti(name, h));
    ASSERT_EQ(g.dims, (Index3{kNi, kNj, kNk})) << name;
    EXPECT_EQ(g.spacing, Vec3d(0.5, 0.25, 2.0));
    EXPECT_EQ(g.origin, Vec3d::Zero());
    EXPECT_EQ(g.sampleType, "int16");
    EXPECT_EQ(g.at(3, 2, 1), 2.0 * stored(3, 2, 1) - 1024.0);
    EXPECT_EQ(g.at(0, 0, 0), -1024.0);
    EXPECT_TRUE(containsNote(g, "scl_slope"));
    EXPECT_TRUE(containsNote(g, "no qform or sform"));
  }
}

TEST(NiftiReader, SlopeZeroMeansUncalibrated) {
  const StructuredGrid g = loadStructuredVolume(writeNifti("uncalibrated.nii", NiftiHeader{}));
  EXPECT_EQ(g.at(4, 3, 2), stored(4, 3, 2));
  EXPECT_FALSE(containsNote(g, "scl_slope"));
}

// The usual radiological storage: x runs right-to-left and y front-to-back in the file, so the
// sform flips them. The grid comes out in world (RAS) axes, samples reordered.
TEST(NiftiReader, SformWithFlippedAxesPlacesTheGridInWorldAxes) {
  NiftiHeader h;
  h.sformCode = 1;
  h.srow[0][0] = -0.5f;
  h.srow[0][3] = 10.0f;
  h.srow[1][1] = -0.25f;
  h.srow[1][3] = 20.0f;
  h.srow[2][2] = 2.0f;
  h.srow[2][3] = -30.0f;
  const StructuredGrid g = loadStructuredVolume(writeNifti("flipped.nii", h));
  ASSERT_EQ(g.dims, (Index3{kNi, kNj, kNk}));
  EXPECT_EQ(g.spacing, Vec3d(0.5, 0.25, 2.0));
  // File voxel (i, j, k) sits at (10 - 0.5 i, 20 - 0.25 j, -30 + 2 k).
  EXPECT_DOUBLE_EQ(g.origin[0], 10.0 - 0.5 * (kNi - 1));
  EXPECT_DOUBLE_EQ(g.origin[1], 20.0 - 0.25 * (kNj - 1));
  EXPECT_DOUBLE_EQ(g.origin[2], -30.0);
  for (int k = 0; k < kNk; ++k)
    for (int j = 0; j < kNj; ++j)
      for (int i = 0; i < kNi; ++i) {
        const Vec3d world(10.0 - 0.5 * i, 20.0 - 0.25 * j, -30.0 + 2.0 * k);
        const Vec3d index = (world - g.origin).cwiseQuotient(g.spacing);
        EXPECT_EQ(g.at(std::lround(index[0]), std::lround(index[1]), std::lround(index[2])),
                  stored(i, j, k));
      }
  EXPECT_TRUE(containsNote(g, "sform"));
  EXPECT_TRUE(containsNote(g, "-x,-y,+z"));
}

// A qform only (quaternion b = c = 0, d = 1: a half turn about z) and a sagittal-like sform
// that swaps axes: both axis-aligned, both applied.
TEST(NiftiReader, QformAndPermutedSformAreApplied) {
  NiftiHeader q;
  q.qformCode = 1;
  q.quatern[2] = 1.0f;
  q.qoffset[0] = 5.0f;
  const StructuredGrid gq = loadStructuredVolume(writeNifti("qform.nii", q));
  EXPECT_TRUE(containsNote(gq, "qform"));
  EXPECT_TRUE(containsNote(gq, "-x,-y,+z"));
  EXPECT_DOUBLE_EQ(gq.origin[0], 5.0 - 0.5 * (kNi - 1));
  EXPECT_EQ(gq.at(kNi - 1, kNj - 1, 0), stored(0, 0, 0));

  NiftiHeader s;
  s.sformCode = 2;
  s.srow[0][2] = 2.0f;   // file k -> world x
  s.srow[1][0] = 0.5f;   // file i -> world y
  s.srow[2][1] = 0.25f;  // file j -> world z
  const StructuredGrid gs = loadStructuredVolume(writeNifti("swapped.nii", s));
  ASSERT_EQ(gs.dims, (Index3{kNk, kNi, kNj}));
  EXPECT_EQ(gs.spacing, Vec3d(2.0, 0.5, 0.25));
  EXPECT_EQ(gs.at(2, 4, 1), stored(4, 1, 2));
  EXPECT_TRUE(containsNote(gs, "+z,+x,+y") || containsNote(gs, "+y,+z,+x"));
}

TEST(NiftiReader, ObliqueSformKeepsVoxelAxesAndSaysSo) {
  NiftiHeader h;
  h.sformCode = 1;
  const float c = 0.8f, s = 0.6f;  // 36.87 degrees about z
  h.srow[0][0] = 0.5f * c;
  h.srow[0][1] = -0.25f * s;
  h.srow[1][0] = 0.5f * s;
  h.srow[1][1] = 0.25f * c;
  h.srow[2][2] = 2.0f;
  h.srow[0][3] = 7.0f;
  const StructuredGrid g = loadStructuredVolume(writeNifti("oblique.nii", h));
  EXPECT_EQ(g.dims, (Index3{kNi, kNj, kNk}));
  EXPECT_EQ(g.at(1, 2, 0), stored(1, 2, 0));
  EXPECT_DOUBLE_EQ(g.origin[0], 7.0);
  EXPECT_TRUE(containsNote(g, "oblique"));
}

TEST(NiftiReader, ReadsTheFirstTimePoint) {
  NiftiHeader h;
  h.timePoints = 2;
  const StructuredGrid g = loadStructuredVolume(writeNifti("series.nii", h));
  EXPECT_EQ(g.at(2, 2, 2), stored(2, 2, 2));
  EXPECT_TRUE(containsNote(g, "2 time points"));
}

TEST(NiftiReader, RejectsBrokenFilesWithTheReason) {
  const std::string good = niftiBytes(NiftiHeader{});
  const fs::path dir = test::scratchDir();
  const std::string truncated = (dir / "truncated.nii").string();
  std::ofstream(truncated, std::ios::binary) << good.substr(0, 200);
  expectError([&] { loadStructuredVolume(truncated); }, {"cannot read " + truncated, "NIfTI"});
  const std::string garbage = (dir / "garbage.nii").string();
  std::ofstream(garbage, std::ios::binary) << std::string(600, 'x');
  expectError([&] { loadStructuredVolume(garbage); }, {"cannot read " + garbage, "NIfTI"});
  const std::string other = (dir / "notes.gz").string();
  std::ofstream(other, std::ios::binary) << "x";
  expectError([&] { loadStructuredVolume(other); }, {"unknown volume format '.gz'", ".nii.gz"});
}

// ---- DICOM (explicit VR little endian, one slice per file) ----------------------------------

void element(std::string& out, std::uint16_t group, std::uint16_t tag, const char vr[2],
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

std::string us(std::uint16_t v) {
  return std::string(reinterpret_cast<const char*>(&v), 2);
}

// Slice k of a CT series: rows x columns = kNj x kNi, pixel spacing 0.25 (rows) \ 0.5
// (columns), 2 mm apart along z, rescaled as stored - 1024.
std::string dicomSlice(int k) {
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

fs::path writeDicomSeries(const std::string& name) {
  const fs::path dir = test::scratchDir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  // Named out of order (b, c, a): the reader sorts by position, not by name.
  for (int k = 0; k < kNk; ++k)
    std::ofstream(dir / (std::string(1, "bca"[k]) + ".dcm"), std::ios::binary) << dicomSlice(k);
  return dir;
}

TEST(DicomReader, ReadsASeriesDirectoryInSlicePositionOrder) {
  const fs::path dir = writeDicomSeries("ct-series");
  const StructuredGrid g = loadStructuredVolume(dir.string());
  ASSERT_EQ(g.dims, (Index3{kNi, kNj, kNk}));
  // Pixel Spacing is (row spacing, column spacing): x, along a row, is the second value.
  EXPECT_EQ(g.spacing, Vec3d(0.5, 0.25, 2.0));
  EXPECT_EQ(g.origin, Vec3d::Zero());
  // VTK's reader keeps a right-handed frame: rows from the image's last one up (y), slices
  // from the largest position along the normal down (z); the rescale is applied.
  for (int k = 0; k < kNk; ++k)
    for (int j = 0; j < kNj; ++j)
      for (int i = 0; i < kNi; ++i)
        EXPECT_EQ(g.at(i, kNj - 1 - j, kNk - 1 - k), stored(i, j, k) - 1024.0)
            << i << ' ' << j << ' ' << k;
  EXPECT_TRUE(containsNote(g, "DICOM series of 3 slices"));
}

TEST(DicomReader, RejectsEmptyDirectoriesAndSingleFiles) {
  const fs::path empty = test::scratchDir() / "no-dicom";
  fs::remove_all(empty);
  fs::create_directories(empty);
  std::ofstream(empty / "readme.txt") << "not an image";
  expectError([&] { loadStructuredVolume(empty.string()); },
              {"cannot read " + empty.string(), "none of its 1 files is a DICOM file"});
  const fs::path dir = writeDicomSeries("ct-single");
  const std::string one = (dir / "a.dcm").string();
  expectError([&] { loadStructuredVolume(one); }, {one, "directory"});
}

}  // namespace
}  // namespace mfadvr
