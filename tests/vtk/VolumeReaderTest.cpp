// vtkMFAVolumeReader: the grid and samples VTK's own reader gives, but read by the requested
// extent, so that every piece of a parallel pipeline gets its own samples (VTK 9.1's NRRD reader
// returns zeros for a piece); files it cannot read box by box are read whole and cut; bad files
// are errors with an empty output.
#include <gtest/gtest.h>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExtentTranslator.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkType.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "GzipBytes.h"
#include "TestSupport.h"
#include "VtkErrorLog.h"
#include "core/encode/PieceEncoder.h"
#include "core/grid/SampleRange.h"
#include "io/VolumeLoader.h"
#include "vtkMFAEncoder.h"
#include "vtkMFAModelData.h"
#include "vtkMFAVolumeReader.h"

namespace mfadvr::test {
namespace {

namespace fs = std::filesystem;

constexpr int kNx = 20, kNy = 16, kNz = 12;

// int16 samples, each distinct, in an attached-data NRRD file with a placement: big-endian and
// raw, or with `gzip` little-endian and gzip-compressed (the encoding for which VTK 9.1's reader
// returns zeros for a piece).
std::string writeNrrd(const fs::path& dir, bool gzip = false) {
  const std::endian order = gzip ? std::endian::little : std::endian::big;
  std::string data;
  for (int n = 0; n < kNx * kNy * kNz; ++n) {
    const auto v = static_cast<std::int16_t>(n % 2 ? 3 * n : -n);
    unsigned char bytes[2];
    std::memcpy(bytes, &v, 2);
    if (std::endian::native != order) std::swap(bytes[0], bytes[1]);
    data.append(reinterpret_cast<const char*>(bytes), 2);
  }
  const fs::path path = dir / (gzip ? "gzip.nrrd" : "volume.nrrd");
  std::ofstream(path, std::ios::binary)
      << "NRRD0004\ntype: short\ndimension: 3\nsizes: 20 16 12\nspace: 3D-right-handed\n"
         "space directions: (0.5,0,0) (0,0.25,0) (0,0,2)\nspace origin: (1.5,-2,3)\n"
      << (gzip ? "encoding: gzip\nendian: little\n\n" + gzipBytes(data)
               : "encoding: raw\nendian: big\n\n" + data);
  return path.string();
}

// The samples of `image` within `extent`, in order (x fastest), as doubles.
std::vector<double> samplesIn(vtkImageData* image, const int extent[6]) {
  std::vector<double> out;
  vtkDataArray* a = image->GetPointData()->GetScalars();
  for (int k = extent[4]; k <= extent[5]; ++k)
    for (int j = extent[2]; j <= extent[3]; ++j)
      for (int i = extent[0]; i <= extent[1]; ++i) {
        int at[3] = {i, j, k};
        out.push_back(a->GetComponent(image->ComputePointId(at), 0));
      }
  return out;
}

TEST(MFAVolumeReader, GivesTheGridAndSamplesOfVtksReader) {
  const std::string path = writeNrrd(scratchDir());
  vtkNew<vtkMFAVolumeReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkNew<vtkNrrdReader> vtk;
  vtk->SetFileName(path.c_str());
  vtk->Update();
  vtkImageData *ours = reader->GetOutput(), *theirs = vtk->GetOutput();
  int e1[6], e2[6];
  ours->GetExtent(e1);
  theirs->GetExtent(e2);
  EXPECT_TRUE(std::equal(e1, e1 + 6, e2));
  for (int a = 0; a < 3; ++a) {
    // VTK's origin is the position of index 0, which is the first sample here.
    EXPECT_EQ(ours->GetOrigin()[a], theirs->GetOrigin()[a]);
    EXPECT_EQ(ours->GetSpacing()[a], theirs->GetSpacing()[a]);
  }
  ASSERT_NE(ours->GetPointData()->GetScalars(), nullptr);
  EXPECT_EQ(ours->GetScalarType(), VTK_SHORT);
  EXPECT_EQ(ours->GetScalarType(), theirs->GetScalarType());
  EXPECT_STREQ(ours->GetPointData()->GetScalars()->GetName(),
               theirs->GetPointData()->GetScalars()->GetName());
  EXPECT_EQ(samplesIn(ours, e1), samplesIn(theirs, e2));
}

// Each of 3 pieces, and a box asked for as an extent, hold their own samples of `path`.
void expectPiecesAndExtent(const std::string& path) {
  const StructuredGrid whole = loadStructuredVolume(path);
  auto reader = vtkSmartPointer<vtkMFAVolumeReader>::New();
  reader->SetFileName(path.c_str());
  int all[6] = {0, kNx - 1, 0, kNy - 1, 0, kNz - 1}, own[6], got[6];
  vtkNew<vtkExtentTranslator> translator;
  const auto expectSamples = [&](const int ext[6]) {
    const SampleRange box{{ext[0], ext[2], ext[4]}, {ext[1], ext[3], ext[5]}};
    const StructuredGrid part = subGrid(whole, box);
    const std::vector<double> expected(part.values.begin(), part.values.end());
    EXPECT_EQ(samplesIn(reader->GetOutput(), ext), expected);
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), box.sampleCount());
  };
  for (int piece = 0; piece < 3; ++piece) {
    SCOPED_TRACE("piece " + std::to_string(piece));
    translator->PieceToExtentThreadSafe(piece, 3, 0, all, own, vtkExtentTranslator::BLOCK_MODE, 0);
    reader->UpdatePiece(piece, 3, 0);
    reader->GetOutput()->GetExtent(got);
    EXPECT_TRUE(std::equal(got, got + 6, own)) << "a piece was read as another extent";
    expectSamples(own);
  }
  // An extent asked for directly (as MFA Encode asks for its piece grown by ghost layers), of a
  // reader that holds no larger extent already.
  int box[6] = {3, 17, 1, 2, 5, 11};
  reader = vtkSmartPointer<vtkMFAVolumeReader>::New();
  reader->SetFileName(path.c_str());
  reader->UpdateExtent(box);
  reader->GetOutput()->GetExtent(got);
  EXPECT_TRUE(std::equal(got, got + 6, box));
  expectSamples(box);
}

TEST(MFAVolumeReader, ReadsEachPieceAndExtentAskedFor) {
  for (const bool gzip : {false, true}) {
    SCOPED_TRACE(gzip ? "gzip" : "raw");
    expectPiecesAndExtent(writeNrrd(scratchDir(), gzip));
  }
}

// The fault this reader exists for: MFA Encode split among ranks fits, on every rank, that
// rank's samples with their ghost layers as read from a gzip NRRD file.
TEST(MFAVolumeReader, EncodesEveryPieceOfAFile) {
  const std::string path = writeNrrd(scratchDir(), true);
  const StructuredGrid whole = loadStructuredVolume(path);
  vtkNew<vtkMFAVolumeReader> reader;
  reader->SetFileName(path.c_str());
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputConnection(reader->GetOutputPort());
  encoder->SetNumberOfControlPoints(12, 10, 8);
  encoder->SetGhostLevels(2);
  EncodeOptions options;
  options.controlCounts = {12, 10, 8};
  int all[6] = {0, kNx - 1, 0, kNy - 1, 0, kNz - 1}, own[6];
  vtkNew<vtkExtentTranslator> translator;
  for (int piece = 0; piece < 2; ++piece) {
    SCOPED_TRACE("piece " + std::to_string(piece));
    translator->PieceToExtentThreadSafe(piece, 2, 0, all, own, vtkExtentTranslator::BLOCK_MODE, 0);
    const SampleRange range =
        withGhostLayers({{own[0], own[2], own[4]}, {own[1], own[3], own[5]}}, 2, whole.dims);
    const StructuredGrid samples = subGrid(whole, range);
    const auto [lo, hi] = std::minmax_element(samples.values.begin(), samples.values.end());
    const Model expected = encodeStructuredPiece(samples, whole.dims, options, *lo, *hi);
    encoder->UpdatePiece(piece, 2, 0);
    ASSERT_TRUE(encoder->GetOutput()->HasModel());
    const Model& fitted = *encoder->GetOutput()->GetModel();
    EXPECT_EQ(fitted.provenance().sampleDims, range.dims());
    const auto a = fitted.spline().controlPoints(), b = expected.spline().controlPoints();
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
  }
}

// A raw file is placed by its name alone; its samples get the array name VTK's raw reader uses.
TEST(MFAVolumeReader, ReadsARawFileByItsName) {
  const fs::path path = scratchDir() / "ramp_6x5x4_uint16.raw";
  {
    std::ofstream out(path, std::ios::binary);
    for (std::uint16_t n = 0; n < 120; ++n) out.write(reinterpret_cast<const char*>(&n), 2);
  }
  vtkNew<vtkMFAVolumeReader> reader;
  reader->SetFileName(path.c_str());
  int box[6] = {1, 4, 2, 4, 1, 2};
  reader->UpdateExtent(box);
  vtkImageData* out = reader->GetOutput();
  EXPECT_EQ(out->GetScalarType(), VTK_UNSIGNED_SHORT);
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "ImageFile");
  std::vector<double> expected;
  for (int k = 1; k <= 2; ++k)
    for (int j = 2; j <= 4; ++j)
      for (int i = 1; i <= 4; ++i) expected.push_back(i + 6 * (j + 5 * k));
  EXPECT_EQ(samplesIn(out, box), expected);
}

// A text-encoded NRRD cannot be read box by box: it is read whole (as float32) and cut.
TEST(MFAVolumeReader, CutsTheExtentOutOfFilesReadWhole) {
  const fs::path path = scratchDir() / "text.nrrd";
  {
    std::ofstream out(path);
    out << "NRRD0004\ntype: float\ndimension: 3\nsizes: 12 3 2\nencoding: ascii\n\n";
    for (int n = 0; n < 72; ++n) out << n * 0.5 << '\n';
  }
  vtkNew<vtkMFAVolumeReader> reader;
  reader->SetFileName(path.c_str());
  int box[6] = {2, 9, 1, 2, 1, 1};
  reader->UpdateExtent(box);
  vtkImageData* out = reader->GetOutput();
  EXPECT_EQ(out->GetScalarType(), VTK_FLOAT);
  std::vector<double> expected;
  for (int j = 1; j <= 2; ++j)
    for (int i = 2; i <= 9; ++i) expected.push_back((i + 12 * (j + 3)) * 0.5);
  EXPECT_EQ(samplesIn(out, box), expected);
}

TEST(MFAVolumeReader, ReportsBadFilesWithAnEmptyOutput) {
  const fs::path dir = scratchDir();
  const fs::path shortFile = dir / "short.nrrd";
  std::ofstream(shortFile, std::ios::binary)
      << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 20 20 20\nencoding: raw\n\n"
      << std::string(100, 'x');
  for (const std::string& path : {shortFile.string(), (dir / "missing.nrrd").string()}) {
    SCOPED_TRACE(path);
    vtkNew<vtkMFAVolumeReader> reader;
    ErrorLog log(reader);
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_NE(log.text.find(path), std::string::npos) << log.text;
    EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 0);
  }
  vtkNew<vtkMFAVolumeReader> unnamed;
  ErrorLog log(unnamed);
  unnamed->Update();
  EXPECT_NE(log.text.find("no FileName"), std::string::npos) << log.text;
}

// A gzip file's grid is known without inflating it; inflating it, at the first RequestData, is
// reported as progress with its own text, and an observer that sets AbortExecute stops it: an
// error and an empty output, and the next update reads the file.
TEST(MFAVolumeReader, InflatesAtTheFirstRequestDataWithProgressThatCanBeAborted) {
  const std::string path = writeNrrd(scratchDir(), true);
  struct Heard {
    std::vector<std::pair<double, std::string>> events;  // progress, text
    bool abort = false;
  } heard;
  vtkNew<vtkCallbackCommand> listener;
  listener->SetClientData(&heard);
  listener->SetCallback([](vtkObject* caller, unsigned long, void* data, void*) {
    auto* h = static_cast<Heard*>(data);
    auto* reader = static_cast<vtkMFAVolumeReader*>(caller);
    const char* text = reader->GetProgressText();
    h->events.emplace_back(reader->GetProgress(), text ? text : "");
    if (h->abort && !h->events.back().second.empty()) reader->SetAbortExecute(1);
  });
  vtkNew<vtkMFAVolumeReader> reader;
  reader->AddObserver(vtkCommand::ProgressEvent, listener);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  int extent[6];
  reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  EXPECT_EQ(extent[5], kNz - 1);
  EXPECT_TRUE(heard.events.empty());  // nothing inflated for the grid
  reader->Update();
  const std::pair<double, std::string> inflated{1.0, "inflating " + path};
  EXPECT_NE(std::find(heard.events.begin(), heard.events.end(), inflated), heard.events.end());
  EXPECT_EQ(reader->GetProgressText(), nullptr);
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), kNx * kNy * kNz);

  vtkNew<vtkMFAVolumeReader> aborted;
  aborted->AddObserver(vtkCommand::ProgressEvent, listener);
  ErrorLog log(aborted);
  heard.abort = true;
  aborted->SetFileName(path.c_str());
  aborted->Update();
  EXPECT_NE(log.text.find("was aborted"), std::string::npos) << log.text;
  EXPECT_EQ(aborted->GetOutput()->GetNumberOfPoints(), 0);
  heard.abort = false;
  aborted->Modified();
  aborted->Update();
  EXPECT_EQ(aborted->GetOutput()->GetNumberOfPoints(), kNx * kNy * kNz);
}

TEST(MFAVolumeReader, CanReadVolumeFilesByName) {
  const fs::path dir = scratchDir();
  std::ofstream(dir / "points.vtk") << "# vtk DataFile Version 3.0\nx\nASCII\n"
                                       "DATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n";
  std::ofstream(dir / "mesh.vtk") << "# vtk DataFile Version 3.0\nx\nASCII\n"
                                     "DATASET UNSTRUCTURED_GRID\n";
  EXPECT_TRUE(vtkMFAVolumeReader::CanReadFile((dir / "points.vtk").c_str()));
  EXPECT_FALSE(vtkMFAVolumeReader::CanReadFile((dir / "mesh.vtk").c_str()));
  EXPECT_TRUE(vtkMFAVolumeReader::CanReadFile("fuel_64x64x64_uint8.raw"));
  EXPECT_FALSE(vtkMFAVolumeReader::CanReadFile("fuel.raw"));
  EXPECT_TRUE(vtkMFAVolumeReader::CanReadFile("head.NRRD"));
  EXPECT_TRUE(vtkMFAVolumeReader::CanReadFile("brain.nii.gz"));
  EXPECT_TRUE(vtkMFAVolumeReader::CanReadFile("builtin:marschner-lobb:41"));
  EXPECT_FALSE(vtkMFAVolumeReader::CanReadFile("model.mfa"));
  EXPECT_FALSE(vtkMFAVolumeReader::CanReadFile(nullptr));
}

}  // namespace
}  // namespace mfadvr::test
