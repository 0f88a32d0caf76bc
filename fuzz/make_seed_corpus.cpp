// Writes seed inputs for the fuzzers: small valid models (uniform and non-uniform knots, several
// degrees, one with a domain mask, one with a mesh boundary, a multi-block file, a time-varying
// model), time-series collections (.pvd and .series), point lists ("x y z" and "x y z v") and
// 2-D transfer functions (JSON boxes), so
// that mutations start from the interesting structure.
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/analytic/BuiltinFunction.h"
#include "core/analytic/BuiltinSeries.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/StructuredEncoder.h"
#include "core/encode/TimeSeriesEncoder.h"
#include "core/mask/DomainBoundary.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ControlCoding.h"
#include "core/model/ModelFile.h"

int main(int argc, char** argv) {
  if (argc != 5) return 2;
  const std::filesystem::path models = argv[1], points = argv[2], tf2d = argv[3],
                              collections = argv[4];
  std::filesystem::create_directories(collections);
  std::ofstream(collections / "run.pvd")
      << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n"
         "<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"a_000.vti\"/>\n"
         "<DataSet file=\"b/a_001.vti\" timestep=\"0.5e1\"/>\n</Collection>\n</VTKFile>\n";
  std::ofstream(collections / "run.series")
      << R"({"file-series-version": "1.0", "files": [{"name": "a_000.nrrd", "time": 0},)"
      << R"( {"name": "/data/a_001.nrrd", "time": 2.5}]})";
  std::filesystem::create_directories(models);
  std::filesystem::create_directories(points);
  std::filesystem::create_directories(tf2d);
  std::ofstream(tf2d / "boxes.json")
      << R"({"boxes": [{"value": [0.2, 0.5], "gradient": [0, 3], "color": [1, 0.5, 0], )"
      << R"("opacity": 0.4}, {"value": [0.4, 1], "gradient": [2, 9], "opacity": 1}], )"
      << R"("size": [16, 8]})";
  std::ofstream(tf2d / "curvature.json")
      << R"({"boxes": [{"k1": [0.5, 4], "k2": [-1, 1], "color": [1, 0.5, 0], "weight": 0.7, )"
      << R"("opacity": 0.4}, {"k1": [-2, 0], "k2": [-3, -1]}], "size": [16, 8]})";
  int i = 0;
  for (mfadvr::Degree3 p : {mfadvr::Degree3{1, 1, 1}, mfadvr::Degree3{3, 2, 2}}) {
    mfadvr::StructuredFitOptions o;
    o.degree = p;
    o.controlCounts = {4, 3, 3};
    const auto m =
        mfadvr::fitStructured(mfadvr::sampleBuiltinSpec("builtin:marschner-lobb:6x5x4"), o);
    mfadvr::saveModel(m, models / ("seed" + std::to_string(i++) + ".mfa"));
  }
  for (const mfadvr::ControlCoding c : {mfadvr::ControlCoding{mfadvr::ControlCoder::kLossless, 0.0},
                                        mfadvr::ControlCoding{mfadvr::ControlCoder::kZfp, 1e-3}}) {
    // Coded control points (format version 3).
    mfadvr::StructuredFitOptions o;
    o.controlCounts = {5, 4, 4};
    const auto m = mfadvr::codeControlPoints(
        mfadvr::fitStructured(mfadvr::sampleBuiltinSpec("builtin:marschner-lobb:6x5x4"), o), c);
    mfadvr::saveModel(m, models / ("seed" + std::to_string(i++) + ".mfa"));
    // The coded section alone, in the form the fuzzer's second half reads (see
    // fuzz_model_file.cpp): a selector byte, then the payload.
    const std::string payload =
        mfadvr::encodeControlPoints(m.spline().controlPoints(), {5, 4, 4}, c);
    std::ofstream(models / ("seed-payload" + std::to_string(i++) + ".bin"), std::ios::binary)
        << static_cast<char>(c.coder == mfadvr::ControlCoder::kZfp ? 0x83 : 0x03) << payload;
  }
  {
    // A masked model: 3 x 4 x 5 = 60 nodes, so the last mask byte has padding bits.
    mfadvr::StructuredFitOptions o;
    o.degree = {2, 2, 2};
    o.controlCounts = {3, 3, 3};
    auto m = mfadvr::fitStructured(mfadvr::sampleBuiltinSpec("builtin:marschner-lobb:5x5x5"), o);
    std::vector<std::uint8_t> nodes(60);
    for (size_t n = 0; n < nodes.size(); ++n) nodes[n] = (n * 7 % 5) < 3;
    m.setMask(mfadvr::DomainMask(mfadvr::MaskKind::PointCoverage, {3, 4, 5}, nodes));
    mfadvr::saveModel(m, models / ("seed" + std::to_string(i++) + ".mfa"));
  }
  {
    // A model of a mesh with its exact boundary: one tetrahedron (4 boundary triangles).
    mfadvr::StructuredFitOptions o;
    o.degree = {1, 1, 1};
    o.controlCounts = {2, 2, 2};
    auto m = mfadvr::fitStructured(mfadvr::sampleBuiltinSpec("builtin:marschner-lobb:3x3x3"), o);
    const std::vector<mfadvr::Vec3d> points{{-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    const std::vector<mfadvr::Tetrahedron> tets{{0, 1, 2, 3}};
    m.setBoundary(std::make_shared<const mfadvr::DomainBoundary>(
        mfadvr::boundaryOfTetrahedra(points, tets)));
    mfadvr::saveModel(m, models / ("seed" + std::to_string(i++) + ".mfa"));
  }
  {
    // A multi-block model: 2 x 1 x 1 blocks with one ghost layer.
    mfadvr::EncodeOptions o;
    o.degree = {1, 1, 1};
    const auto blocks = mfadvr::encodeStructuredBlocks(
        mfadvr::sampleBuiltinSpec("builtin:marschner-lobb:5x3x3"), {2, 1, 1}, 1, o);
    mfadvr::saveBlockModels(blocks, {2, 1, 1}, models / "seed-blocks.mfa");
  }
  {
    // A time-varying model (format version 4): 4 x 3 x 3 samples at 4 steps, linear in time.
    mfadvr::EncodeOptions o;
    o.degree = {1, 1, 1};
    mfadvr::TimeSeriesOptions t;
    t.degree = 2;
    t.controlCount = 3;
    mfadvr::saveModel(mfadvr::encodeTimeSeries(
                          mfadvr::BuiltinVolumeSeries("builtin:orbiting-blobs:4x3x3x4"), o, t),
                      models / "seed-time.mfa");
  }
  std::ofstream(points / "seed.txt") << "x,y,z\n0 0 0\n1.5, -2e-3, 4\n# c\n";
  std::ofstream(points / "seed-values.csv") << "x,y,z,rho\n0,0,0,1\n1.5 -2e-3 4 -7e2\n# c\n";
  return 0;
}
