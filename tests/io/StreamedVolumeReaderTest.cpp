// Header formats whose samples are read a box at a time (io/StreamedVolumeReader.h): the
// streamed grid must be the one VTK's reader gives, placement, names, notes and every sample,
// and the formats it cannot stand for must be left to the in-memory read.
#include <stdlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>

#include "MedicalTestFiles.h"
#include "TestSupport.h"
#include "core/grid/SampleRange.h"
#include "io/NrrdVolumeReader.h"
#include "io/StreamedVolumeReader.h"
#include "io/VtkDataConversion.h"
#include "io/VtkVolumeReader.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;

// 12 x 5 x 4 samples (a fastest axis of more than 9: VTK's NRRD reader takes shorter ones for
// components), each value distinct and exact in float32.
constexpr int kNx = 12, kNy = 5, kNz = 4, kCount = kNx * kNy * kNz;

template <typename T>
std::string samples(std::endian order) {
  std::string out;
  for (int n = 0; n < kCount; ++n) {
    const T v = static_cast<T>(n % 2 ? n : -n / 2);
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    if (order != std::endian::native) std::reverse(bytes, bytes + sizeof(T));
    out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
  }
  return out;
}

std::string write(const fs::path& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

// A temporary folder of the test's own (TMPDIR, where the inflation writes its copies), so that
// the check below sees no copy of a test or program running beside it (ctest -j2 ran the two
// inflating tests together, and one saw the other's copy).
void useOwnTemporaryFolder(const fs::path& dir) {
  const fs::path folder = dir / "tmp";
  fs::create_directories(folder);
  ::setenv("TMPDIR", folder.c_str(), 1);
}

// No inflated copy is left in the temporary folder.
void expectNoInflatedFiles() {
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
    EXPECT_EQ(entry.path().filename().string().rfind("mfadvr-inflated-", 0), std::string::npos)
        << entry.path();
}

// Everything a model records of a grid, and every sample.
void expectSameGrid(const StructuredGrid& a, const StructuredGrid& b) {
  EXPECT_EQ(a.dims, b.dims);
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.spacing, b.spacing);
  EXPECT_EQ(a.fieldName, b.fieldName);
  EXPECT_EQ(a.fieldAssociation, b.fieldAssociation);
  EXPECT_EQ(a.sampleType, b.sampleType);
  EXPECT_EQ(a.inputBytes, b.inputBytes);
  EXPECT_EQ(a.values, b.values);
}

// The streamed grid against `reference`: everything a model records, and every sample; then a
// box read against the same box of the whole grid.
void expectSameAs(const std::string& path, const StructuredGrid& reference, GzipPayloads gzip) {
  SCOPED_TRACE(path);
  const auto source = openStreamedVolume(path, {}, gzip);
  ASSERT_NE(source, nullptr);
  expectSameGrid(source->read(wholeRange(source->layout().dims)), reference);
  EXPECT_EQ(source->layout().notes, reference.notes);
  const Index3& d = reference.dims;
  const SampleRange box{{1, 1, 1}, {d[0] - 2, d[1] - 1, d[2] - 1}};
  EXPECT_EQ(source->read(box).values, subGrid(reference, box).values);
}

void expectSameAsVtk(const std::string& path, VtkVolumeFormat format,
                     GzipPayloads gzip = GzipPayloads::kLeaveToVtk) {
  expectSameAs(path, readVtkVolume(path, format, {}), gzip);
}

// NRRD, which mfadvr reads itself: the streamed grid is the in-memory one, and on these valid
// files both are the grid VTK's own NRRD reader gives.
void expectSameAsVtkNrrd(const std::string& path, GzipPayloads gzip = GzipPayloads::kLeaveToVtk) {
  SCOPED_TRACE(path);
  const StructuredGrid ours = readNrrdVolume(path);
  expectSameAs(path, ours, gzip);
  vtkNew<vtkNrrdReader> vtk;
  vtk->SetFileName(path.c_str());
  vtk->Update();
  expectSameGrid(ours, gridFromVtkImage(vtk->GetOutput(), "", path));
}

TEST(StreamedVolumeReader, NrrdRawAttachedAndDetached) {
  const fs::path dir = test::scratchDir();
  const std::string head =
      "NRRD0004\ntype: float\ndimension: 3\nsizes: 12 5 4\nspace: 3D-right-handed\n"
      "space directions: (0.5,0,0) (0,0.25,0) (0,0,2)\nspace origin: (1.5,-2,3)\n"
      "encoding: raw\n";
  expectSameAsVtkNrrd(
      write(dir / "a.nrrd", head + "endian: little\n\n" + samples<float>(std::endian::little)));
  // Big-endian 16-bit samples in a data file of their own.
  write(dir / "b.raw", samples<std::int16_t>(std::endian::big));
  expectSameAsVtkNrrd(write(dir / "b.nhdr",
                            "NRRD0004\ntype: short\ndimension: 3\nsizes: 12 5 4\nspacings: 1 2 3\n"
                            "encoding: raw\nendian: big\ndata file: b.raw\n"));
}

TEST(StreamedVolumeReader, MetaImageLocalAndDetached) {
  const fs::path dir = test::scratchDir();
  const std::string head =
      "ObjectType = Image\nNDims = 3\nBinaryData = True\nDimSize = 12 5 4\n"
      "ElementSpacing = 0.5 0.25 2\nOffset = 1.5 -2 3\n";
  expectSameAsVtk(
      write(dir / "a.mha", head + "ElementType = MET_USHORT\nElementDataFile = LOCAL\n" +
                               samples<std::uint16_t>(std::endian::little)),
      VtkVolumeFormat::kMetaImage);
  write(dir / "b.data", samples<double>(std::endian::big));
  expectSameAsVtk(
      write(dir / "b.mhd", head + "BinaryDataByteOrderMSB = True\n"
                                  "ElementType = MET_DOUBLE\nElementDataFile = b.data\n"),
      VtkVolumeFormat::kMetaImage);
}

TEST(StreamedVolumeReader, LegacyBinaryStructuredPoints) {
  const std::string text =
      "# vtk DataFile Version 3.0\nstreamed\nBINARY\nDATASET STRUCTURED_POINTS\n"
      "DIMENSIONS 12 5 4\nORIGIN 1.5 -2 3\nSPACING 0.5 0.25 2\nPOINT_DATA 240\n"
      "SCALARS density int 1\nLOOKUP_TABLE default\n" +
      samples<std::int32_t>(std::endian::big) + "\nSCALARS label short 1\nLOOKUP_TABLE default\n" +
      samples<std::int16_t>(std::endian::big) + "\n";
  expectSameAsVtk(write(test::scratchDir() / "v.vtk", text),
                  VtkVolumeFormat::kLegacyStructuredPoints);
}

TEST(StreamedVolumeReader, NiftiCalibratedAndPlacedInItsStoredOrder) {
  test::NiftiHeader h;
  h.slope = 2.0f;
  h.intercept = -1024.0f;
  h.sformCode = 1;
  h.srow[0][0] = 0.5f;
  h.srow[0][3] = 10.0f;
  h.srow[1][1] = 0.25f;
  h.srow[2][2] = 2.0f;
  h.srow[2][3] = -30.0f;
  const fs::path dir = test::scratchDir();
  expectSameAsVtk(write(dir / "v.nii", test::niftiBytes(h)), VtkVolumeFormat::kNifti);
  h.timePoints = 2;  // the first volume is read
  expectSameAsVtk(write(dir / "t.nii", test::niftiBytes(h)), VtkVolumeFormat::kNifti);
}

// Gzip data is inflated once to a temporary file, which is gone when the source is opened.
TEST(StreamedVolumeReader, GzipPayloadsAreInflatedToATemporaryFile) {
  const fs::path dir = test::scratchDir();
  useOwnTemporaryFolder(dir);
  const auto inflate = GzipPayloads::kInflateToTemporaryFile;
  expectSameAsVtkNrrd(write(dir / "a.nrrd",
                            "NRRD0004\ntype: ushort\ndimension: 3\nsizes: 12 5 4\n"
                            "encoding: gzip\nendian: little\n\n" +
                                test::gzipBytes(samples<std::uint16_t>(std::endian::little))),
                      inflate);
  // Big-endian gzip data: VTK 9.1's reader leaves its bytes unswapped; the streamed read
  // gives the samples of the same data stored raw.
  const std::string big = "NRRD0004\ntype: short\ndimension: 3\nsizes: 12 5 4\nendian: big\n";
  const auto gz = openStreamedVolume(
      write(dir / "c.nrrd",
            big + "encoding: gzip\n\n" + test::gzipBytes(samples<std::int16_t>(std::endian::big))),
      {}, inflate);
  const auto raw = openStreamedVolume(write(
      dir / "c-raw.nrrd", big + "encoding: raw\n\n" + samples<std::int16_t>(std::endian::big)));
  ASSERT_TRUE(gz && raw);
  EXPECT_EQ(gz->read(wholeRange(gz->layout().dims)).values,
            raw->read(wholeRange(raw->layout().dims)).values);
  write(dir / "b.raw.gz", test::gzipBytes(samples<float>(std::endian::little)));
  expectSameAsVtkNrrd(write(dir / "b.nhdr",
                            "NRRD0005\ntype: float\ndimension: 3\nsizes: 12 5 4\n"
                            "encoding: gzip\ndata file: b.raw.gz\n"),
                      inflate);
  test::NiftiHeader h;
  h.slope = 0.5f;
  h.timePoints = 2;
  expectSameAsVtk(write(dir / "v.nii.gz", test::gzipBytes(test::niftiBytes(h))),
                  VtkVolumeFormat::kNifti, inflate);
  // A damaged byte inside the deflate data: the size in the gzip trailer still matches, the
  // inflation finds it.
  std::string damaged = test::gzipBytes(samples<float>(std::endian::little));
  damaged[damaged.size() / 2] = static_cast<char>(damaged[damaged.size() / 2] ^ 0x55);
  test::expectError(
      [&] {
        openStreamedVolume(write(dir / "d.nrrd",
                                 "NRRD0004\ntype: float\ndimension: 3\nsizes: 12 5 4\n"
                                 "encoding: gzip\n\n" +
                                     damaged),
                           {}, inflate);
      },
      {"d.nrrd", "gzip data is cut off or corrupt"});
  expectNoInflatedFiles();
}

// Inflation tells its progress, a few times for a file of several buffers and once at its end,
// and a listener that throws stops it, leaving no temporary file behind.
TEST(StreamedVolumeReader, InflationTellsItsProgressAndCanBeStopped) {
  const fs::path dir = test::scratchDir();
  useOwnTemporaryFolder(dir);
  std::string data(size_t{256} * 128 * 40 * 2, '\0');  // 2.6 MB of ushort: 3 inflated buffers
  for (size_t n = 0; n < data.size(); ++n) data[n] = static_cast<char>(n * 7 % 251);
  const std::string path = write(dir / "large.nrrd",
                                 "NRRD0004\ntype: ushort\ndimension: 3\nsizes: 256 128 40\n"
                                 "encoding: gzip\nendian: little\n\n" +
                                     test::gzipBytes(data));
  const auto total = static_cast<std::int64_t>(data.size());
  std::vector<std::int64_t> done;
  const auto source = openStreamedVolume(path, {}, GzipPayloads::kInflateToTemporaryFile,
                                         [&](std::int64_t d, std::int64_t t) {
                                           EXPECT_EQ(t, total);
                                           done.push_back(d);
                                         });
  ASSERT_NE(source, nullptr);
  ASSERT_GE(done.size(), 2u);
  EXPECT_LE(done.size(), 257u);
  EXPECT_TRUE(std::is_sorted(done.begin(), done.end()));
  EXPECT_EQ(std::adjacent_find(done.begin(), done.end()), done.end());
  EXPECT_EQ(done.back(), total);
  // The same grid, described before inflating: what a reader gives before it reads samples.
  const std::optional<GzipVolume> described = describeGzipVolume(path);
  ASSERT_TRUE(described.has_value());
  EXPECT_EQ(described->layout.dims, source->layout().dims);
  EXPECT_EQ(described->layout.fieldName, source->layout().fieldName);
  EXPECT_EQ(described->layout.sampleType, source->layout().sampleType);
  EXPECT_EQ(described->layout.inputBytes, source->layout().inputBytes);
  EXPECT_EQ(described->open()->read(wholeRange(source->layout().dims)).values,
            source->read(wholeRange(source->layout().dims)).values);
  // Planes 10 .. 24 alone: the stream inflated up to plane 24 (progress counts the planes before
  // 10 too), their samples those of the whole grid, their origin at plane 10.
  done.clear();
  const std::int64_t planeBytes = 256 * 128 * 2;
  const auto planes = described->openPlanes(10, 24, [&](std::int64_t d, std::int64_t t) {
    EXPECT_EQ(t, 25 * planeBytes);
    done.push_back(d);
  });
  ASSERT_FALSE(done.empty());
  EXPECT_EQ(done.back(), 25 * planeBytes);
  EXPECT_EQ(planes->layout().dims, (Index3{256, 128, 15}));
  EXPECT_EQ(planes->layout().origin, source->layout().position(0, 0, 10));
  EXPECT_EQ(planes->layout().sampleType, "uint16");
  EXPECT_EQ(planes->read(wholeRange(planes->layout().dims)).values,
            source->read({{0, 0, 10}, {255, 127, 24}}).values);
  test::expectError([&] { described->openPlanes(30, 40); }, {"outside the grid along z"});
  EXPECT_FALSE(describeGzipVolume(write(dir / "raw.nrrd",
                                        "NRRD0004\ntype: ushort\ndimension: 3\nsizes: 12 5 4\n"
                                        "encoding: raw\nendian: little\n\n" +
                                            samples<std::uint16_t>(std::endian::little)))
                   .has_value());
  // The samples are the data's all the same.
  const StructuredGrid grid = source->read(wholeRange(source->layout().dims));
  EXPECT_EQ(grid.values[1], static_cast<float>(14 + 256 * 21));  // bytes 2 and 3

  int calls = 0;
  test::expectError(
      [&] {
        openStreamedVolume(path, {}, GzipPayloads::kInflateToTemporaryFile,
                           [&](std::int64_t, std::int64_t) {
                             ++calls;
                             throw Error("stopped by the user");
                           });
      },
      {"stopped by the user"});
  EXPECT_EQ(calls, 1);
  expectNoInflatedFiles();
}

TEST(StreamedVolumeReader, OtherStoragesAreLeftToTheInMemoryRead) {
  const fs::path dir = test::scratchDir();
  const std::string nrrd = "NRRD0004\ntype: short\ndimension: 3\nsizes: 12 5 4\nencoding: ";
  EXPECT_EQ(openStreamedVolume(write(
                dir / "g.nrrd",
                nrrd + "gzip\n\n" + test::gzipBytes(samples<std::int16_t>(std::endian::little)))),
            nullptr);
  std::string text;
  for (int n = 0; n < kCount; ++n) text += std::to_string(n) + "\n";
  EXPECT_EQ(openStreamedVolume(write(dir / "t.nrrd", nrrd + "ascii\n\n" + text)), nullptr);
  // Two channels per sample.
  EXPECT_EQ(openStreamedVolume(write(
                dir / "c.mha",
                "ObjectType = Image\nNDims = 3\nDimSize = 6 5 4\nElementNumberOfChannels = 2\n"
                "ElementType = MET_SHORT\nElementDataFile = LOCAL\n" +
                    samples<std::int16_t>(std::endian::little))),
            nullptr);
  // A sform that flips x: the samples are reordered into world axes.
  test::NiftiHeader flipped;
  flipped.sformCode = 1;
  flipped.srow[0][0] = -0.5f;
  flipped.srow[1][1] = 0.25f;
  flipped.srow[2][2] = 2.0f;
  EXPECT_EQ(openStreamedVolume(write(dir / "f.nii", test::niftiBytes(flipped))), nullptr);
  // A raw NRRD, but a field chosen by name: the in-memory read says what there is.
  VolumeLoadOptions named;
  named.field.name = "density";
  EXPECT_EQ(openStreamedVolume(write(dir / "a.nrrd",
                                     nrrd + "raw\n\n" + samples<std::int16_t>(std::endian::little)),
                               named),
            nullptr);
}

TEST(StreamedVolumeReader, OptionsReplaceThePlacementAndHeaderErrorsStayErrors) {
  const fs::path dir = test::scratchDir();
  const std::string nrrd =
      "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 12 5 4\nspacings: 1 2 3\nencoding: raw\n\n";
  VolumeLoadOptions options;
  options.spacing = Vec3d(4, 5, 6);
  const auto source =
      openStreamedVolume(write(dir / "a.nrrd", nrrd + std::string(kCount, '\1')), options);
  ASSERT_NE(source, nullptr);
  EXPECT_EQ(source->layout().spacing, Vec3d(4, 5, 6));
  test::expectError(
      [&] { openStreamedVolume(write(dir / "cut.nrrd", nrrd + std::string(kCount - 1, '\1'))); },
      {"cut.nrrd", "truncated"});
}

}  // namespace
}  // namespace mfadvr
