// Scattered inputs (loadScatteredData): meshes and point clouds in VTK XML, legacy VTK and text,
// written here by hand so that the tests pin the formats themselves rather than VTK's writers;
// then the shared real meshes when they are present.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "TestSupport.h"
#include "core/util/Error.h"
#include "io/ScatteredLoader.h"

namespace mfadvr {
namespace {

using test::expectError;

std::string writeFile(const std::filesystem::path& path, const std::string& content) {
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

// The unit cube's corners, point n at (n & 1, n >> 1 & 1, n >> 2 & 1), and a value per corner.
Vec3d corner(int n) {
  return Vec3d(n & 1, (n >> 1) & 1, (n >> 2) & 1);
}
double cornerValue(int n) {
  return corner(n).x() + 2 * corner(n).y() + 4 * corner(n).z();
}

std::string cornerText() {
  std::ostringstream s;
  for (int n = 0; n < 8; ++n)
    s << corner(n).x() << ' ' << corner(n).y() << ' ' << corner(n).z() << '\n';
  return s.str();
}
std::string cornerValueText() {
  std::ostringstream s;
  for (int n = 0; n < 8; ++n) s << cornerValue(n) << ' ';
  return s.str();
}

// The cube as five tetrahedra: four corner tets and the middle one.
const int kFiveTets[5][4] = {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}};
// The cube as one VTK hexahedron (VTK's corner order).
const int kHex[8] = {0, 1, 3, 2, 4, 5, 7, 6};

double tetVolume(const ScatteredData& d, const Tetrahedron& t) {
  const Vec3d a = d.points[t[1]] - d.points[t[0]];
  const Vec3d b = d.points[t[2]] - d.points[t[0]];
  const Vec3d c = d.points[t[3]] - d.points[t[0]];
  return std::abs(a.dot(b.cross(c))) / 6.0;
}

double totalVolume(const ScatteredData& d) {
  double v = 0;
  for (const auto& t : d.tets) v += tetVolume(d, t);
  return v;
}

void expectCornerPointsAndValues(const ScatteredData& d) {
  ASSERT_EQ(d.pointCount(), 8);
  ASSERT_EQ(d.values.size(), 8u);
  for (int n = 0; n < 8; ++n) {
    EXPECT_EQ(d.points[n], corner(n)) << n;
    EXPECT_EQ(d.values[n], cornerValue(n)) << n;
  }
}

// ---- VTK XML unstructured grid ----------------------------------------------------------------

struct VtuCells {
  std::string connectivity, offsets, types;
  int count = 0, ids = 0;
  void add(int type, std::initializer_list<int> points) {
    for (int p : points) connectivity += std::to_string(p) + " ";
    ids += static_cast<int>(points.size());
    offsets += std::to_string(ids) + " ";
    types += std::to_string(type) + " ";
    ++count;
  }
};

VtuCells fiveTets() {
  VtuCells c;
  for (const auto& t : kFiveTets) c.add(10, {t[0], t[1], t[2], t[3]});
  return c;
}

VtuCells oneHex() {
  VtuCells c;
  c.add(12, {kHex[0], kHex[1], kHex[2], kHex[3], kHex[4], kHex[5], kHex[6], kHex[7]});
  return c;
}

// An XML element holding an ASCII data array.
std::string dataArray(const std::string& type, const std::string& name, int components,
                      const std::string& values) {
  return "<DataArray type=\"" + type + "\"" + (name.empty() ? "" : " Name=\"" + name + "\"") +
         " NumberOfComponents=\"" + std::to_string(components) + "\" format=\"ascii\">" + values +
         "</DataArray>\n";
}

// The cube's corners with point data 'temp' (the corner values, the active scalars) and 'vec'
// (3 components), the given cells and cell data.
std::string vtuText(const VtuCells& cells, const std::string& cellData = "") {
  return "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<UnstructuredGrid>\n<Piece NumberOfPoints=\"8\" NumberOfCells=\"" +
         std::to_string(cells.count) + "\">\n<PointData Scalars=\"temp\">\n" +
         dataArray("Float32", "temp", 1, cornerValueText()) +
         dataArray("Float64", "vec", 3, cornerText()) + "</PointData>\n<CellData>" + cellData +
         "</CellData>\n<Points>\n" + dataArray("Float64", "", 3, cornerText()) +
         "</Points>\n<Cells>\n" + dataArray("Int64", "connectivity", 1, cells.connectivity) +
         dataArray("Int64", "offsets", 1, cells.offsets) +
         dataArray("UInt8", "types", 1, cells.types) +
         "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

TEST(ScatteredLoader, VtuTetrahedra) {
  const auto dir = test::scratchDir();
  const auto path = writeFile(dir / "cube.vtu", vtuText(fiveTets()));
  EXPECT_TRUE(isScatteredInput(path));
  const ScatteredData d = loadScatteredData(path);
  expectCornerPointsAndValues(d);
  EXPECT_EQ(d.source, path);
  EXPECT_EQ(d.kind, "tetrahedral mesh");
  EXPECT_EQ(d.fieldName, "temp");
  EXPECT_EQ(d.fieldAssociation, "point data");
  EXPECT_EQ(d.sampleType, "float32");
  EXPECT_EQ(d.inputBytes, 8 * 4);
  EXPECT_EQ(d.inputCells, 5);
  ASSERT_EQ(d.tets.size(), 5u);
  for (int t = 0; t < 5; ++t)
    for (int v = 0; v < 4; ++v) EXPECT_EQ(d.tets[t][v], kFiveTets[t][v]);
  EXPECT_NEAR(totalVolume(d), 1.0, 1e-12);
}

TEST(ScatteredLoader, VtuHexahedronIsSplitIntoTetrahedra) {
  const auto dir = test::scratchDir();
  const auto path = writeFile(dir / "hex.vtu", vtuText(oneHex()));
  const ScatteredData d = loadScatteredData(path);
  expectCornerPointsAndValues(d);
  EXPECT_EQ(d.kind, "mixed-cell mesh");
  EXPECT_EQ(d.inputCells, 1);
  EXPECT_GE(d.tets.size(), 5u);
  EXPECT_LE(d.tets.size(), 6u);
  EXPECT_NEAR(totalVolume(d), 1.0, 1e-12);
  for (const auto& t : d.tets) EXPECT_GT(tetVolume(d, t), 0.0);
}

TEST(ScatteredLoader, WedgeIsSplitAndUnusedPointsStay) {
  // Half the cube as a wedge on corners 0 1 2 / 4 5 6; corners 3 and 7 belong to no cell.
  VtuCells cells;
  cells.add(13, {0, 1, 2, 4, 5, 6});
  const ScatteredData d =
      loadScatteredData(writeFile(test::scratchDir() / "w.vtu", vtuText(cells)));
  expectCornerPointsAndValues(d);
  EXPECT_EQ(d.kind, "mixed-cell mesh");
  EXPECT_EQ(d.tets.size(), 3u);
  EXPECT_NEAR(totalVolume(d), 0.5, 1e-12);
}

TEST(ScatteredLoader, MixedCellsIgnoreSurfaceCells) {
  const auto dir = test::scratchDir();
  // A hexahedron, a tetrahedron inside it, and a boundary triangle: the triangle is no volume.
  VtuCells cells = oneHex();
  cells.add(10, {0, 1, 2, 4});
  cells.add(5, {0, 1, 2});
  const ScatteredData d = loadScatteredData(writeFile(dir / "m.vtu", vtuText(cells)));
  EXPECT_EQ(d.kind, "mixed-cell mesh");
  EXPECT_EQ(d.inputCells, 2);
  EXPECT_NEAR(totalVolume(d), 1.0 + 1.0 / 6.0, 1e-12);
}

TEST(ScatteredLoader, SurfaceOnlyMeshIsAPointCloud) {
  const auto dir = test::scratchDir();
  VtuCells cells;
  cells.add(5, {0, 1, 2});
  cells.add(9, {4, 5, 7, 6});
  const ScatteredData d = loadScatteredData(writeFile(dir / "s.vtu", vtuText(cells)));
  expectCornerPointsAndValues(d);
  EXPECT_EQ(d.kind, "point cloud");
  EXPECT_TRUE(d.tets.empty());
  EXPECT_EQ(d.inputCells, 0);
}

TEST(ScatteredLoader, CellDataIsAveragedToPoints) {
  const auto dir = test::scratchDir();
  const std::string cellData = dataArray("Int16", "label", 1, "1 2 3 4 5");
  const auto path = writeFile(dir / "c.vtu", vtuText(fiveTets(), cellData));
  ScatteredLoadOptions options;
  options.field.name = "label";
  const ScatteredData d = loadScatteredData(path, options);
  EXPECT_EQ(d.fieldName, "label");
  EXPECT_EQ(d.fieldAssociation, "cell data averaged to points");
  EXPECT_EQ(d.sampleType, "int16");
  EXPECT_EQ(d.inputBytes, 5 * 2);
  ASSERT_EQ(d.pointCount(), 8);
  EXPECT_EQ(d.tets.size(), 5u);
  EXPECT_DOUBLE_EQ(d.values[0], 1.0);                    // only in tet 1
  EXPECT_DOUBLE_EQ(d.values[7], (2 + 3 + 4 + 5) / 4.0);  // in every tet but the first
  EXPECT_DOUBLE_EQ(d.values[1], (1 + 2 + 3 + 5) / 4.0);
}

TEST(ScatteredLoader, CellDataOnlyIsTheDefault) {
  const auto dir = test::scratchDir();
  // No point data at all: the first cell array is the field.
  std::string text = vtuText(fiveTets(), dataArray("Float64", "q", 1, "1 1 1 1 1"));
  const auto from = text.find("<PointData"), to = text.find("</PointData>") + 12;
  text.erase(from, to - from);
  const ScatteredData d = loadScatteredData(writeFile(dir / "q.vtu", text));
  EXPECT_EQ(d.fieldName, "q");
  EXPECT_EQ(d.fieldAssociation, "cell data averaged to points");
  for (double v : d.values) EXPECT_DOUBLE_EQ(v, 1.0);
}

TEST(ScatteredLoader, FieldErrors) {
  const auto dir = test::scratchDir();
  const std::string cellData = dataArray("Int16", "label", 1, "1 2 3 4 5");
  const auto path = writeFile(dir / "c.vtu", vtuText(fiveTets(), cellData));
  ScatteredLoadOptions options;
  options.field.name = "nope";
  expectError([&] { loadScatteredData(path, options); },
              {path, "'nope'", "point data: 'temp', 'vec' (3 components)", "cell data: 'label'"});
  options.field.name = "vec";
  expectError([&] { loadScatteredData(path, options); },
              {path, "'vec'", "3 components", "--component", "'temp'"});
}

TEST(ScatteredLoader, ComponentAndMagnitudeOfAVectorArray) {
  const auto dir = test::scratchDir();
  // 'vec' holds each corner's coordinates.
  const auto path = writeFile(dir / "v.vtu", vtuText(fiveTets()));
  ScatteredLoadOptions options;
  options.field.name = "vec";
  options.field.component = 1;
  const ScatteredData y = loadScatteredData(path, options);
  EXPECT_EQ(y.fieldName, "vec_1");
  EXPECT_EQ(y.inputBytes, 8 * 3 * 8);
  for (size_t i = 0; i < y.values.size(); ++i) EXPECT_EQ(y.values[i], y.points[i][1]) << i;
  options.field.component = FieldSelection::kMagnitude;
  const ScatteredData m = loadScatteredData(path, options);
  EXPECT_EQ(m.fieldName, "vec_magnitude");
  for (size_t i = 0; i < m.values.size(); ++i)
    EXPECT_DOUBLE_EQ(m.values[i], m.points[i].norm()) << i;
  options.field.component = 3;
  expectError([&] { loadScatteredData(path, options); }, {path, "--component 3", "0..2"});
}

TEST(ScatteredLoader, AssociationPicksPointsOrCells) {
  const auto dir = test::scratchDir();
  const std::string cellData = dataArray("Int16", "label", 1, "1 2 3 4 5");
  const auto path = writeFile(dir / "c.vtu", vtuText(fiveTets(), cellData));
  ScatteredLoadOptions options;
  options.field.association = FieldAssociation::kCells;
  const ScatteredData d = loadScatteredData(path, options);
  EXPECT_EQ(d.fieldName, "label");
  EXPECT_EQ(d.fieldAssociation, "cell data averaged to points");
  options.field.name = "label";
  options.field.association = FieldAssociation::kPoints;
  expectError([&] { loadScatteredData(path, options); },
              {path, "no point data array named 'label'", "--association cell"});
}

TEST(ScatteredLoader, NoArraysIsAnError) {
  const auto dir = test::scratchDir();
  std::string text = vtuText(fiveTets());
  const auto from = text.find("<PointData"), to = text.find("</PointData>") + 12;
  text.erase(from, to - from);
  const auto path = writeFile(dir / "bare.vtu", text);
  expectError([&] { loadScatteredData(path); }, {path, "no point-data or cell-data arrays"});
}

TEST(ScatteredLoader, BrokenAndEmptyFiles) {
  const auto dir = test::scratchDir();
  const auto empty = writeFile(dir / "empty.vtu", "");
  expectError([&] { loadScatteredData(empty); }, {"cannot read " + empty, "the file is empty"});
  const auto junk = writeFile(dir / "junk.vtu", "<VTKFile type=\"Unstr");
  expectError([&] { loadScatteredData(junk); }, {"cannot read " + junk});
  // An image-data file under a .vtu name: VTK's own message.
  const auto wrong = writeFile(dir / "wrong.vtu",
                               "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" "
                               "version=\"0.1\"><ImageData WholeExtent=\"0 1 0 1 0 1\" "
                               "Origin=\"0 0 0\" Spacing=\"1 1 1\"></ImageData></VTKFile>\n");
  expectError([&] { loadScatteredData(wrong); }, {"cannot read " + wrong});
  const auto noPoints =
      writeFile(dir / "nopoints.vtp",
                "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\">"
                "<PolyData><Piece NumberOfPoints=\"0\"><Points>" +
                    dataArray("Float32", "", 3, "") + "</Points></Piece></PolyData></VTKFile>\n");
  expectError([&] { loadScatteredData(noPoints); }, {noPoints, "no points"});
}

TEST(ScatteredLoader, MissingFileAndUnknownExtension) {
  const auto dir = test::scratchDir();
  const auto missing = (dir / "none.vtu").string();
  expectError([&] { loadScatteredData(missing); }, {"cannot open " + missing, "No such file"});
  const auto folder = dir / "d.csv";
  std::filesystem::create_directories(folder);
  expectError([&] { loadScatteredData(folder.string()); }, {folder.string(), "directory"});
  const auto other = writeFile(dir / "m.obj", "v 0 0 0\n");
  expectError([&] { loadScatteredData(other); }, {other, "'.obj'", ".vtu", ".vts", ".vtp", ".csv"});
  EXPECT_FALSE(isScatteredInput(other));
  EXPECT_FALSE(isScatteredInput("volume.nrrd"));
  EXPECT_FALSE(isScatteredInput("fuel_64x64x64_uint8.raw"));
  EXPECT_TRUE(isScatteredInput("POINTS.CSV"));
  EXPECT_TRUE(isScatteredInput("a.xyz"));
  EXPECT_FALSE(isScatteredInput(missing + ".vtk"));  // unreadable: the volume loader says why
}

// ---- VTK XML structured grid and polydata -----------------------------------------------------

TEST(ScatteredLoader, VtsCurvilinearGrid) {
  const auto dir = test::scratchDir();
  // The cube sheared along x (volume still 1): x += z / 2.
  std::ostringstream points;
  for (int n = 0; n < 8; ++n)
    points << corner(n).x() + 0.5 * corner(n).z() << ' ' << corner(n).y() << ' ' << corner(n).z()
           << ' ';
  const std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"StructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "<StructuredGrid WholeExtent=\"0 1 0 1 0 1\">\n<Piece Extent=\"0 1 0 1 0 1\">\n"
      "<PointData>" +
      dataArray("Float64", "p", 1, cornerValueText()) + "</PointData>\n<Points>" +
      dataArray("Float32", "", 3, points.str()) +
      "</Points>\n</Piece>\n</StructuredGrid>\n</VTKFile>\n";
  const auto path = writeFile(dir / "g.vts", text);
  EXPECT_TRUE(isScatteredInput(path));
  const ScatteredData d = loadScatteredData(path);
  EXPECT_EQ(d.kind, "curvilinear grid");
  EXPECT_EQ(d.fieldName, "p");
  EXPECT_EQ(d.sampleType, "float64");
  EXPECT_EQ(d.inputCells, 1);
  ASSERT_EQ(d.pointCount(), 8);
  for (int n = 0; n < 8; ++n) {
    EXPECT_DOUBLE_EQ(d.points[n].x(), corner(n).x() + 0.5 * corner(n).z());
    EXPECT_EQ(d.values[n], cornerValue(n));
  }
  EXPECT_EQ(d.tets.size(), 5u);
  EXPECT_NEAR(totalVolume(d), 1.0, 1e-6);
}

TEST(ScatteredLoader, VtpPointsIgnoreTheirPolygons) {
  const auto dir = test::scratchDir();
  const std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n"
      "<Piece NumberOfPoints=\"5\" NumberOfPolys=\"1\">\n"
      "<PointData>" +
      dataArray("Int32", "id", 1, "10 11 12 13 14") + "</PointData>\n<Points>" +
      dataArray("Float64", "", 3, "0 0 0  2 0 0  0 3 0  0 0 4  1 1 1") + "</Points>\n<Polys>" +
      dataArray("Int32", "connectivity", 1, "0 1 2") + dataArray("Int32", "offsets", 1, "3") +
      "</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  const auto path = writeFile(dir / "p.vtp", text);
  const ScatteredData d = loadScatteredData(path);
  EXPECT_EQ(d.kind, "point cloud");
  EXPECT_TRUE(d.tets.empty());
  EXPECT_EQ(d.inputCells, 0);
  EXPECT_EQ(d.sampleType, "int32");
  ASSERT_EQ(d.pointCount(), 5);
  EXPECT_EQ(d.points[3], Vec3d(0, 0, 4));
  EXPECT_EQ(d.values, (std::vector<double>{10, 11, 12, 13, 14}));
}

// ---- legacy VTK --------------------------------------------------------------------------------

std::string legacyUnstructured() {
  std::ostringstream s;
  s << "# vtk DataFile Version 3.0\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 float\n"
    << cornerText() << "CELLS 5 25\n";
  for (const auto& t : kFiveTets)
    s << "4 " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
  s << "CELL_TYPES 5\n10\n10\n10\n10\n10\n"
    << "POINT_DATA 8\nSCALARS a float 1\nLOOKUP_TABLE default\n"
    << cornerValueText() << '\n'
    << "SCALARS b double 1\nLOOKUP_TABLE default\n8 7 6 5 4 3 2 1\n";
  return s.str();
}

TEST(ScatteredLoader, LegacyUnstructuredGrid) {
  const auto dir = test::scratchDir();
  const auto path = writeFile(dir / "u.vtk", legacyUnstructured());
  EXPECT_TRUE(isScatteredInput(path));
  const ScatteredData d = loadScatteredData(path);
  expectCornerPointsAndValues(d);
  EXPECT_EQ(d.kind, "tetrahedral mesh");
  EXPECT_EQ(d.fieldName, "a");
  EXPECT_EQ(d.tets.size(), 5u);
  // The second SCALARS block is read too.
  ScatteredLoadOptions options;
  options.field.name = "b";
  const ScatteredData b = loadScatteredData(path, options);
  EXPECT_EQ(b.fieldName, "b");
  EXPECT_EQ(b.sampleType, "float64");
  EXPECT_EQ(b.values, (std::vector<double>{8, 7, 6, 5, 4, 3, 2, 1}));
}

TEST(ScatteredLoader, LegacyDatasetTypeDecides) {
  const auto dir = test::scratchDir();
  const auto points = writeFile(
      dir / "sp.vtk",
      "# vtk DataFile Version 3.0\nvolume\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n"
      "ORIGIN 0 0 0\nSPACING 1 1 1\nPOINT_DATA 8\nSCALARS s float 1\nLOOKUP_TABLE default\n"
      "0 1 2 3 4 5 6 7\n");
  EXPECT_FALSE(isScatteredInput(points));
  expectError([&] { loadScatteredData(points); }, {points, "STRUCTURED_POINTS", "volume"});
  const auto field =
      writeFile(dir / "f.vtk", "# vtk DataFile Version 3.0\nf\nASCII\nDATASET FIELD\n");
  EXPECT_FALSE(isScatteredInput(field));
  expectError([&] { loadScatteredData(field); }, {field, "DATASET FIELD", "UNSTRUCTURED_GRID"});
  // A rectilinear grid: its voxels are split into tetrahedra, like a curvilinear grid's cells.
  const auto rect = writeFile(dir / "r.vtk",
                              "# vtk DataFile Version 3.0\nr\nASCII\nDATASET RECTILINEAR_GRID\n"
                              "DIMENSIONS 2 2 3\nX_COORDINATES 2 float\n0 1\n"
                              "Y_COORDINATES 2 float\n0 2\nZ_COORDINATES 3 float\n0 1 5\n"
                              "POINT_DATA 12\nSCALARS t float 1\nLOOKUP_TABLE default\n"
                              "0 1 2 3 4 5 6 7 8 9 10 11\n");
  EXPECT_TRUE(isScatteredInput(rect));
  const ScatteredData r = loadScatteredData(rect);
  EXPECT_EQ(r.kind, "rectilinear grid");
  EXPECT_EQ(r.pointCount(), 12);
  EXPECT_EQ(r.inputCells, 2);
  EXPECT_EQ(r.boxMax(), Vec3d(1, 2, 5));
  EXPECT_GE(r.tets.size(), 10u);
  const auto notVtk = writeFile(dir / "n.vtk", "hello\n");
  EXPECT_FALSE(isScatteredInput(notVtk));
  expectError([&] { loadScatteredData(notVtk); }, {"cannot read " + notVtk, "legacy VTK"});

  // A structured grid and polydata in legacy form; lower-case keywords as VTK allows.
  std::ostringstream sg;
  sg << "# vtk DataFile Version 3.0\ngrid\nASCII\ndataset structured_grid\nDIMENSIONS 2 2 2\n"
     << "POINTS 8 float\n"
     << cornerText() << "POINT_DATA 8\nSCALARS s float 1\n"
     << "LOOKUP_TABLE default\n"
     << cornerValueText() << '\n';
  const auto grid = writeFile(dir / "sg.vtk", sg.str());
  EXPECT_TRUE(isScatteredInput(grid));
  const ScatteredData g = loadScatteredData(grid);
  EXPECT_EQ(g.kind, "curvilinear grid");
  expectCornerPointsAndValues(g);
  EXPECT_NEAR(totalVolume(g), 1.0, 1e-6);

  std::ostringstream pd;
  pd << "# vtk DataFile Version 3.0\ncloud\nASCII\nDATASET POLYDATA\nPOINTS 8 float\n"
     << cornerText() << "VERTICES 1 2\n1 0\nPOINT_DATA 8\nSCALARS s float 1\n"
     << "LOOKUP_TABLE default\n"
     << cornerValueText() << '\n';
  const auto cloud = writeFile(dir / "pd.vtk", pd.str());
  EXPECT_TRUE(isScatteredInput(cloud));
  const ScatteredData c = loadScatteredData(cloud);
  EXPECT_EQ(c.kind, "point cloud");
  expectCornerPointsAndValues(c);
}

TEST(ScatteredLoader, LegacyReadErrorsComeFromVtk) {
  const auto dir = test::scratchDir();
  std::string text = legacyUnstructured();
  text = text.substr(0, text.find("CELLS")) + "CELLS 5 25\n4 0 1\n";  // cut short
  const auto path = writeFile(dir / "cut.vtk", text);
  expectError([&] { loadScatteredData(path); }, {"cannot read " + path, "legacy VTK"});
}

// Found by fuzzing: VTK's legacy reader matches keywords by prefix, so "CELLSxyz0" is a CELLS
// line whose counts it reads from the lines after (and then dereferenced null).
TEST(ScatteredLoader, LegacyKeywordsAreMatchedByPrefixAsVtkDoes) {
  const auto dir = test::scratchDir();
  std::string text = legacyUnstructured();
  text = text.substr(0, text.find("CELLS")) + "CELLSxyz0\n4 0 1 2 3\n4 1 2 3 4\n";
  const auto path = writeFile(dir / "prefix.vtk", text);
  expectError([&] { loadScatteredData(path); }, {"cannot read " + path, "CELLS line has"});
}

// Found by fuzzing: a keyword inside a block of numbers, which VTK's reader then acts on.
TEST(ScatteredLoader, LegacyWordsInsideNumberBlocksAreErrors) {
  const auto dir = test::scratchDir();
  const auto path = writeFile(dir / "word.vtk",
                              "# vtk DataFile Version 3.0\nw\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                              "POINTS 4 float\n0 0 CELLS 2 0\n4 0 1 2 3\n");
  expectError([&] { loadScatteredData(path); }, {"cannot read " + path, "'CELLS' where value 3"});
}

// A dataset's FIELD block that VTK's reader cannot read ended the program (it sets the field data
// without checking it); such blocks are refused, wherever they stand among the geometry blocks.
TEST(ScatteredLoader, LegacyDatasetFieldBlocksAreChecked) {
  const auto dir = test::scratchDir();
  std::string text = legacyUnstructured();
  const std::string field = "FIELD FieldData 1\nTIME 1 1 double\n1.5\n";
  text.insert(text.find("CELL_TYPES"), field);
  EXPECT_EQ(loadScatteredData(writeFile(dir / "f.vtk", text)).pointCount(), 8);
  for (const auto& [bad, expected] : std::vector<std::pair<std::string, std::string>>{
           {"TIME 1 1 strng", "FIELD array 'TIME'"}, {"TIME 3 1 double", "where value 2"}}) {
    std::string broken = text;
    broken.replace(broken.find("TIME 1 1 double"), 15, bad);
    const auto path = writeFile(dir / "f.vtk", broken);
    expectError([&] { loadScatteredData(path); }, {"cannot read " + path, expected});
  }
  const auto rect = writeFile(dir / "r.vtk",
                              "# vtk DataFile Version 3.0\nr\nASCII\nDATASET RECTILINEAR_GRID\n"
                              "DIMENSIONS 2 2 3\nX_COORDINATES 2 float\n0 1\n"
                              "Y_COORDINATES 2 float\n0 2\nFIELD FieldData 1\nT 1 1 strng\nx\n"
                              "Z_COORDINATES 3 float\n0 1 5\n"
                              "POINT_DATA 12\nSCALARS t float 1\nLOOKUP_TABLE default\n"
                              "0 1 2 3 4 5 6 7 8 9 10 11\n");
  expectError([&] { loadScatteredData(rect); }, {"cannot read " + rect, "FIELD"});
}

// The cells of a CELLS (or poly data's POLYGONS) block must fill it exactly: VTK's reader walks
// the block by the cells' point counts and read past its end where they added up to more (found
// by a valgrind replay of a fuzzing corpus).
TEST(ScatteredLoader, LegacyCellCountsMustFillTheirBlock) {
  const auto dir = test::scratchDir();
  const std::string good = legacyUnstructured();
  for (const auto& [from, to, expected] : std::vector<std::array<std::string, 3>>{
           {"CELLS 5 25\n4", "CELLS 5 25\n9", "CELLS block's 25 integers end after cell 4 of 5"},
           {"CELLS 5 25\n4", "CELLS 5 25\n29", "cell 1 of CELLS declares 29 points"},
           {"CELLS 5 25", "CELLS 5 26", "5 cells of CELLS take 25 of its 26 integers"},
           {"CELLS 5 25\n4 ", "CELLS 5 25\n4.5 ", "'4.5' where integer 1 of 25 belongs"},
           {"CELLS 5 25\n4", "CELLS 5 25\n-4", "declares -4 points"}}) {
    std::string broken = good;
    broken.replace(broken.find(from), from.size(), to);
    const auto path = writeFile(dir / "c.vtk", broken);
    expectError([&] { loadScatteredData(path); }, {"cannot read " + path, expected});
  }
  const std::string head =
      "# vtk DataFile Version 3.0\np\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n"
      "0 0 0 1 0 0 0 1 0 0 0 1\n";
  const auto poly = writeFile(dir / "p.vtk", head + "POLYGONS 2 8\n3 0 1 2\n5 1 2 3\n");
  expectError([&] { loadScatteredData(poly); },
              {"cannot read " + poly, "cell 2 of POLYGONS declares 5 points"});
}

// Two cells on five points (connectivity 0 1 2 3 | 1 2 3 4) with the given offsets and types.
std::string twoCellGrid(const std::filesystem::path& path, const std::string& offsets,
                        const std::string& types) {
  return writeFile(
      path,
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"5\" "
      "NumberOfCells=\"2\">\n<PointData Scalars=\"f\">\n<DataArray type=\"Float32\" "
      "Name=\"f\" format=\"ascii\">1 2 3 4 5</DataArray>\n</PointData>\n<Points>\n"
      "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 "
      "1 0 0 0 1 1 1 1</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" "
      "Name=\"connectivity\" format=\"ascii\">0 1 2 3 1 2 3 4</DataArray>\n<DataArray "
      "type=\"Int64\" Name=\"offsets\" format=\"ascii\">" +
          offsets + "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" +
          types + "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
}

TEST(ScatteredLoader, TetrahedronWithoutFourPointsIsAnError) {
  // Found by fuzzing: VTK's XML reader accepts a cell of type 10 (tetrahedron) with 2 points.
  const auto path = twoCellGrid(test::scratchDir() / "two.vtu", "2 8", "10 10");
  expectError([&] { loadScatteredData(path); }, {path, "has 2 points, which no cell of its type"});
}

TEST(ScatteredLoader, CellWithThePointsOfNoCellOfItsTypeIsAnError) {
  // Found by fuzzing: a Lagrange tetrahedron (type 71) of 1 point crashed VTK's tetrahedralizer.
  const auto dir = test::scratchDir();
  const auto one = twoCellGrid(dir / "lagrange1.vtu", "1 8", "71 10");
  expectError([&] { loadScatteredData(one); },
              {one, "cell 0 (VTK cell type 71) has 1 points, which no cell of its type has"});
  const auto pyramid = twoCellGrid(dir / "pyramid4.vtu", "4 8", "14 10");
  expectError([&] { loadScatteredData(pyramid); }, {pyramid, "cell 0 (VTK cell type 14) has 4"});
  // A first-order Lagrange tetrahedron has the 4 points of a linear one: it loads.
  const ScatteredData ok = loadScatteredData(twoCellGrid(dir / "lagrange4.vtu", "4 8", "71 10"));
  EXPECT_EQ(ok.inputCells, 2);
}

template <typename T>
void appendBigEndian(std::string& out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (std::endian::native != std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

TEST(ScatteredLoader, NanValueIsAnError) {
  const auto dir = test::scratchDir();
  // VTK's ASCII readers do not parse "nan"; legacy binary (big-endian) carries it.
  std::string text = "# vtk DataFile Version 3.0\nnan\nBINARY\nDATASET POLYDATA\nPOINTS 8 float\n";
  for (int n = 0; n < 8; ++n)
    for (int a = 0; a < 3; ++a) appendBigEndian(text, static_cast<float>(corner(n)[a]));
  text += "\nPOINT_DATA 8\nSCALARS s float 1\nLOOKUP_TABLE default\n";
  for (int n = 0; n < 8; ++n)
    appendBigEndian(text, n == 5 ? std::numeric_limits<float>::quiet_NaN() : 1.0f);
  text += "\n";
  const auto path = writeFile(dir / "nan.vtk", text);
  expectError([&] { loadScatteredData(path); }, {path, "point 5", "finite"});
}

TEST(ScatteredLoader, FlatBoxIsAnError) {
  const auto dir = test::scratchDir();
  const auto path = writeFile(dir / "flat.csv", "0 0 0 1\n1 0 0 2\n0 1 0 3\n");
  expectError([&] { loadScatteredData(path); }, {path, "no extent along z"});
}

// ---- text ----------------------------------------------------------------------------------

TEST(ScatteredLoader, CsvWithHeader) {
  const auto dir = test::scratchDir();
  const auto path = writeFile(
      dir / "p.csv", "# probes\nx,y,z,pressure\n0,0,0,1.5\n1,0,0,2\n\n0,1,0,-3e2\n0,0,1,4\n");
  EXPECT_TRUE(isScatteredInput(path));
  const ScatteredData d = loadScatteredData(path);
  EXPECT_EQ(d.fieldName, "pressure");
  EXPECT_EQ(d.kind, "point cloud");
  EXPECT_EQ(d.fieldAssociation, "point data");
  EXPECT_EQ(d.sampleType, "text");
  EXPECT_EQ(d.inputBytes, 4 * 8);
  EXPECT_EQ(d.inputCells, 0);
  EXPECT_TRUE(d.tets.empty());
  ASSERT_EQ(d.pointCount(), 4);
  EXPECT_EQ(d.points[2], Vec3d(0, 1, 0));
  EXPECT_EQ(d.values, (std::vector<double>{1.5, 2, -300, 4}));

  ScatteredLoadOptions options;
  options.field.name = "pressure";
  EXPECT_EQ(loadScatteredData(path, options).pointCount(), 4);
  options.field.name = "density";
  expectError([&] { loadScatteredData(path, options); }, {path, "'density'", "'pressure'"});
}

TEST(ScatteredLoader, TextWithoutHeader) {
  const auto dir = test::scratchDir();
  const auto txt = writeFile(dir / "p.txt", "0 0 0 1\n1\t0 0 2\r\n0 1 0 3\n0 0 1 4\n");
  const ScatteredData d = loadScatteredData(txt);
  EXPECT_EQ(d.fieldName, "value");
  EXPECT_EQ(d.values, (std::vector<double>{1, 2, 3, 4}));
  const auto xyz = writeFile(dir / "p.xyz", "x y z\n0 0 0 1\n1 0 0 2\n0 1 0 3\n0 0 1 4\n");
  EXPECT_EQ(loadScatteredData(xyz).fieldName, "value");  // a header of three names
  // A last line without its line break may be cut off ("0 0 1 4" from "0 0 1 45.5").
  const auto cut = writeFile(dir / "cut.txt", "0 0 0 1\n1 0 0 2\n0 1 0 3\n0 0 1 4");
  test::expectError([&] { loadScatteredData(cut); }, {cut, "line 4", "line break"});
}

TEST(ScatteredLoader, TextErrorsNameTheLine) {
  const auto dir = test::scratchDir();
  const auto bad = writeFile(dir / "bad.csv", "x,y,z,v\n0,0,0,1\n1,0,0\n");
  expectError([&] { loadScatteredData(bad); }, {bad + " line 3", "four numbers"});
  const auto word = writeFile(dir / "word.csv", "0,0,0,1\n1,0,0,abc\n");
  expectError([&] { loadScatteredData(word); }, {word + " line 2"});
  const auto nan = writeFile(dir / "nan.csv", "0,0,0,1\n# c\n1,0,0,nan\n");
  expectError([&] { loadScatteredData(nan); }, {nan + " line 3", "finite"});
  const auto empty = writeFile(dir / "empty.csv", "");
  expectError([&] { loadScatteredData(empty); }, {empty, "the file is empty"});
  const auto headerOnly = writeFile(dir / "h.csv", "x,y,z,v\n# nothing\n");
  expectError([&] { loadScatteredData(headerOnly); }, {headerOnly, "no points"});
}

// ---- the shared real meshes ------------------------------------------------------------------

TEST(ScatteredLoaderRealData, BluntFin) {
  const auto path = test::dataFile("bluntfin_tets.vtu");
  if (path.empty()) GTEST_SKIP() << "bluntfin_tets.vtu not in " << test::dataDir();
  const ScatteredData d = loadScatteredData(path.string());
  EXPECT_EQ(d.pointCount(), 40960);
  EXPECT_EQ(d.tets.size(), 187395u);
  EXPECT_EQ(d.inputCells, 187395);
  EXPECT_EQ(d.kind, "tetrahedral mesh");
  EXPECT_EQ(d.fieldName, "Density");  // the active scalars
  EXPECT_EQ(d.sampleType, "float32");
  EXPECT_EQ(d.inputBytes, 40960 * 4);
  const auto [lo, hi] = std::minmax_element(d.values.begin(), d.values.end());
  EXPECT_NEAR(*lo, 0.1926, 1e-4);
  EXPECT_NEAR(*hi, 4.9775, 1e-4);
  std::set<std::int64_t> used;
  for (const auto& t : d.tets) used.insert(t.begin(), t.end());
  EXPECT_EQ(static_cast<std::int64_t>(used.size()), d.pointCount());

  ScatteredLoadOptions options;
  options.field.name = "Pressure";
  const ScatteredData p = loadScatteredData(path.string(), options);
  const auto [plo, phi] = std::minmax_element(p.values.begin(), p.values.end());
  EXPECT_NEAR(*plo, 0.2595, 1e-3);
  EXPECT_NEAR(*phi, 10.0127, 1e-3);
  options.field.name = "Momentum";
  expectError([&] { loadScatteredData(path.string(), options); },
              {"'Momentum'", "3 components", "'Temperature'"});
}

TEST(ScatteredLoaderRealData, Spx) {
  const auto path = test::dataFile("spx.vtk");
  if (path.empty()) GTEST_SKIP() << "spx.vtk not in " << test::dataDir();
  EXPECT_TRUE(isScatteredInput(path.string()));
  const ScatteredData d = loadScatteredData(path.string());
  EXPECT_EQ(d.pointCount(), 2896);
  EXPECT_EQ(d.tets.size(), 12936u);
  EXPECT_EQ(d.kind, "tetrahedral mesh");
  EXPECT_EQ(d.fieldName, "scalars");
  const auto [lo, hi] = std::minmax_element(d.values.begin(), d.values.end());
  EXPECT_GE(*lo, 0.0);
  EXPECT_NEAR(*hi, 2.254, 1e-3);
}

}  // namespace
}  // namespace mfadvr
