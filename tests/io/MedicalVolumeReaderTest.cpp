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

#include "MedicalTestFiles.h"
#include "TestSupport.h"
#include "core/util/Error.h"
#include "io/VolumeLoader.h"

namespace mfadvr {
namespace {

using test::expectError;
using namespace test;  // the file writers of MedicalTestFiles.h
namespace fs = std::filesystem;

bool containsNote(const StructuredGrid& g, const std::string& part) {
  return std::any_of(g.notes.begin(), g.notes.end(),
                     [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

std::string writeNifti(const std::string& name, const NiftiHeader& h) {
  const fs::path path = test::scratchDir() / name;
  const std::string bytes = niftiBytes(h);
  if (name.ends_with(".gz") || name.ends_with(".GZ")) {
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
  // Found by fuzzing: a NIfTI-1 magic with a wrong sizeof_hdr and datatype reached VTK's
  // reader, whose datatype lookup ran off its table.
  std::string wrongSize = good;
  wrongSize.replace(0, 4, std::string("\x5c\x01\x00\x2f", 4));
  const std::string sized = (dir / "wrong-size.nii").string();
  std::ofstream(sized, std::ios::binary) << wrongSize;
  expectError([&] { loadStructuredVolume(sized); },
              {"cannot read " + sized, "sizeof_hdr is 788529500", "348"});
  // Found by fuzzing: sizeof_hdr 540 (NIfTI-2) with NIfTI-1's magic, in a file shorter than a
  // NIfTI-2 header, reached VTK's reader, which goes by the magic and dereferenced null.
  std::string mixed = good;
  mixed.replace(0, 4, std::string("\x1c\x02\x00\x00", 4));
  const std::string mixedPath = (dir / "mixed.nii").string();
  std::ofstream(mixedPath, std::ios::binary) << mixed.substr(0, 473);
  expectError([&] { loadStructuredVolume(mixedPath); },
              {"cannot read " + mixedPath, "sizeof_hdr is 540", "NIfTI-2's magic"});
  const std::string other = (dir / "notes.gz").string();
  std::ofstream(other, std::ios::binary) << "x";
  expectError([&] { loadStructuredVolume(other); }, {"unknown volume format '.gz'", ".nii.gz"});
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

TEST(DicomReader, EmptyTypeOneValueIsAnError) {
  // Found by fuzzing: VTK's reader took an empty Photometric Interpretation as a null string.
  const fs::path dir = writeDicomSeries("ct-empty-photometric");
  std::string slice = dicomSlice(0);
  const std::string tag(
      "\x28\x00\x04\x00"
      "CS",
      6);
  const size_t at = slice.find(tag);
  ASSERT_NE(at, std::string::npos);
  const size_t length = static_cast<unsigned char>(slice[at + 6]);
  slice.erase(at + 8, length);
  slice[at + 6] = '\0';
  std::ofstream(dir / "a.dcm", std::ios::binary) << slice;
  expectError([&] { loadStructuredVolume(dir.string()); },
              {(dir / "a.dcm").string(), "element (0028,0004) is empty"});
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
