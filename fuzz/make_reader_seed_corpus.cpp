// Writes seed inputs for the reader fuzzers: a small valid file of every kind, prefixed with
// the byte that selects its kind (fuzz_file_loaders.cpp, fuzz_declared_size.cpp).
// Usage: make_reader_seed_corpus LOADERS_DIR HEADERS_DIR

#include <netcdf.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "MedicalTestFiles.h"

namespace {

std::string values(int count, const char* separator) {
  std::ostringstream s;
  for (int n = 0; n < count; ++n) s << (n * 37 % 101) * 0.5 << separator;
  return s.str();
}

std::string floats(int count) {
  std::string out;
  for (int n = 0; n < count; ++n) {
    const float v = float(n % 13) - 4.0f;
    out.append(reinterpret_cast<const char*>(&v), 4);
  }
  return out;
}

void write(const std::filesystem::path& dir, const std::string& name, char kind,
           const std::string& bytes) {
  std::ofstream(dir / name, std::ios::binary) << kind << bytes;
}

// A small CF NetCDF file (classic format): v(time, z, y, x) of 3 steps of 4 x 3 x 2 floats,
// with coordinate variables and a fill value, written by libnetcdf to `scratch` and read back.
std::string netcdfBytes(const std::filesystem::path& scratch) {
  int nc = -1, dims[4], coords[4], var = -1;
  if (nc_create(scratch.c_str(), NC_CLOBBER, &nc) != NC_NOERR) return {};
  const char* names[4] = {"time", "z", "y", "x"};
  const size_t sizes[4] = {NC_UNLIMITED, 2, 3, 4};
  for (int d = 0; d < 4; ++d) {
    nc_def_dim(nc, names[d], sizes[d], &dims[d]);
    nc_def_var(nc, names[d], NC_DOUBLE, 1, &dims[d], &coords[d]);
  }
  nc_put_att_text(nc, coords[0], "units", 11, "s since 0 0");
  nc_def_var(nc, "v", NC_FLOAT, 4, dims, &var);
  const float fill = -1.0f;
  nc_put_att_float(nc, var, "_FillValue", NC_FLOAT, 1, &fill);
  nc_enddef(nc);
  for (int d = 1; d < 4; ++d) {
    const double c[4] = {0.0, 0.5, 1.0, 1.5};
    nc_put_var_double(nc, coords[d], c);
  }
  for (size_t s = 0; s < 3; ++s) {
    const double t = 0.25 * double(s);
    nc_put_var1_double(nc, coords[0], &s, &t);
    float v[24];
    for (int i = 0; i < 24; ++i) v[i] = float(i % 7) + float(s);
    const size_t start[4] = {s, 0, 0, 0}, count[4] = {1, 2, 3, 4};
    nc_put_vara_float(nc, var, start, count, v);
  }
  nc_close(nc);
  std::ifstream in(scratch, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  std::filesystem::remove(scratch);
  return bytes.str();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  const std::filesystem::path loaders = argv[1], headers = argv[2];
  std::filesystem::create_directories(loaders);
  std::filesystem::create_directories(headers);
  const int n = 10 * 4 * 3;  // NRRD and VTK volumes: 10 x 4 x 3 samples
  const std::string nrrd =
      "NRRD0004\ntype: float\ndimension: 3\nsizes: 10 4 3\nencoding: raw\nendian: little\n"
      "spacings: 1 0.5 2\n\n" +
      floats(n);
  const std::string nrrdGzip =
      "NRRD0005\ntype: float\ndimension: 3\nsizes: 10 4 3\nencoding: gzip\nendian: little\n\n" +
      mfadvr::test::gzipBytes(floats(n));
  const std::string nrrdAscii =
      "NRRD0004\ntype: double\ndimension: 3\nsizes: 10 4 3\nencoding: ascii\n\n" + values(n, "\n");
  const std::string mha =
      "ObjectType = Image\nNDims = 3\nDimSize = 10 4 3\nElementSpacing = 1 1 1\n"
      "ElementType = MET_FLOAT\nElementDataFile = LOCAL\n" +
      floats(n);
  const std::string vtk =
      "# vtk DataFile Version 3.0\nseed\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 10 4 3\n"
      "SPACING 1 1 1\nORIGIN 0 0 0\nPOINT_DATA 120\nSCALARS density float 1\n"
      "LOOKUP_TABLE default\n" +
      values(n, " ") + "\n";
  const std::string vti =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n<ImageData WholeExtent=\"0 9 0 3 0 2\" Origin=\"0 0 0\" "
      "Spacing=\"1 1 1\">\n<Piece Extent=\"0 9 0 3 0 2\">\n<PointData Scalars=\"d\">\n"
      "<DataArray type=\"Float32\" Name=\"d\" format=\"ascii\">" +
      values(n, " ") + "</DataArray>\n</PointData>\n</Piece>\n</ImageData>\n</VTKFile>\n";
  const std::string nifti = mfadvr::test::niftiBytes(mfadvr::test::NiftiHeader{});
  // Two tetrahedra sharing a face.
  const std::string vtu =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
      "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"5\" "
      "NumberOfCells=\"2\">\n<PointData Scalars=\"f\">\n<DataArray type=\"Float32\" Name=\"f\" "
      "format=\"ascii\">1 2 3 4 5</DataArray>\n</PointData>\n<Points>\n<DataArray "
      "type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0 1 1 1 1"
      "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
      "format=\"ascii\">0 1 2 3 1 2 3 4</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
      "format=\"ascii\">4 8</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
      "format=\"ascii\">10 10</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  const std::string legacyMesh =
      "# vtk DataFile Version 3.0\nseed\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n"
      "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\nCELLS 2 10\n4 0 1 2 3\n4 1 2 3 4\nCELL_TYPES 2\n10\n10\n"
      "POINT_DATA 5\nSCALARS f float 1\nLOOKUP_TABLE default\n1 2 3 4 5\n";
  const std::string csv = "x,y,z,v\n0,0,0,1\n1,0,0,2\n0,1,0,3\n0,0,1,4\n1,1,1,5\n";

  write(loaders, "nrrd-raw", 0, nrrd);
  write(loaders, "nrrd-gzip", 0, nrrdGzip);
  write(loaders, "nrrd-ascii", 0, nrrdAscii);
  write(loaders, "mha", 1, mha);
  write(loaders, "vtk", 2, vtk);
  write(loaders, "vti", 3, vti);
  write(loaders, "nii", 4, nifti);
  write(loaders, "nii-gz", 5, mfadvr::test::gzipBytes(nifti));
  write(loaders, "dicom", 6, mfadvr::test::dicomSlice(0));
  write(loaders, "raw", 7, std::string(24, '\7'));
  write(loaders, "vtu", 8, vtu);
  write(loaders, "legacy-mesh", 9, legacyMesh);
  write(loaders, "csv", 10, csv);
  write(loaders, "netcdf", 11, netcdfBytes(loaders / "scratch.nc"));
  // Time series in one file: a NRRD with a time axis last, a NIfTI image of two time points.
  write(loaders, "nrrd-time", 0,
        "NRRD0004\ntype: float\ndimension: 4\nsizes: 10 4 3 2\nkinds: space space space time\n"
        "encoding: raw\nendian: little\n\n" +
            floats(2 * n));
  mfadvr::test::NiftiHeader twoTimes;
  twoTimes.timePoints = 2;
  write(loaders, "nii-time", 4, mfadvr::test::niftiBytes(twoTimes));

  write(headers, "nrrd", 0, nrrd);
  write(headers, "nrrd-ascii", 0, nrrdAscii);
  write(headers, "mha", 1, mha);
  write(headers, "vtk", 2, vtk);
  write(headers, "vtk-mesh", 2, legacyMesh);
  write(headers, "vti", 3, vti);
  write(headers, "vtu", 3, vtu);
  write(headers, "nii", 4, nifti);
  write(headers, "dicom", 5, mfadvr::test::dicomSlice(1));
  return 0;
}
