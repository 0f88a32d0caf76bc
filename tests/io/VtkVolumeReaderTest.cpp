// Formats read through VTK (.vti, legacy .vtk, .mha/.mhd) and NRRD (.nrrd/.nhdr, read by
// mfadvr itself: NrrdVolumeReader.h): small files written here by hand, so that the tests pin the
// formats themselves rather than VTK's writers.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkSmartPointer.h>

#include <cstdio>

#include "GzipBytes.h"
#include "TestSupport.h"
#include "core/util/Error.h"
#include "io/RawVolumeReader.h"
#include "io/VolumeLoader.h"
#include "io/VtkSupport.h"

namespace mfadvr {
namespace {

using test::expectError;

// The grid every hand-written file describes: 10x4x3 samples, anisotropic spacing. (VTK's NRRD
// reader takes a fastest axis of 9 samples or fewer for vector components.)
const Index3 kDims{10, 4, 3};
const Vec3d kOrigin(1.5, -2.0, 3.0);
const Vec3d kSpacing(0.5, 0.25, 2.0);
constexpr int kCount = 10 * 4 * 3;

// Exactly representable in float32, so every format round-trips them bit for bit.
float density(int n) {
  const int i = n % 10, j = (n / 10) % 4, k = n / 40;
  return 0.25f * i - 1.5f * j + 10.0f * k;
}
std::int16_t label(int n) {
  const int i = n % 10, j = (n / 10) % 4, k = n / 40;
  return static_cast<std::int16_t>(i + 10 * j - 100 * k);
}

template <typename T>
void appendBytes(std::string& out, T value, std::endian order) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (order != std::endian::native) std::reverse(bytes, bytes + sizeof(T));
  out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

std::string densityBytes(std::endian order) {
  std::string out;
  for (int n = 0; n < kCount; ++n) appendBytes(out, density(n), order);
  return out;
}

std::string labelBytes(std::endian order) {
  std::string out;
  for (int n = 0; n < kCount; ++n) appendBytes(out, label(n), order);
  return out;
}

std::string writeFile(const std::filesystem::path& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

void expectDensityGrid(const StructuredGrid& g, const Vec3d& origin = kOrigin) {
  EXPECT_EQ(g.dims, kDims);
  EXPECT_EQ(g.origin, origin);
  EXPECT_EQ(g.spacing, kSpacing);
  EXPECT_EQ(g.sampleType, "float32");
  EXPECT_EQ(g.inputBytes, kCount * 4);
  ASSERT_EQ(g.values.size(), static_cast<size_t>(kCount));
  for (int n = 0; n < kCount; ++n) EXPECT_EQ(g.values[n], density(n)) << n;
}

void expectLabelGrid(const StructuredGrid& g) {
  EXPECT_EQ(g.dims, kDims);
  EXPECT_EQ(g.origin, kOrigin);
  EXPECT_EQ(g.spacing, kSpacing);
  EXPECT_EQ(g.sampleType, "int16");
  EXPECT_EQ(g.inputBytes, kCount * 2);
  ASSERT_EQ(g.values.size(), static_cast<size_t>(kCount));
  for (int n = 0; n < kCount; ++n) EXPECT_EQ(g.values[n], label(n)) << n;
}

// ---- VTK XML image data ----------------------------------------------------------------------

std::string asciiDensity() {
  std::ostringstream s;
  for (int n = 0; n < kCount; ++n) s << density(n) << ' ';
  return s.str();
}
std::string asciiLabel() {
  std::ostringstream s;
  for (int n = 0; n < kCount; ++n) s << label(n) << ' ';
  return s.str();
}
std::string asciiVectors() {
  std::ostringstream s;
  for (int n = 0; n < 3 * kCount; ++n) s << n << ' ';
  return s.str();
}

std::string cellValues() {
  std::string s;
  for (int n = 0; n < (kDims[0] - 1) * (kDims[1] - 1) * (kDims[2] - 1); ++n) s += "1 ";
  return s;
}

// `firstIndex` shifts the extent: VTK's origin is then the position of index 0, not of the
// first sample.
std::string vtiText(int firstIndex = 0, const std::string& extraImageAttributes = "") {
  std::ostringstream extent;
  for (int a = 0; a < 3; ++a)
    extent << (a ? " " : "") << firstIndex << ' ' << firstIndex + kDims[a] - 1;
  const Vec3d origin = kOrigin - firstIndex * kSpacing;
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
    << "  <ImageData WholeExtent=\"" << extent.str() << "\" Origin=\"" << origin[0] << ' '
    << origin[1] << ' ' << origin[2] << "\" Spacing=\"" << kSpacing[0] << ' ' << kSpacing[1] << ' '
    << kSpacing[2] << "\" " << extraImageAttributes << ">\n"
    << "    <Piece Extent=\"" << extent.str() << "\">\n"
    << "      <PointData Scalars=\"label\">\n"
    << "        <DataArray type=\"Float32\" Name=\"density\" format=\"ascii\">" << asciiDensity()
    << "</DataArray>\n"
    << "        <DataArray type=\"Int16\" Name=\"label\" format=\"ascii\">" << asciiLabel()
    << "</DataArray>\n"
    << "        <DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" "
       "format=\"ascii\">"
    << asciiVectors() << "</DataArray>\n"
    << "      </PointData>\n"
    << "      <CellData>\n"
    << "        <DataArray type=\"Float32\" Name=\"pressure\" format=\"ascii\">" << cellValues()
    << "</DataArray>\n"
    << "      </CellData>\n"
    << "    </Piece>\n"
    << "  </ImageData>\n"
    << "</VTKFile>\n";
  return s.str();
}

// The VTK type of each raw sample type holds samples of that type (the name VTK's arrays are
// described by comes back), and other names are refused.
TEST(VtkSampleTypes, EveryRawTypeHasAVtkTypeOfItsOwn) {
  for (const std::string& type : rawSampleTypes()) {
    vtkSmartPointer<vtkDataArray> array;
    array.TakeReference(vtkDataArray::CreateDataArray(vtkTypeOfSampleType(type)));
    ASSERT_NE(array, nullptr) << type;
    EXPECT_EQ(vtkSampleTypeName(array), type);
  }
  expectError([] { vtkTypeOfSampleType("float16"); }, {"float16"});
}

TEST(VtiReader, ActiveScalarsByDefault) {
  const auto path = writeFile(test::scratchDir() / "v.vti", vtiText());
  const StructuredGrid g = loadStructuredVolume(path);
  expectLabelGrid(g);
  EXPECT_EQ(g.fieldName, "label");
  EXPECT_EQ(g.source, path);
}

TEST(VtiReader, FieldByName) {
  const auto path = writeFile(test::scratchDir() / "v.vti", vtiText());
  VolumeLoadOptions options;
  options.field.name = "density";
  const StructuredGrid g = loadStructuredVolume(path, options);
  expectDensityGrid(g);
  EXPECT_EQ(g.fieldName, "density");
}

TEST(VtiReader, ExtentNotStartingAtZeroShiftsTheOrigin) {
  const auto path = writeFile(test::scratchDir() / "v.vti", vtiText(3));
  VolumeLoadOptions options;
  options.field.name = "density";
  expectDensityGrid(loadStructuredVolume(path, options));
}

TEST(VtiReader, OptionsOverrideTheFile) {
  const auto path = writeFile(test::scratchDir() / "v.vti", vtiText());
  VolumeLoadOptions options;
  options.origin = Vec3d(0, 0, 0);
  options.spacing = Vec3d(1, 1, 1);
  const StructuredGrid g = loadStructuredVolume(path, options);
  EXPECT_EQ(g.origin, Vec3d::Zero());
  EXPECT_EQ(g.spacing, Vec3d::Ones());
}

TEST(VtiReader, MissingFieldListsTheArrays) {
  const auto path = writeFile(test::scratchDir() / "v.vti", vtiText());
  VolumeLoadOptions options;
  options.field.name = "temperature";
  expectError([&] { loadStructuredVolume(path, options); },
              {path, "'temperature'", "'density'", "'label'", "'velocity' (3 components)"});
}

TEST(VtiReader, CellFieldByNameIsReadAtTheCellCentres) {
  const auto path = writeFile(test::scratchDir() / "v.vti", vtiText());
  VolumeLoadOptions options;
  options.field.name = "pressure";
  const StructuredGrid g = loadStructuredVolume(path, options);
  EXPECT_EQ(g.dims, (Index3{9, 3, 2}));
  EXPECT_EQ(g.origin, kOrigin + 0.5 * kSpacing);
  EXPECT_EQ(g.spacing, kSpacing);
  EXPECT_EQ(g.fieldAssociation, "cell data");
  for (double v : g.values) EXPECT_EQ(v, 1.0);
  // Asked for from the points only, it is not there.
  options.field.association = FieldAssociation::kPoints;
  expectError([&] { loadStructuredVolume(path, options); },
              {path, "'pressure'", "cell-data", "--association cell"});
  // The whole cell data, without a name: its only array.
  options.field = {};
  options.field.association = FieldAssociation::kCells;
  EXPECT_EQ(loadStructuredVolume(path, options).fieldName, "pressure");
}

TEST(VtiReader, VectorFieldNeedsAComponent) {
  const auto path = writeFile(test::scratchDir() / "v.vti", vtiText());
  VolumeLoadOptions options;
  options.field.name = "velocity";
  expectError([&] { loadStructuredVolume(path, options); },
              {path, "3 components", "--component N (0..2)", "--component magnitude"});
  options.field.component = 3;
  expectError([&] { loadStructuredVolume(path, options); }, {path, "--component 3", "0..2"});
}

TEST(VtiReader, ComponentAndMagnitudeOfAVectorField) {
  // 'velocity' holds the numbers 0, 1, 2, ... as (x, y, z) triples.
  const auto path = writeFile(test::scratchDir() / "v.vti", vtiText());
  VolumeLoadOptions options;
  options.field.name = "velocity";
  options.field.component = 2;
  const StructuredGrid z = loadStructuredVolume(path, options);
  EXPECT_EQ(z.dims, kDims);
  EXPECT_EQ(z.fieldName, "velocity_2");
  EXPECT_EQ(z.inputBytes, kCount * 3 * 8);
  for (int n = 0; n < kCount; ++n) EXPECT_EQ(z.values[n], 3 * n + 2) << n;
  options.field.component = FieldSelection::kMagnitude;
  const StructuredGrid m = loadStructuredVolume(path, options);
  EXPECT_EQ(m.fieldName, "velocity_magnitude");
  for (int n = 0; n < kCount; ++n) {
    const double x = 3 * n, y = 3 * n + 1, w = 3 * n + 2;
    EXPECT_EQ(m.values[n], static_cast<float>(std::sqrt(x * x + y * y + w * w))) << n;
  }
}

// An image with cell data only, the usual output of finite-volume codes: 'phi' numbers the
// cells x fastest. `dimsZ` 1 makes the image flat.
std::string cellOnlyVtiText(int dimsZ = kDims[2]) {
  std::ostringstream s, values;
  const int cells = (kDims[0] - 1) * (kDims[1] - 1) * std::max(dimsZ - 1, 1);
  for (int n = 0; n < cells; ++n) values << n << ' ';
  s << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
    << "<ImageData WholeExtent=\"0 " << kDims[0] - 1 << " 0 " << kDims[1] - 1 << " 0 " << dimsZ - 1
    << "\" Origin=\"" << kOrigin[0] << ' ' << kOrigin[1] << ' ' << kOrigin[2] << "\" Spacing=\""
    << kSpacing[0] << ' ' << kSpacing[1] << ' ' << kSpacing[2] << "\">\n"
    << "<Piece Extent=\"0 " << kDims[0] - 1 << " 0 " << kDims[1] - 1 << " 0 " << dimsZ - 1
    << "\">\n<PointData></PointData>\n<CellData Scalars=\"phi\">\n"
    << "<DataArray type=\"Float32\" Name=\"phi\" format=\"ascii\">" << values.str()
    << "</DataArray>\n</CellData>\n</Piece>\n</ImageData>\n</VTKFile>\n";
  return s.str();
}

TEST(VtiReader, CellDataOnlyIsReadAtTheCellCentres) {
  const auto path = writeFile(test::scratchDir() / "cells.vti", cellOnlyVtiText());
  const StructuredGrid g = loadStructuredVolume(path);
  EXPECT_EQ(g.dims, (Index3{9, 3, 2}));
  EXPECT_EQ(g.origin, kOrigin + 0.5 * kSpacing);
  EXPECT_EQ(g.spacing, kSpacing);
  EXPECT_EQ(g.fieldName, "phi");
  EXPECT_EQ(g.fieldAssociation, "cell data");
  ASSERT_EQ(g.values.size(), 9u * 3u * 2u);
  for (size_t n = 0; n < g.values.size(); ++n) EXPECT_EQ(g.values[n], static_cast<double>(n));
  ASSERT_FALSE(g.notes.empty());
  EXPECT_NE(g.notes.back().find("cell centre"), std::string::npos) << g.notes.back();
  VolumeLoadOptions points;
  points.field.association = FieldAssociation::kPoints;
  expectError([&] { loadStructuredVolume(path, points); },
              {path, "point data", "cell data: 'phi'"});
}

TEST(VtiReader, ExtentsOutsideTheWholeExtentAreErrors) {
  // Found by fuzzing: VTK's reader copied a piece past its WholeExtent from address 0.
  const auto dir = test::scratchDir();
  const std::string good = cellOnlyVtiText();
  std::string outside = good;
  outside.replace(outside.find("<Piece Extent=\"0 "), 18, "<Piece Extent=\"1 ");
  outside.replace(outside.find(" 0 2\">\n<PointData>"), 4, " 0 3");
  const auto pastEnd = writeFile(dir / "piece-outside.vti", outside);
  expectError([&] { loadStructuredVolume(pastEnd); },
              {pastEnd, "a piece's Extent is not six integers inside the WholeExtent"});
  std::string reversed = good;
  reversed.replace(reversed.find("WholeExtent=\"0 "), 15, "WholeExtent=\"10 ");
  const auto empty = writeFile(dir / "whole-reversed.vti", reversed);
  expectError([&] { loadStructuredVolume(empty); },
              {empty, "WholeExtent has a maximum below its minimum along x"});
}

TEST(VtiReader, FlatImageIsTwoDimensionalData) {
  const auto path = writeFile(test::scratchDir() / "flat.vti", cellOnlyVtiText(1));
  expectError([&] { loadStructuredVolume(path); }, {path, "10 x 4 x 1 points", "2-D data"});
  // A flat image whose only array has two components (texture coordinates): 2-D first.
  std::string texture = cellOnlyVtiText(1);
  const auto replace = [&](const std::string& from, const std::string& to) {
    texture.replace(texture.find(from), from.size(), to);
  };
  replace("<CellData Scalars=\"phi\">", "<CellData>");
  // Twice the values: two components per cell.
  std::string zeros;
  for (int n = 0; n < 9 * 3; ++n) zeros += "0 ";
  replace("Name=\"phi\" format=\"ascii\">",
          "Name=\"uv\" NumberOfComponents=\"2\" format=\"ascii\">" + zeros);
  const auto uv = writeFile(test::scratchDir() / "uv.vti", texture);
  expectError([&] { loadStructuredVolume(uv); }, {uv, "2-D data"});
}

TEST(VtiReader, CompositeDataIsNotADataSet) {
  const auto path =
      writeFile(test::scratchDir() / "blocks.vti",
                "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\">\n"
                "<vtkMultiBlockDataSet>\n<DataSet index=\"0\" file=\"blocks/blocks_0.vti\"/>\n"
                "</vtkMultiBlockDataSet>\n</VTKFile>\n");
  expectError([&] { loadStructuredVolume(path); },
              {"cannot read " + path, "vtkMultiBlockDataSet", "not a data set"});
}

TEST(LegacyVtkReader, FieldDataOnlyIsNotADataSet) {
  const auto path = writeFile(test::scratchDir() / "f.vtk",
                              "# vtk DataFile Version 1.0\nattributes\nASCII\n\n"
                              "FIELD time0 1\nthickness 1 3 float\n1 2 3\n");
  expectError([&] { loadStructuredVolume(path); }, {path, "field data only", "not a data set"});
}

TEST(VtiReader, EmptyFileSaysSo) {
  const auto path = writeFile(test::scratchDir() / "empty.vti", "");
  expectError([&] { loadStructuredVolume(path); }, {path, "the file is empty"});
}

TEST(VtiReader, RotatedGridIsAnError) {
  const auto path =
      writeFile(test::scratchDir() / "v.vti", vtiText(0, "Direction=\"0 1 0 -1 0 0 0 0 1\""));
  expectError([&] { loadStructuredVolume(path); }, {path, "direction"});
}

TEST(VtiReader, MalformedFileIsAnError) {
  const auto path = writeFile(test::scratchDir() / "v.vti", "<VTKFile type=\"ImageData\"");
  expectError([&] { loadStructuredVolume(path); }, {"cannot read " + path, "XML"});
}

TEST(VtiReader, OtherXmlDatasetIsAnError) {
  const auto data = test::dataFile("bluntfin_tets.vtu");
  if (data.empty()) GTEST_SKIP() << "bluntfin_tets.vtu not in " << test::dataDir();
  // An unstructured grid renamed to .vti: the image reader must refuse it, not crash.
  const auto path = (test::scratchDir() / "bluntfin.vti").string();
  std::filesystem::copy_file(data, path);
  expectError([&] { loadStructuredVolume(path); }, {"cannot read " + path});
}

// ---- legacy VTK ----------------------------------------------------------------------------

std::string legacyHeader(const std::string& encoding) {
  std::ostringstream s;
  s << "# vtk DataFile Version 3.0\nhand-written test volume\n"
    << encoding << "\n"
    << "DATASET STRUCTURED_POINTS\nDIMENSIONS 10 4 3\nORIGIN 1.5 -2 3\nSPACING 0.5 0.25 2\n"
    << "POINT_DATA " << kCount << "\n";
  return s.str();
}

TEST(LegacyVtkReader, AsciiStructuredPoints) {
  const std::string text = legacyHeader("ASCII") +
                           "SCALARS density float 1\nLOOKUP_TABLE default\n" + asciiDensity() +
                           "\nSCALARS label short 1\nLOOKUP_TABLE default\n" + asciiLabel() + "\n";
  const auto path = writeFile(test::scratchDir() / "v.vtk", text);
  const StructuredGrid first = loadStructuredVolume(path);
  expectDensityGrid(first);
  EXPECT_EQ(first.fieldName, "density");

  // The second SCALARS block is only there when the reader is told to read all of them.
  VolumeLoadOptions options;
  options.field.name = "label";
  const StructuredGrid second = loadStructuredVolume(path, options);
  expectLabelGrid(second);
  EXPECT_EQ(second.fieldName, "label");
}

TEST(LegacyVtkReader, BinaryStructuredPoints) {
  // Legacy binary data is big-endian whatever the host.
  const std::string text = legacyHeader("BINARY") +
                           "SCALARS label short 1\nLOOKUP_TABLE default\n" +
                           labelBytes(std::endian::big) + "\n";
  const auto path = writeFile(test::scratchDir() / "v.vtk", text);
  expectLabelGrid(loadStructuredVolume(path));
}

// Header layouts VTK 9.1's legacy reader reads completely (each checked with it): blank lines
// before the file type and between keywords, an empty title, CR LF line ends, keywords in
// lower case, versions 1.0 to 5.1, ASPECT_RATIO for SPACING, SCALARS without a component
// count, a newline after the binary data. The size check in front of the reader must let all
// of them through.
TEST(LegacyVtkReader, HeaderLayoutsThatVtkReads) {
  const std::string data = labelBytes(std::endian::big);
  // VTK's own ironProt.vtk: version 1.0, blank lines around BINARY and before POINT_DATA.
  const std::string ironProtLayout =
      "# vtk DataFile Version 1.0\nIron protein\n\nBINARY\n\nDATASET STRUCTURED_POINTS\n"
      "DIMENSIONS 10 4 3\nASPECT_RATIO 0.5 0.25 2\nORIGIN 1.5 -2 3\n\nPOINT_DATA 120\n"
      "SCALARS label short\nLOOKUP_TABLE default\n" +
      data + "\n";
  std::string crlf = legacyHeader("BINARY") + "SCALARS label short 1\nLOOKUP_TABLE default\n";
  for (size_t at = crlf.find('\n'); at != std::string::npos; at = crlf.find('\n', at + 2))
    crlf.replace(at, 1, "\r\n");
  const std::string emptyTitle =
      "# vtk DataFile Version 2.0\n\nbinary\ndataset structured_points\ndimensions 10 4 3\n"
      "origin 1.5 -2 3\nspacing 0.5 0.25 2\npoint_data 120\nscalars label short 1\n"
      "lookup_table default\n" +
      data;
  std::string v51 =
      legacyHeader("BINARY") + "SCALARS label short 1\nLOOKUP_TABLE default\n" + data + "\n";
  v51.replace(v51.find("3.0"), 3, "5.1");
  const std::pair<const char*, std::string> files[] = {
      {"ironprot.vtk", ironProtLayout},
      {"crlf.vtk", crlf + data + "\r\n"},
      {"lower.vtk", emptyTitle},
      {"v51.vtk", v51},
  };
  for (const auto& [name, text] : files) {
    SCOPED_TRACE(name);
    const auto path = writeFile(test::scratchDir() / name, text);
    expectLabelGrid(loadStructuredVolume(path));
  }
  // A blank line before ASCII and between blocks.
  const std::string ascii = "# vtk DataFile Version 3.0\ntitle\n\n\nASCII\n\n" +
                            legacyHeader("ASCII").substr(legacyHeader("ASCII").find("DATASET")) +
                            "\nSCALARS density float 1\n\nLOOKUP_TABLE default\n" + asciiDensity();
  expectDensityGrid(loadStructuredVolume(writeFile(test::scratchDir() / "a.vtk", ascii)));
}

// A dataset's FIELD block is set by VTK's readers without checking that it was read: one that
// cannot be read ended the program (a null dereference, found by fuzzing). Well-formed blocks,
// as VTK's writer makes them (with METADATA and a NULL_ARRAY), still load.
TEST(LegacyVtkReader, DatasetFieldBlocksAreCheckedBeforeVtkReadsThem) {
  const std::string points = "DATASET STRUCTURED_POINTS\n";
  const auto withField = [&](const std::string& field) {
    std::string text = legacyHeader("ASCII") + "SCALARS density float 1\nLOOKUP_TABLE default\n" +
                       asciiDensity() + "\n";
    return text.insert(text.find(points) + points.size(), field);
  };
  const std::string wellFormed =
      "FIELD FieldData 3\nTIME 1 1 double\n1.5\nCYCLE 2 2 int\n3 4 5 6\nMETADATA\n"
      "COMPONENT_NAMES\na\nb\n\nNULL_ARRAY\n";
  const auto good = writeFile(test::scratchDir() / "field.vtk", withField(wellFormed));
  expectDensityGrid(loadStructuredVolume(good));

  for (const auto& [field, expected] : std::vector<std::pair<std::string, std::string>>{
           {"fieldSIONS 10 4 3\n", "FIELD line has 3 fields"},
           {"FIELD FieldData 1\nNAMES 1 1 string\nabc\n", "numeric type"},
           {"FIELD FieldData 1\nTIME 2 1 double\n1.5\n", "where value 2"},
           {"FIELD FieldData 1\nTIME 1 double\n1.5\n", "not 4"},
           {"FIELD FieldData x\n", "not an array count"},
           {"FIELD FieldData 1\nTIME 4294967297 0 double\n", "not a component count"},
           {"FIELD FieldData 1\n" + std::string(300, 'n') + " 1 1 double\n1\n",
            "word of 300 characters"}}) {
    const auto path = writeFile(test::scratchDir() / "field.vtk", withField(field));
    expectError([&] { loadStructuredVolume(path); }, {path, expected});
  }
  // VTK reads words, not lines: a FIELD block on the DATASET line or after ASCII is read too.
  for (const auto& [from, to, expected] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"STRUCTURED_POINTS\n", "STRUCTURED_POINTS FIELD f 1\nT 1 1 strng\nx\n",
            "DATASET line has 4 fields"},
           {"ASCII\n", "ASCII FIELD f 1\n", "ASCII or BINARY line"},
           {"ORIGIN", "ORIGIN" + std::string(300, 'x'), "word of 306 characters"},
           // VTK reads "3" and takes "field" for the next keyword (found by fuzzing).
           {"DIMENSIONS 10 4 3", "DIMENSIONS 10 4 3field",
            "holds '3field', which is not a number"}}) {
    std::string text = withField("");
    text.replace(text.find(from), from.size(), to);
    const auto path = writeFile(test::scratchDir() / "field.vtk", text);
    expectError([&] { loadStructuredVolume(path); }, {path, expected});
  }
  // Values VTK reads across a line end: the walk must not lose its place.
  std::string split = withField("");
  split.replace(split.find("SPACING 0.5 0.25 2"), 18, "SPACING 0.5 0.25\n2");
  const auto path = writeFile(test::scratchDir() / "field.vtk", split);
  expectError([&] { loadStructuredVolume(path); }, {path, "SPACING line has 2 fields"});
}

TEST(LegacyVtkReader, CutBinaryDataIsStillAnError) {
  const std::string text =
      "# vtk DataFile Version 1.0\nIron protein\n\nBINARY\n\n"
      "DATASET STRUCTURED_POINTS\nDIMENSIONS 10 4 3\n"
      "ASPECT_RATIO 0.5 0.25 2\nORIGIN 1.5 -2 3\n\nPOINT_DATA 120\n"
      "SCALARS label short\nLOOKUP_TABLE default\n" +
      labelBytes(std::endian::big).substr(0, 239);
  const auto path = writeFile(test::scratchDir() / "cut.vtk", text);
  expectError([&] { loadStructuredVolume(path); }, {path, "240 bytes", "truncated"});
}

TEST(LegacyVtkReader, MissingFieldListsTheArrays) {
  const std::string text = legacyHeader("ASCII") +
                           "SCALARS density float 1\nLOOKUP_TABLE default\n" + asciiDensity() +
                           "\n";
  const auto path = writeFile(test::scratchDir() / "v.vtk", text);
  VolumeLoadOptions options;
  options.field.name = "label";
  expectError([&] { loadStructuredVolume(path, options); }, {path, "'label'", "'density'"});
}

TEST(LegacyVtkReader, UnstructuredGridNeedsStructuredPoints) {
  const auto path = test::dataFile("spx.vtk");
  if (path.empty()) GTEST_SKIP() << "spx.vtk not in " << test::dataDir();
  expectError([&] { loadStructuredVolume(path.string()); },
              {path.string(), "STRUCTURED_POINTS", "vtkUnstructuredGrid"});
}

TEST(LegacyVtkReader, PolyDataNeedsStructuredPoints) {
  const auto path = writeFile(test::scratchDir() / "p.vtk",
                              "# vtk DataFile Version 3.0\npoints\nASCII\nDATASET POLYDATA\n"
                              "POINTS 1 float\n0 0 0\n");
  expectError([&] { loadStructuredVolume(path); }, {path, "STRUCTURED_POINTS", "vtkPolyData"});
}

TEST(LegacyVtkReader, NotAVtkFileIsAnError) {
  const auto path = writeFile(test::scratchDir() / "v.vtk", "hello\n");
  expectError([&] { loadStructuredVolume(path); }, {"cannot read " + path});
}

// ---- MetaImage ---------------------------------------------------------------------------

std::string metaHeader(const std::string& type, const std::string& dataFile) {
  return "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
         "DimSize = 10 4 3\nElementSpacing = 0.5 0.25 2\nOffset = 1.5 -2 3\nElementType = " +
         type + "\nElementDataFile = " + dataFile + "\n";
}

TEST(MetaImageReader, ReadsMhaWithLocalData) {
  const auto path = writeFile(test::scratchDir() / "v.mha",
                              metaHeader("MET_SHORT", "LOCAL") + labelBytes(std::endian::little));
  expectLabelGrid(loadStructuredVolume(path));
}

TEST(MetaImageReader, ReadsMhdWithDetachedData) {
  const auto dir = test::scratchDir();
  writeFile(dir / "v.data", densityBytes(std::endian::little));
  const auto path = writeFile(dir / "v.mhd", metaHeader("MET_FLOAT", "v.data"));
  expectDensityGrid(loadStructuredVolume(path));
}

TEST(MetaImageReader, MissingDataFileIsAnError) {
  const auto path =
      writeFile(test::scratchDir() / "v.mhd", metaHeader("MET_FLOAT", "nowhere.data"));
  expectError([&] { loadStructuredVolume(path); }, {"cannot read " + path, "nowhere.data"});
}

// A file series: three slices of 10 x 4 shorts, one file each, named by `name`(slice).
template <class Name>
std::filesystem::path writeLabelSlices(const Name& name) {
  const auto dir = test::scratchDir();
  const std::string bytes = labelBytes(std::endian::little);
  const size_t slice = bytes.size() / 3;
  for (int k = 0; k < 3; ++k) writeFile(dir / name(k), bytes.substr(k * slice, slice));
  return dir;
}

TEST(MetaImageReader, ReadsANumberedFileSeries) {
  const auto dir =
      writeLabelSlices([](int k) { return "s" + std::to_string(10 + 2 * k) + ".raw"; });
  expectLabelGrid(
      loadStructuredVolume(writeFile(dir / "v.mhd", metaHeader("MET_SHORT", "s%d.raw 10 14 2"))));
  // MetaIO's defaults: numbers from 1, one per slice.
  const auto ones = writeLabelSlices([](int k) { return "t" + std::to_string(k + 1) + ".raw"; });
  expectLabelGrid(
      loadStructuredVolume(writeFile(ones / "v.mhd", metaHeader("MET_SHORT", "t%d.raw"))));
}

TEST(MetaImageReader, ReadsAFileList) {
  const auto dir = writeLabelSlices([](int k) { return "slice " + std::to_string(k) + ".raw"; });
  expectLabelGrid(loadStructuredVolume(
      writeFile(dir / "v.mhd",
                metaHeader("MET_SHORT", "LIST 2D") + "slice 0.raw\nslice 1.raw\nslice 2.raw\n")));
}

// MetaIO skips a slice file it cannot open (its samples stay unset) and hands the pattern to
// sprintf: every such series is refused before VTK's reader runs.
TEST(MetaImageReader, FileSeriesThatMetaIoWouldMisreadAreErrors) {
  const auto dir = writeLabelSlices([](int k) { return "s" + std::to_string(k + 1) + ".raw"; });
  const auto header = [&](const std::string& dataFile, const std::string& after = "") {
    return writeFile(dir / "v.mhd", metaHeader("MET_SHORT", dataFile) + after);
  };
  std::string path = header("s%d.raw 1 4 1");
  expectError([&] { loadStructuredVolume(path); }, {path, "numbers 4 files", "3"});
  path = header("s%d.raw 2");
  expectError([&] { loadStructuredVolume(path); }, {path, "'s4.raw'", "does not exist"});
  path = header("s%d.raw 1 3");  // MetaIO's step: (3 - 1) / 3 = 0
  expectError([&] { loadStructuredVolume(path); }, {path, "step of 0"});
  path = header("s%s.raw 1 3 1");
  expectError([&] { loadStructuredVolume(path); }, {path, "%d-style"});
  path = header("s%d%d.raw 1 3 1");
  expectError([&] { loadStructuredVolume(path); }, {path, "%d-style"});
  path = header("s%d.raw 1 x 1");
  expectError([&] { loadStructuredVolume(path); }, {path, "'x', not an integer"});
  path = header("LIST", "s1.raw\ns2.raw\n");
  expectError([&] { loadStructuredVolume(path); }, {path, "names 2 files", "needs 3"});
  path = header("LIST", "s1.raw\nnone.raw\ns3.raw\n");
  expectError([&] { loadStructuredVolume(path); }, {path, "'none.raw'", "does not exist"});
  path = header("LIST", "s1.raw\ns2.raw\ns3.raw");  // MetaIO drops a last line without its end
  expectError([&] { loadStructuredVolume(path); }, {path, "names 2 files"});
  writeFile(dir / "short.raw", "12345");
  path = header("LIST", "s1.raw\nshort.raw\ns3.raw\n");
  expectError([&] { loadStructuredVolume(path); }, {path, "'short.raw'", "10 x 4"});
  // A name that is neither: MetaIO opens it whole (fuzzing found VTK reading no sample of it).
  path = header("L027 45.5 13.5");
  expectError([&] { loadStructuredVolume(path); }, {path, "'L027 45.5 13.5'", "does not exist"});
}

// ---- NRRD ----------------------------------------------------------------------------------

std::string nrrdHeader(const std::string& type, const std::string& encoding,
                       const std::string& extra = "") {
  return "NRRD0004\n# hand-written test volume\ntype: " + type +
         "\ndimension: 3\nsizes: 10 4 3\nspace: 3D-right-handed\n"
         "space directions: (0.5,0,0) (0,0.25,0) (0,0,2)\nspace origin: (1.5,-2,3)\n"
         "encoding: " +
         encoding + "\nendian: little\n" + extra;
}

TEST(NrrdReader, RawEncoding) {
  const auto path = writeFile(test::scratchDir() / "v.nrrd", nrrdHeader("float", "raw") + "\n" +
                                                                 densityBytes(std::endian::little));
  expectDensityGrid(loadStructuredVolume(path));
}

TEST(NrrdReader, GzipEncoding) {
  const auto path = writeFile(
      test::scratchDir() / "v.nrrd",
      nrrdHeader("short", "gzip") + "\n" + test::gzipBytes(labelBytes(std::endian::little)));
  expectLabelGrid(loadStructuredVolume(path));
}

// The samples as text, one per line or several per line, comma- or space-separated.
std::string densityText() {
  std::string out;
  char number[32];
  for (int n = 0; n < kCount; ++n) {
    std::snprintf(number, sizeof number, "%.9g", density(n));
    out += number;
    out += n % 10 == 9 ? "\n" : (n % 3 == 0 ? ", " : " ");
  }
  return out;
}

TEST(NrrdReader, AsciiEncoding) {
  const auto path =
      writeFile(test::scratchDir() / "v.nrrd", nrrdHeader("float", "ascii") + "\n" + densityText());
  expectDensityGrid(loadStructuredVolume(path));
}

TEST(NrrdReader, AsciiEncodingDetached) {
  const auto dir = test::scratchDir();
  writeFile(dir / "v.txt", densityText());
  const auto path = writeFile(dir / "v.nhdr", nrrdHeader("float", "ascii", "data file: v.txt\n"));
  expectDensityGrid(loadStructuredVolume(path));
}

TEST(NrrdReader, AsciiWordIsAnError) {
  std::string text = densityText();
  text.replace(text.find(' '), 1, " abc ");
  const auto path =
      writeFile(test::scratchDir() / "v.nrrd", nrrdHeader("float", "ascii") + "\n" + text);
  expectError([&] { loadStructuredVolume(path); }, {path, "'abc'", "not a number"});
}

TEST(NrrdReader, SpacingsWithoutSpace) {
  const auto path = writeFile(test::scratchDir() / "v.nrrd",
                              "NRRD0004\ntype: float\ndimension: 3\nsizes: 10 4 3\n"
                              "spacings: 0.5 0.25 2\nencoding: raw\nendian: little\n\n" +
                                  densityBytes(std::endian::little));
  expectDensityGrid(loadStructuredVolume(path), Vec3d::Zero());
}

TEST(NrrdReader, DetachedHeader) {
  const auto dir = test::scratchDir();
  writeFile(dir / "v.raw.gz", test::gzipBytes(densityBytes(std::endian::little)));
  const auto path = writeFile(dir / "v.nhdr", nrrdHeader("float", "gzip", "data file: v.raw.gz\n"));
  expectDensityGrid(loadStructuredVolume(path));
}

TEST(NrrdReader, MissingDetachedDataIsAnError) {
  const auto path = writeFile(test::scratchDir() / "v.nhdr",
                              nrrdHeader("float", "raw", "data file: nowhere.raw\n"));
  expectError([&] { loadStructuredVolume(path); }, {"cannot read " + path, "nowhere.raw"});
}

// The header's kinds say what an axis is: a fastest axis of 4 samples is a spatial axis (VTK's
// reader took any of 9 or fewer for vector components and refused the volume).
TEST(NrrdReader, ShortFastestAxisIsSpatial) {
  std::string header = nrrdHeader("short", "raw", "kinds: space space space\n");
  header.replace(header.find("sizes: 10 4 3"), 13, "sizes: 4 10 3");
  const auto path =
      writeFile(test::scratchDir() / "v.nrrd", header + "\n" + labelBytes(std::endian::little));
  const StructuredGrid g = loadStructuredVolume(path);
  EXPECT_EQ(g.dims, (Index3{4, 10, 3}));
  EXPECT_TRUE(g.notes.empty());
  ASSERT_EQ(g.values.size(), static_cast<size_t>(kCount));
  for (int n = 0; n < kCount; ++n) EXPECT_EQ(g.values[n], label(n)) << n;
  // Without kinds too, with a note that says how the axis was taken.
  const auto bare = writeFile(test::scratchDir() / "w.nrrd",
                              "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 10 3\nencoding: raw\n"
                              "endian: little\n\n" +
                                  labelBytes(std::endian::little));
  const StructuredGrid b = loadStructuredVolume(bare);
  EXPECT_EQ(b.dims, (Index3{4, 10, 3}));
  ASSERT_EQ(b.notes.size(), 1u);
  EXPECT_NE(b.notes[0].find("no kinds"), std::string::npos) << b.notes[0];
}

// An axis of one sample that is not spatial (a scalar 'vector' axis, a direction of 'none') is
// dropped; the labels name the field.
TEST(NrrdReader, AxesOfOneValueAreDropped) {
  const auto dir = test::scratchDir();
  const auto path = writeFile(
      dir / "v.nrrd",
      "NRRD0005\ntype: float\ndimension: 4\nsizes: 1 10 4 3\nkinds: scalar domain domain domain\n"
      "space: right-anterior-superior\n"
      "space directions: none (0.5, 0, 0) (0,0.25,0) (0,0,2)\nspace origin: (1.5, -2, 3)\n"
      "labels: \"density\" \"x\" \"y\" \"z\"\nencoding: raw\nendian: little\n\n" +
          densityBytes(std::endian::little));
  const StructuredGrid g = loadStructuredVolume(path);
  expectDensityGrid(g);
  EXPECT_EQ(g.fieldName, "density");
  // A fourth axis of one sample and no kinds: one step of a series.
  expectDensityGrid(loadStructuredVolume(
      writeFile(dir / "w.nrrd",
                "NRRD0004\ntype: float\ndimension: 4\nsizes: 10 4 3 1\nspacings: 0.5 0.25 2 1\n"
                "axis mins: 1.5 -2 3 0\nencoding: raw\nendian: little\n\n" +
                    densityBytes(std::endian::little))));
  VolumeLoadOptions other;
  other.field.name = "pressure";
  expectError([&] { loadStructuredVolume(path, other); }, {path, "'density'", "'pressure'"});
}

// What mfadvr does not read is refused with the reason, before any data is read.
TEST(NrrdReader, UnreadLayoutsAreErrors) {
  const auto dir = test::scratchDir();
  const std::string data = densityBytes(std::endian::little);
  const auto refused = [&](const std::string& name, const std::string& fields,
                           const std::vector<std::string>& parts) {
    SCOPED_TRACE(name);
    const auto path = writeFile(
        dir / name, "NRRD0004\ntype: float\nencoding: raw\n" + fields + "\n" + data + data + data);
    std::vector<std::string> all = parts;
    all.push_back("cannot read " + path + " as NRRD");
    expectError([&] { loadStructuredVolume(path); }, all);
  };
  refused("vector.nrrd", "dimension: 4\nsizes: 3 10 4 3\nkinds: 3-vector space space space\n",
          {"axis 0", "kind 3-vector", "3 samples", "scalar volumes"});
  // A time series (read by `encode` as one 4-D model): one volume is not read from it.
  {
    const auto path = writeFile(dir / "time.nrrd",
                                "NRRD0004\ntype: float\nencoding: raw\ndimension: 4\nsizes: 10 4 3 "
                                "2\nkinds: space space space time\n\n" +
                                    data + data);
    expectError([&] { loadStructuredVolume(path); },
                {"axis 3", "time axis of 2 samples", "4-D model", "unu slice -a 3 -p 0"});
  }
  refused("flat.nrrd", "dimension: 2\nsizes: 40 3\n", {"2 spatial axes", "a volume has 3"});
  refused("thin.nrrd", "dimension: 3\nsizes: 40 3 1\n", {"40 x 3 x 1", "2-D data"});
  refused("list.nhdr", "dimension: 3\nsizes: 10 4 3\ndata file: LIST 2\na.raw\nb.raw\n",
          {"several files"});
  refused("pattern.nhdr", "dimension: 3\nsizes: 10 4 3\ndata file: s%03d.raw 1 3 1 2\n",
          {"several files"});
  refused("lineskip.nrrd", "dimension: 3\nsizes: 10 4 3\nline skip: 2\n", {"line skip 2"});
  refused("int64.nrrd", "dimension: 3\nsizes: 10 4 3\ntype: int64\n", {"'type' appears twice"});
  refused("endian.nrrd", "dimension: 3\nsizes: 10 4 3\nendian: middle\n", {"endian 'middle'"});
  refused("directions.nrrd",
          "dimension: 3\nsizes: 10 4 3\nspace dimension: 3\n"
          "space directions: (1,0,0) (0,1) (0,0,1)\n",
          {"space directions", "'(0,1)'"});
  refused("origin.nrrd", "dimension: 3\nsizes: 10 4 3\nspace origin: 1 2 3\n",
          {"space origin '1 2 3'"});
  refused("spacing.nrrd", "dimension: 3\nsizes: 10 4 3\nspacings: 1 0 1\n",
          {"spacing 0", "positive"});
  const auto wide = writeFile(dir / "wide.nrrd",
                              "NRRD0004\ntype: int64\nencoding: raw\n"
                              "dimension: 3\nsizes: 10 4 3\n\n" +
                                  data + data);
  expectError([&] { loadStructuredVolume(wide); }, {"64-bit integers", "unu convert"});
}

// byte skip: the samples after that many bytes of the data file, or (-1) its last bytes.
TEST(NrrdReader, ByteSkip) {
  const auto dir = test::scratchDir();
  writeFile(dir / "skip.raw", "junk!!!" + densityBytes(std::endian::little));
  expectDensityGrid(loadStructuredVolume(writeFile(
      dir / "skip.nhdr", nrrdHeader("float", "raw", "data file: skip.raw\nbyte skip: 7\n"))));
  expectDensityGrid(loadStructuredVolume(writeFile(
      dir / "end.nhdr", nrrdHeader("float", "raw", "data file: skip.raw\nbyte skip: -1\n"))));
  // Attached data with a skip after the header's blank line.
  expectDensityGrid(loadStructuredVolume(writeFile(
      dir / "attached.nrrd",
      nrrdHeader("float", "raw", "byte skip: 3\n") + "\nabc" + densityBytes(std::endian::little))));
  // gzip: the skip counts bytes of the inflated stream.
  expectDensityGrid(loadStructuredVolume(writeFile(
      dir / "skip.nrrd", nrrdHeader("float", "gzip", "byte skip: 5\n") + "\n" +
                             test::gzipBytes("12345" + densityBytes(std::endian::little)))));
}

// Directions that flip an axis are not applied: their lengths space the samples, a note says so.
TEST(NrrdReader, FlippedDirectionsArePlacedInIndexAxes) {
  std::string header = nrrdHeader("float", "raw");
  header.replace(header.find("(0.5,0,0)"), 9, "(-0.5,0,0)");
  const auto path =
      writeFile(test::scratchDir() / "v.nrrd", header + "\n" + densityBytes(std::endian::little));
  const StructuredGrid g = loadStructuredVolume(path);
  expectDensityGrid(g);
  ASSERT_EQ(g.notes.size(), 1u);
  EXPECT_NE(g.notes[0].find("rotate or flip"), std::string::npos) << g.notes[0];
}

TEST(NrrdReader, TruncatedGzipIsAnError) {
  std::string payload = test::gzipBytes(densityBytes(std::endian::little));
  payload.resize(payload.size() / 2);
  const auto path =
      writeFile(test::scratchDir() / "v.nrrd", nrrdHeader("float", "gzip") + "\n" + payload);
  expectError([&] { loadStructuredVolume(path); }, {"cannot read " + path});
}

// Found by fuzzing: VTK's reader takes every "dimension:" line in turn, and a huge one ends the
// program; NRRD allows each field once.
TEST(NrrdReader, FieldGivenTwiceIsAnError) {
  const auto path =
      writeFile(test::scratchDir() / "v.nrrd", "NRRD0005\ndimension: 32222222222222222\n" +
                                                   nrrdHeader("float", "raw").substr(9) + "\n" +
                                                   densityBytes(std::endian::little));
  expectError([&] { loadStructuredVolume(path); },
              {"cannot read " + path, "'dimension' appears twice"});
}

TEST(NrrdReader, NotANrrdIsAnError) {
  const auto path = writeFile(test::scratchDir() / "v.nrrd", "P6\n5 4\n255\n");
  expectError([&] { loadStructuredVolume(path); }, {"cannot read " + path, "NRRD"});
}

TEST(NrrdReader, RealBonsai) {
  const auto path = test::dataFile("bonsai.nrrd");
  if (path.empty()) GTEST_SKIP() << "bonsai.nrrd not in " << test::dataDir();
  const StructuredGrid g = loadStructuredVolume(path.string());
  EXPECT_EQ(g.dims, (Index3{256, 256, 256}));
  EXPECT_EQ(g.sampleType, "uint8");
  EXPECT_EQ(g.inputBytes, 256 * 256 * 256);
  EXPECT_EQ(g.origin, Vec3d::Constant(-128.0));
  EXPECT_EQ(g.spacing, Vec3d::Ones());
  const auto [lo, hi] = std::minmax_element(g.values.begin(), g.values.end());
  EXPECT_EQ(*lo, 0.0);
  EXPECT_EQ(*hi, 255.0);
  // Sum of the decompressed bytes, computed independently with Python's zlib.
  double sum = 0.0;
  for (double v : g.values) sum += v;
  EXPECT_EQ(sum, 230038784.0);
}

}  // namespace
}  // namespace mfadvr
