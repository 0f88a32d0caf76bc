// Writes the models and volumes the ParaView plugin tests read:
//   single.mfa, blocks.mfa   Marschner-Lobb 41^3 on [-1,1]^3, one model and 4 x 1 x 1 blocks;
//   scan-*.mfa, scan.vti     a CT-like head (the ct-head phantom mapped to 0..255, field
//                            'scalars') on a box that is not a cube, with non-unit spacing that
//                            differs per axis and an origin away from zero, as real scans are:
//                            one model (scan-1.mfa), blocks split along x, y and z
//                            (scan-x.mfa, scan-y.mfa, scan-z.mfa) and 2 x 2 x 1 (scan-xy.mfa),
//                            and the samples as VTK XML image data (scan.vti) and as a gzip
//                            uint8 NRRD file (scan.nrrd) for MFA Encode;
//   head.mfa                 the model docs/paraview.md's examples open (default encoding of
//                            builtin:ct-head:64);
//   blobs.mfa, blobs-0.3.mfa a time-varying model (builtin:orbiting-blobs:24x24x24x6, steps at
//                            t = 0, 0.2, ..., 1) and, as a 3-D model, its instant at t = 0.3
//                            (between two steps) as `mfadvr render --time 0.3` renders it;
//   blobs.pvd, blobs_N.vti   the steps of that series as a ParaView collection (MFA Encode's
//                            TimeSeries).
// Interpolating quadratic fits throughout. The scan's samples are 8-bit integers, so its models
// are coded as `mfadvr encode` codes an integer scan by default: zfp control points that round
// back to every sample (ParaView's process also holds CFITSIO, whose stream_* functions once
// took ZFP's calls: ZfpLibrary.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "GzipBytes.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/analytic/BuiltinSeries.h"
#include "core/encode/Encoder.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/TimeSeriesEncoder.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"

namespace {

mfadvr::StructuredGrid scanGrid() {
  mfadvr::StructuredGrid grid = mfadvr::sampleBuiltinSpec("builtin:ct-head:40x34x28");
  grid.spacing = mfadvr::Vec3d(0.9, 0.7, 1.3);
  grid.origin = mfadvr::Vec3d(12.0, -7.0, 30.0);
  grid.fieldName = "scalars";
  grid.source = "scan";
  // Hounsfield units -1000..1000 to the 0..255 of an 8-bit scan.
  for (float& v : grid.values)
    v = static_cast<float>(std::lround(std::clamp((v + 1000.0) * 255.0 / 2000.0, 0.0, 255.0)));
  grid.sampleType = "uint8";
  grid.inputBytes = grid.sampleCount();
  return grid;
}

void writeVti(const mfadvr::StructuredGrid& g, const std::filesystem::path& path) {
  std::ofstream out(path);
  const std::string extent = "0 " + std::to_string(g.dims[0] - 1) + " 0 " +
                             std::to_string(g.dims[1] - 1) + " 0 " + std::to_string(g.dims[2] - 1);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
         "byte_order=\"LittleEndian\">\n<ImageData WholeExtent=\""
      << extent << "\" Origin=\"" << g.origin[0] << ' ' << g.origin[1] << ' ' << g.origin[2]
      << "\" Spacing=\"" << g.spacing[0] << ' ' << g.spacing[1] << ' ' << g.spacing[2]
      << "\">\n<Piece Extent=\"" << extent << "\">\n<PointData Scalars=\"" << g.fieldName
      << "\">\n<DataArray type=\"Float32\" Name=\"" << g.fieldName << "\" format=\"ascii\">\n";
  for (size_t i = 0; i < g.values.size(); ++i)
    out << static_cast<float>(g.values[i]) << ((i + 1) % 16 ? ' ' : '\n');
  out << "\n</DataArray>\n</PointData>\n</Piece>\n</ImageData>\n</VTKFile>\n";
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// The samples rounded to uint8 in a gzip NRRD file (the encoding scanners and Slicer write)
// with the grid's placement.
void writeNrrd(const mfadvr::StructuredGrid& g, const std::filesystem::path& path) {
  std::string samples;
  for (const float v : g.values) samples.push_back(static_cast<char>(std::lround(v)));
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: " << g.dims[0] << ' ' << g.dims[1] << ' '
      << g.dims[2] << "\nspace: 3D-right-handed\nspace directions: (" << g.spacing[0] << ",0,0) (0,"
      << g.spacing[1] << ",0) (0,0," << g.spacing[2] << ")\nspace origin: (" << g.origin[0] << ','
      << g.origin[1] << ',' << g.origin[2] << ")\nencoding: gzip\n\n"
      << mfadvr::test::gzipBytes(samples);
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    const mfadvr::StructuredGrid grid = mfadvr::sampleBuiltinSpec("builtin:marschner-lobb:41");
    mfadvr::EncodeOptions options;
    options.degree = {2, 2, 2};
    mfadvr::saveModel(mfadvr::encodeStructured(grid, options), dir / "single.mfa");
    mfadvr::saveBlockModels(mfadvr::encodeStructuredBlocks(grid, {4, 1, 1}, -1, options), {4, 1, 1},
                            dir / "blocks.mfa");

    const mfadvr::StructuredGrid scan = scanGrid();
    mfadvr::EncodeOptions scanOptions = options;
    scanOptions.coding.coder = mfadvr::ControlCoder::kZfp;  // the default of integer samples
    const mfadvr::Model scanModel = mfadvr::encodeStructured(scan, scanOptions);
    if (scanModel.controlCoding().coder != mfadvr::ControlCoder::kZfp)
      throw std::runtime_error("the scan's model is not zfp-coded");
    mfadvr::saveModel(scanModel, dir / "scan-1.mfa");
    const std::pair<const char*, mfadvr::Index3> splits[] = {
        {"x", {2, 1, 1}}, {"y", {1, 2, 1}}, {"z", {1, 1, 2}}, {"xy", {2, 2, 1}}};
    for (const auto& [name, blocks] : splits)
      mfadvr::saveBlockModels(mfadvr::encodeStructuredBlocks(scan, blocks, -1, scanOptions), blocks,
                              dir / ("scan-" + std::string(name) + ".mfa"));
    writeVti(scan, dir / "scan.vti");
    writeNrrd(scan, dir / "scan.nrrd");
    // The model docs/paraview.md's example opens (`mfadvr encode builtin:ct-head:64`).
    mfadvr::saveModel(mfadvr::encodeStructured(mfadvr::sampleBuiltinSpec("builtin:ct-head:64"),
                                               mfadvr::EncodeOptions{}),
                      dir / "head.mfa");
    const mfadvr::TimeVaryingModel blobs =
        mfadvr::encodeTimeSeries(mfadvr::BuiltinVolumeSeries("builtin:orbiting-blobs:24x24x24x6"),
                                 mfadvr::EncodeOptions{}, mfadvr::TimeSeriesOptions{});
    mfadvr::saveModel(blobs, dir / "blobs.mfa");
    mfadvr::saveModel(blobs.at(0.3), dir / "blobs-0.3.mfa");
    // The same steps as a ParaView collection of image files, for MFA Encode's TimeSeries.
    const mfadvr::BuiltinVolumeSeries steps("builtin:orbiting-blobs:24x24x24x6");
    std::ofstream pvd(dir / "blobs.pvd");
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "<Collection>\n";
    for (int s = 0; s < steps.size(); ++s) {
      const std::string name = "blobs_" + std::to_string(s) + ".vti";
      writeVti(steps.load(s), dir / name);
      pvd << "<DataSet timestep=\"" << steps.time(s) << "\" file=\"" << name << "\"/>\n";
    }
    pvd << "</Collection>\n</VTKFile>\n";
    if (!pvd) throw std::runtime_error("cannot write blobs.pvd");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
