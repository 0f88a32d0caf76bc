// No silent data loss: for every input format, a valid file cut at several points, and single
// bytes changed where the file declares its sizes, give an error naming the file instead of a
// grid or point set with zeros or garbage where the data was. The valid files are written by
// VTK's own writers (the files users have) and, for NRRD, DICOM and NIfTI, byte by byte.
#include <gtest/gtest.h>

#include <vtkDataSetTriangleFilter.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMetaImageWriter.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkStructuredPointsWriter.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "MedicalTestFiles.h"
#include "TestSupport.h"
#include "core/util/Error.h"
#include "io/ScatteredLoader.h"
#include "io/VolumeLoader.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;

// 17 x 13 x 11 float samples (distinct sizes, so that a swapped or changed size shows).
constexpr int kX = 17, kY = 13, kZ = 11;

vtkNew<vtkImageData> makeImage() {
  vtkNew<vtkImageData> image;
  image->SetDimensions(kX, kY, kZ);
  image->SetSpacing(0.5, 0.25, 2.0);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(kX * kY * kZ);
  for (vtkIdType n = 0; n < kX * kY * kZ; ++n) values->SetValue(n, float(n % 97) * 0.5f - 7.0f);
  image->GetPointData()->SetScalars(values);
  return image;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string floatBytes() {
  std::string out;
  for (int n = 0; n < kX * kY * kZ; ++n) {
    const float v = float(n % 97) * 0.5f - 7.0f;
    out.append(reinterpret_cast<const char*>(&v), 4);
  }
  return out;
}

std::string nrrdHeader(const std::string& encoding) {
  return "NRRD0004\ntype: float\ndimension: 3\nsizes: " + std::to_string(kX) + " " +
         std::to_string(kY) + " " + std::to_string(kZ) + "\nencoding: " + encoding +
         "\nendian: little\nspacings: 0.5 0.25 2\n\n";
}

// A valid file of each kind, in `dir`; `data` is the file whose bytes the cuts apply to (a
// detached data file, or the file itself).
struct Sample {
  std::string name;  // what the failure messages call it
  fs::path input;    // what the loader is given
  fs::path data;     // the file that is cut
  bool volume = true;
  // Whether the samples are the end of the file (legacy VTK files end with a METADATA block
  // that VTK 9 writes and that carries no samples).
  bool dataAtEnd = true;
  // Header edits that change a declared size: each must be an error.
  std::vector<std::pair<std::string, std::string>> sizeEdits;
};

Sample sample(std::string name, fs::path input, fs::path data, bool volume = true,
              std::vector<std::pair<std::string, std::string>> sizeEdits = {}) {
  const bool legacy = data.extension() == ".vtk";
  return {std::move(name), std::move(input), std::move(data),
          volume,          !legacy,          std::move(sizeEdits)};
}

std::vector<Sample> writeSamples(const fs::path& dir) {
  std::vector<Sample> out;
  auto image = makeImage();
  const std::string dims = std::to_string(kX) + " " + std::to_string(kY) + " " + std::to_string(kZ);
  const std::string bigger =
      std::to_string(kX) + " " + std::to_string(kY) + " " + std::to_string(kZ + 1);
  const std::string smaller =
      std::to_string(kX) + " " + std::to_string(kY) + " " + std::to_string(kZ - 1);

  {  // VTK XML image data, appended raw (the layout large files use) and inline base64
    vtkNew<vtkXMLImageDataWriter> w;
    w->SetInputData(image);
    w->SetFileName((dir / "appended.vti").c_str());
    w->SetDataModeToAppended();
    w->EncodeAppendedDataOff();
    w->SetCompressorTypeToNone();
    w->Write();
    vtkNew<vtkXMLImageDataWriter> inlined;
    inlined->SetInputData(image);
    inlined->SetFileName((dir / "inline.vti").c_str());
    inlined->SetDataModeToBinary();  // base64 inside the XML
    inlined->SetCompressorTypeToZLib();
    inlined->Write();
    out.push_back(sample("vti appended", dir / "appended.vti", dir / "appended.vti"));
    out.push_back(sample("vti inline", dir / "inline.vti", dir / "inline.vti"));
  }
  {  // legacy structured points, binary and ASCII
    vtkNew<vtkStructuredPointsWriter> w;
    w->SetInputData(image);
    w->SetFileName((dir / "binary.vtk").c_str());
    w->SetFileTypeToBinary();
    w->Write();
    w->SetFileName((dir / "ascii.vtk").c_str());
    w->SetFileTypeToASCII();
    w->Write();
    out.push_back(sample("legacy binary", dir / "binary.vtk", dir / "binary.vtk", true,
                         {{"DIMENSIONS " + dims, "DIMENSIONS " + bigger},
                          {"POINT_DATA " + std::to_string(kX * kY * kZ),
                           "POINT_DATA " + std::to_string(kX * kY * (kZ + 1))}}));
    out.push_back(sample("legacy ascii", dir / "ascii.vtk", dir / "ascii.vtk", true,
                         {{"DIMENSIONS " + dims, "DIMENSIONS " + bigger}}));
  }
  {  // MetaImage: one file, and header + data file
    vtkNew<vtkMetaImageWriter> w;
    w->SetInputData(image);
    w->SetCompression(false);
    w->SetFileName((dir / "local.mha").c_str());
    w->Write();
    w->SetFileName((dir / "detached.mhd").c_str());
    w->SetRAWFileName((dir / "detached.raw").c_str());
    w->Write();
    out.push_back(sample("mha", dir / "local.mha", dir / "local.mha", true,
                         {{"DimSize = " + dims, "DimSize = " + bigger},
                          {"DimSize = " + dims, "DimSize = " + smaller},
                          {"MET_FLOAT", "MET_DOUBLE"}}));
    out.push_back(sample("mhd", dir / "detached.mhd", dir / "detached.raw", true,
                         {{"DimSize = " + dims, "DimSize = " + smaller}}));
  }
  {  // NRRD: raw, gzip and ASCII attached, raw detached
    writeBytes(dir / "raw.nrrd", nrrdHeader("raw") + floatBytes());
    writeBytes(dir / "gzip.nrrd", nrrdHeader("gzip") + test::gzipBytes(floatBytes()));
    std::ostringstream ascii;
    for (int n = 0; n < kX * kY * kZ; ++n) ascii << float(n % 97) * 0.5f - 7.0f << "\n";
    writeBytes(dir / "ascii.nrrd", nrrdHeader("ascii") + ascii.str());
    std::string detached = nrrdHeader("raw");
    detached.insert(detached.size() - 1, "data file: detached-nrrd.raw\n");
    writeBytes(dir / "detached.nhdr", detached);
    writeBytes(dir / "detached-nrrd.raw", floatBytes());
    const std::vector<std::pair<std::string, std::string>> edits = {
        {"sizes: " + dims, "sizes: " + bigger},
        {"sizes: " + dims, "sizes: " + smaller},
        {"type: float", "type: double"}};
    out.push_back(sample("nrrd raw", dir / "raw.nrrd", dir / "raw.nrrd", true, edits));
    out.push_back(sample("nrrd gzip", dir / "gzip.nrrd", dir / "gzip.nrrd"));
    out.push_back(sample("nrrd ascii", dir / "ascii.nrrd", dir / "ascii.nrrd", true,
                         {{"sizes: " + dims, "sizes: " + bigger}}));
    out.push_back(sample("nhdr", dir / "detached.nhdr", dir / "detached-nrrd.raw", true, edits));
  }
  {  // NIfTI, from VTK's writer, plain and gzip
    vtkNew<vtkNIFTIImageWriter> w;
    w->SetInputData(image);
    w->SetFileName((dir / "plain.nii").c_str());
    w->Write();
    w->SetFileName((dir / "packed.nii.gz").c_str());
    w->Write();
    out.push_back(sample("nii", dir / "plain.nii", dir / "plain.nii"));
    out.push_back(sample("nii.gz", dir / "packed.nii.gz", dir / "packed.nii.gz"));
  }
  {  // raw volume named by its size
    const std::string name = "cube_" + std::to_string(kX) + "x" + std::to_string(kY) + "x" +
                             std::to_string(kZ) + "_float32.raw";
    writeBytes(dir / name, floatBytes());
    out.push_back(sample("raw", dir / name, dir / name));
  }
  {  // DICOM series: the middle slice is cut
    const fs::path series = dir / "dicom";
    fs::create_directories(series);
    for (int k = 0; k < test::kNk; ++k)
      writeBytes(series / ("s" + std::to_string(k) + ".dcm"), test::dicomSlice(k));
    out.push_back(sample("dicom", series, series / "s1.dcm"));
  }
  {  // meshes: XML and legacy unstructured grids of tetrahedra
    vtkNew<vtkDataSetTriangleFilter> tets;
    tets->SetInputData(image);
    tets->Update();
    vtkNew<vtkXMLUnstructuredGridWriter> xml;
    xml->SetInputData(tets->GetOutput());
    xml->SetFileName((dir / "mesh.vtu").c_str());
    xml->SetDataModeToAppended();
    xml->EncodeAppendedDataOff();
    xml->SetCompressorTypeToNone();
    xml->Write();
    vtkNew<vtkUnstructuredGridWriter> legacy;
    legacy->SetInputData(tets->GetOutput());
    legacy->SetFileName((dir / "mesh.vtk").c_str());
    legacy->SetFileTypeToBinary();
    legacy->Write();
    out.push_back(sample("vtu", dir / "mesh.vtu", dir / "mesh.vtu", false));
    out.push_back(sample("legacy mesh", dir / "mesh.vtk", dir / "mesh.vtk", false));
  }
  {  // a point list
    std::ostringstream csv;
    csv << "x,y,z,v\n";
    for (int n = 0; n < 300; ++n)
      csv << (n % 7) * 0.125 << "," << (n % 11) * 0.25 << "," << (n % 13) * 0.5 << "," << n * 1.25
          << "\n";
    writeBytes(dir / "points.csv", csv.str());
    out.push_back(sample("csv", dir / "points.csv", dir / "points.csv", false));
  }
  return out;
}

void load(const Sample& s) {
  if (s.volume)
    loadStructuredVolume(s.input.string());
  else
    loadScatteredData(s.input.string());
}

// Where a read fails it must say so with an mfadvr::Error that names a file of the input.
void expectLoadError(const Sample& s, const std::string& what) {
  try {
    load(s);
    ADD_FAILURE() << s.name << ", " << what << ": read without an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_TRUE(message.find(s.input.filename().string()) != std::string::npos ||
                message.find(s.data.filename().string()) != std::string::npos)
        << s.name << ", " << what << ": the message names no file: " << message;
  }
}

TEST(TruncatedInput, EveryFormatReadsItsValidFile) {
  for (const Sample& s : writeSamples(test::scratchDir())) {
    SCOPED_TRACE(s.name);
    EXPECT_NO_THROW(load(s));
  }
}

TEST(TruncatedInput, CutFilesAreErrorsInEveryFormat) {
  const fs::path dir = test::scratchDir();
  for (const Sample& s : writeSamples(dir)) {
    const std::string bytes = readBytes(s.data);
    ASSERT_GT(bytes.size(), 100u) << s.name;
    for (double fraction : {0.02, 0.25, 0.5, 0.75, 0.98}) {
      const size_t keep = static_cast<size_t>(fraction * static_cast<double>(bytes.size()));
      writeBytes(s.data, bytes.substr(0, keep));
      expectLoadError(
          s, "cut to " + std::to_string(keep) + " of " + std::to_string(bytes.size()) + " bytes");
    }
    // The last byte of the samples (text formats end with a line break or two, which a file
    // can lose without losing anything).
    if (s.dataAtEnd) {
      const size_t end = bytes.find_last_not_of(" \t\r\n") + 1;
      writeBytes(s.data, bytes.substr(0, end - 1));
      expectLoadError(s, "the last byte of the samples cut");
    }
    writeBytes(s.data, bytes);
  }
}

TEST(TruncatedInput, ChangedDeclaredSizesAreErrors) {
  const fs::path dir = test::scratchDir();
  for (const Sample& s : writeSamples(dir)) {
    const std::string bytes = readBytes(s.input);
    for (const auto& [from, to] : s.sizeEdits) {
      const auto at = bytes.find(from);
      ASSERT_NE(at, std::string::npos) << s.name << ": no '" << from << "' in the header";
      std::string edited = bytes;
      edited.replace(at, from.size(), to);
      writeBytes(s.input, edited);
      expectLoadError(s, "'" + from + "' -> '" + to + "'");
    }
    writeBytes(s.input, bytes);
  }
}

// Single bytes of the binary headers that declare sizes: NIfTI's dim[3] and bitpix, DICOM's
// Rows and the pixel data length, the raw file's name.
TEST(TruncatedInput, ChangedBinaryHeaderBytesAreErrors) {
  const fs::path dir = test::scratchDir();
  test::NiftiHeader h;
  const std::string nifti = test::niftiBytes(h);
  const Sample nii = sample("nii", dir / "h.nii", dir / "h.nii");
  for (const auto& [offset, value] : std::vector<std::pair<size_t, char>>{
           {46, char(test::kNk + 1)},  // dim[3]
           {72, 32},                   // bitpix 16 -> 32
           {70, 16}}) {                // datatype int16 -> float32 (4 bytes a sample)
    std::string edited = nifti;
    edited[offset] = value;
    if (offset == 70) edited[72] = 32;
    writeBytes(nii.input, edited);
    expectLoadError(nii, "NIfTI byte " + std::to_string(offset));
  }

  const fs::path series = dir / "series";
  fs::create_directories(series);
  for (int k = 0; k < test::kNk; ++k)
    writeBytes(series / ("s" + std::to_string(k) + ".dcm"), test::dicomSlice(k));
  const Sample dicom = sample("dicom", series, series / "s1.dcm");
  const std::string slice = test::dicomSlice(1);
  // Rows (0028,0010) US = kNj: its value follows the 8-byte explicit-VR element header.
  const std::string rowsTag("\x28\x00\x10\x00US\x02\x00", 8);
  const auto rows = slice.find(rowsTag);
  ASSERT_NE(rows, std::string::npos);
  std::string edited = slice;
  edited[rows + 8] = char(test::kNj + 1);
  writeBytes(dicom.data, edited);
  expectLoadError(dicom, "DICOM Rows + 1");
  writeBytes(dicom.data, slice);
  EXPECT_NO_THROW(load(dicom));

  const Sample raw = sample("raw", dir / "v_17x13x12_float32.raw", dir / "v_17x13x12_float32.raw");
  writeBytes(raw.input, floatBytes());  // 17 x 13 x 11 samples under a name that says 12
  expectLoadError(raw, "raw name");
}

// VTK's DICOM reader assumes an image size of its own where Rows, Columns or Bits Allocated is
// missing and reads past the pixel data: a slice without one of them (its group byte changed,
// as the fuzzer did) is refused, as is one where it is 0.
TEST(TruncatedInput, DicomSlicesThatVtkWouldMisreadAreErrors) {
  const fs::path series = test::scratchDir() / "series";
  fs::create_directories(series);
  for (int k = 0; k < test::kNk; ++k)
    writeBytes(series / ("s" + std::to_string(k) + ".dcm"), test::dicomSlice(k));
  const Sample dicom = sample("dicom", series, series / "s1.dcm");
  const std::string slice = test::dicomSlice(1);
  for (const char element : {'\x10', '\x11', '\x00'}) {  // (0028,0010), (0028,0011), (0028,0100)
    const std::string tag =
        std::string("\x28\x00", 2) + element + (element == '\x00' ? '\x01' : '\x00') + "US";
    const auto at = slice.find(tag);
    ASSERT_NE(at, std::string::npos);
    std::string edited = slice;
    edited[at] = '\x2F';  // (002F,....): not an attribute VTK's reader knows
    writeBytes(dicom.data, edited);
    expectLoadError(dicom, "DICOM tag " + std::to_string(int(element)) + " missing");
    edited = slice;
    edited[at + 8] = edited[at + 9] = '\0';
    writeBytes(dicom.data, edited);
    expectLoadError(dicom, "DICOM tag " + std::to_string(int(element)) + " of 0");
  }
  // Refused by the check with its own reason, not by what VTK's reader made of the slice.
  const auto expectRefused = [&](const std::string& edited, const std::string& reason) {
    writeBytes(dicom.data, edited);
    try {
      load(dicom);
      ADD_FAILURE() << "DICOM, " << reason << ": read without an error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
    }
  };
  const auto at = [&](const std::string& bytes) {
    const auto found = slice.find(bytes);
    EXPECT_NE(found, std::string::npos) << "the test slice lacks an element";
    return found;
  };
  // VTK's reader takes 3 samples a pixel for an RGB image and 1 for any other, whatever Samples
  // per Pixel says: RGB of one sample (it read past the pixel data) and a monochrome image of
  // three (it mixed them) are refused.
  std::string rgb = slice;
  rgb.replace(at("MONOCHROME2 "), 12, std::string("RGB \0\0\0\0\0\0\0\0", 12));
  expectRefused(rgb, "Samples per Pixel");
  std::string threeSamples = slice;
  threeSamples[at(std::string("\x28\x00\x02\x00US", 6)) + 8] = 3;
  expectRefused(threeSamples, "Samples per Pixel");
  // Samples of 12 bits: VTK's reader copied twice the bytes it had kept.
  std::string twelveBits = slice;
  twelveBits[at(std::string("\x28\x00\x00\x01US", 6)) + 8] = 12;
  expectRefused(twelveBits, "8 or 16 bits");
  // A multi-frame image: VTK's reader would read its first frame alone.
  std::string frames = slice;
  frames.insert(at(std::string("\x28\x00\x10\x00US", 6)), std::string("\x28\x00\x08\x00IS\x02\x00"
                                                                      "3 ",
                                                                      10));
  expectRefused(frames, "3 frames");
  writeBytes(dicom.data, slice);
  EXPECT_NO_THROW(load(dicom));
}

}  // namespace
}  // namespace mfadvr
