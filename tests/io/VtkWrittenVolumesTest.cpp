// Volumes as another program writes them: VTK's own writers (NIfTI, MetaImage, legacy structured
// points, XML image data), each sample type the formats hold, read back by loadStructuredVolume
// and, where it streams the format, by openStreamedVolume. The hand-written headers of the other
// reader tests cover the forms we thought of; these are the forms a user's files come in.
#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMetaImageWriter.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStructuredPointsWriter.h>
#include <vtkType.h>
#include <vtkXMLImageDataWriter.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "TestSupport.h"
#include "core/grid/SampleRange.h"
#include "io/StreamedVolumeReader.h"
#include "io/VolumeLoader.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;

// An odd size on every axis, so that no two axes can be confused.
constexpr int kNx = 13, kNy = 10, kNz = 9;

struct SampleType {
  int vtkType;
  const char* name;  // StructuredGrid::sampleType
  // The value of sample (i, j, k): distinct along each axis, exact in float32 and in the type.
  std::function<double(int, int, int)> value;
};

std::vector<SampleType> sampleTypes() {
  const auto ramp = [](int i, int j, int k) { return 3 * i + 5 * j + 7 * k + (i * j) % 4; };
  return {
      {VTK_UNSIGNED_CHAR, "uint8", [=](int i, int j, int k) { return ramp(i, j, k); }},
      {VTK_SIGNED_CHAR, "int8", [](int i, int j, int k) { return i + 2 * j + 3 * k - 40; }},
      {VTK_SHORT, "int16", [=](int i, int j, int k) { return 37 * ramp(i, j, k) - 2000; }},
      {VTK_UNSIGNED_SHORT, "uint16", [=](int i, int j, int k) { return 401 * ramp(i, j, k); }},
      {VTK_FLOAT, "float32", [=](int i, int j, int k) { return 0.25 * ramp(i, j, k) - 10.0; }},
      {VTK_DOUBLE, "float64", [=](int i, int j, int k) { return -0.5 * ramp(i, j, k) + 3.0; }},
  };
}

vtkNew<vtkImageData> makeImage(const SampleType& type) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(kNx, kNy, kNz);
  image->SetSpacing(0.5, 0.75, 1.25);
  image->SetOrigin(-3.0, 2.0, 10.0);
  image->AllocateScalars(type.vtkType, 1);
  image->GetPointData()->GetScalars()->SetName("density");
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i)
        image->SetScalarComponentFromDouble(i, j, k, 0, type.value(i, j, k));
  return image;
}

// The files VTK writes of `image` under `dir`, one per writer and setting.
std::vector<std::string> writeAll(vtkImageData* image, const fs::path& dir) {
  std::vector<std::string> files;
  const auto add = [&](const fs::path& p) {
    files.push_back(p.string());
    return p.string();
  };
  for (const char* name : {"v.nii", "v.nii.gz"}) {
    vtkNew<vtkNIFTIImageWriter> w;
    w->SetInputData(image);
    w->SetFileName(add(dir / name).c_str());
    w->Write();
  }
  for (const bool compressed : {false, true}) {
    vtkNew<vtkMetaImageWriter> w;
    w->SetInputData(image);
    const fs::path header = dir / (compressed ? "z.mhd" : "v.mha");
    w->SetFileName(add(header).c_str());
    if (compressed) w->SetRAWFileName((dir / "z.zraw").string().c_str());
    w->SetCompression(compressed);
    w->Write();
  }
  for (const bool binary : {true, false}) {
    vtkNew<vtkStructuredPointsWriter> w;
    w->SetInputData(image);
    w->SetFileName(add(dir / (binary ? "binary.vtk" : "ascii.vtk")).c_str());
    if (binary)
      w->SetFileTypeToBinary();
    else
      w->SetFileTypeToASCII();
    w->Write();
  }
  for (const int mode : {vtkXMLWriter::Appended, vtkXMLWriter::Binary, vtkXMLWriter::Ascii}) {
    vtkNew<vtkXMLImageDataWriter> w;
    w->SetInputData(image);
    w->SetFileName(add(dir / ("mode" + std::to_string(mode) + ".vti")).c_str());
    w->SetDataMode(mode);
    w->Write();
  }
  return files;
}

TEST(VtkWrittenVolumes, EveryWriterAndSampleTypeReadsBackExactly) {
  for (const SampleType& type : sampleTypes()) {
    const fs::path dir = test::scratchDir() / type.name;
    fs::create_directories(dir);
    const vtkNew<vtkImageData> image = makeImage(type);
    for (const std::string& path : writeAll(image, dir)) {
      SCOPED_TRACE(path);
      ASSERT_TRUE(fs::exists(path));
      const StructuredGrid grid = loadStructuredVolume(path);
      ASSERT_EQ(grid.dims, (Index3{kNx, kNy, kNz}));
      EXPECT_EQ(grid.spacing, Vec3d(0.5, 0.75, 1.25));
      EXPECT_EQ(grid.origin, Vec3d(-3.0, 2.0, 10.0));
      EXPECT_EQ(grid.sampleType, type.name);
      int wrong = 0;
      for (int k = 0; k < kNz; ++k)
        for (int j = 0; j < kNy; ++j)
          for (int i = 0; i < kNx; ++i)
            wrong += grid.at(i, j, k) != static_cast<float>(type.value(i, j, k));
      EXPECT_EQ(wrong, 0);
      // Where the format is streamed, the streamed samples are the same.
      if (const auto source = openStreamedVolume(path, {}, GzipPayloads::kInflateToTemporaryFile)) {
        const StructuredGrid streamed = source->read(wholeRange(source->layout().dims));
        EXPECT_EQ(streamed.dims, grid.dims);
        EXPECT_EQ(streamed.spacing, grid.spacing);
        EXPECT_EQ(streamed.origin, grid.origin);
        EXPECT_EQ(streamed.values, grid.values);
      }
    }
  }
}

}  // namespace
}  // namespace mfadvr
