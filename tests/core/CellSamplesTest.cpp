// Samples of a mesh's linear field inside its tetrahedra (core/mesh/CellSamples.h) and fits that
// use them (encode --cell-samples).
#include "core/mesh/CellSamples.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include "TestSupport.h"
#include "core/encode/Encoder.h"
#include "core/model/Model.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

bool all(int, int, int) {
  return true;
}

// The n^3 unit cubes of TestSupport's mesh with values f at the points.
template <class F>
ScatteredData cubeData(int n, F&& f) {
  const test::TetMesh m = test::cubeMesh(n, all);
  ScatteredData d;
  d.points = m.points;
  d.tets = m.tets;
  for (const Vec3d& p : d.points) d.values.push_back(f(p));
  d.source = "test mesh";
  d.kind = "tetrahedral mesh";
  return d;
}

double linear(const Vec3d& p) {
  return 1.0 + 2.0 * p.x() - 3.0 * p.y() + 0.5 * p.z();
}

// The barycentric coordinates of p in tetrahedron t (all >= 0 when p lies in it).
std::array<double, 4> barycentric(const ScatteredData& d, const Tetrahedron& t, const Vec3d& p) {
  Eigen::Matrix3d m;
  for (int k = 0; k < 3; ++k)
    m.col(k) = d.points[static_cast<size_t>(t[k + 1])] - d.points[static_cast<size_t>(t[0])];
  const Vec3d w = m.inverse() * (p - d.points[static_cast<size_t>(t[0])]);
  return {1.0 - w.sum(), w[0], w[1], w[2]};
}

TEST(CellSamples, LieInTheirTetrahedraWithTheLinearField) {
  const ScatteredData d = cubeData(2, linear);
  for (int perCell : {1, 4}) {
    const ScatteredData s = withCellSamples(d, perCell);
    ASSERT_EQ(s.pointCount(), d.pointCount() + perCell * static_cast<std::int64_t>(d.tets.size()));
    ASSERT_EQ(cellSampleCount(d, perCell), perCell * static_cast<std::int64_t>(d.tets.size()));
    for (std::int64_t i = 0; i < d.pointCount(); ++i) {
      EXPECT_EQ(s.points[static_cast<size_t>(i)], d.points[static_cast<size_t>(i)]);
      EXPECT_EQ(s.values[static_cast<size_t>(i)], d.values[static_cast<size_t>(i)]);
    }
    EXPECT_EQ(s.tets, d.tets);
    for (size_t t = 0; t < d.tets.size(); ++t)
      for (int k = 0; k < perCell; ++k) {
        const size_t i =
            d.points.size() + t * static_cast<size_t>(perCell) + static_cast<size_t>(k);
        const auto w = barycentric(d, d.tets[t], s.points[i]);
        for (double wk : w) EXPECT_GT(wk, 0.05) << "sample " << k << " of tetrahedron " << t;
        EXPECT_NEAR(s.values[i], linear(s.points[i]), 1e-12);
      }
  }
}

TEST(CellSamples, LeaveFlatTetrahedraOutAndRejectWhatTheyCannotSample) {
  ScatteredData d = cubeData(1, linear);
  d.tets.push_back({0, 1, 2, 3});  // the four corners of the cube's bottom face: no volume
  EXPECT_EQ(cellSampleCount(d, 1), 6);
  EXPECT_EQ(withCellSamples(d, 4).pointCount(), d.pointCount() + 24);
  EXPECT_THROW(withCellSamples(d, 2), Error);
  EXPECT_THROW(withCellSamples(d, 0), Error);
  ScatteredData broken = d;
  broken.tets.push_back({0, 1, 2, 1000});
  EXPECT_THROW(withCellSamples(broken, 1), Error);
  ScatteredData cloud = d;
  cloud.tets.clear();
  EXPECT_THROW(withCellSamples(cloud, 1), Error);
  EncodeOptions o;
  o.cellSamples = 1;
  EXPECT_THROW(encodeScattered(cloud, o), Error);
  o.cellSamples = 3;
  EXPECT_THROW(encodeScattered(d, o), Error);
}

// A steep front across a coarse mesh, fitted with more control points than the mesh has points:
// from the points alone the spline is free between them; with cell samples it follows the
// mesh's linear field there too. The report counts the points and the samples apart.
TEST(CellSamples, TieAFineFitToTheMeshBetweenItsPoints) {
  const auto front = [](const Vec3d& p) { return std::tanh(3.0 * (p.x() - 2.1)); };
  const ScatteredData d = cubeData(4, front);
  auto meshError = [&](int cellSamples, FitReport& r) {
    EncodeOptions o;
    o.controlCounts = {14, 14, 14};
    o.smoothing = 1e-4;
    o.cellSamples = cellSamples;
    o.mask.enabled = false;
    const Model m = encodeScattered(d, o, &r);
    // The worst difference to the linear field at points inside the cells (the 4-point rule's).
    const ScatteredData probe = withCellSamples(d, 4);
    double worst = 0.0;
    for (size_t i = d.points.size(); i < probe.points.size(); ++i)
      worst = std::max(worst, std::abs(m.value(probe.points[i]) - probe.values[i]));
    return worst;
  };
  FitReport pointsOnly, withCells;
  const double free = meshError(0, pointsOnly);
  const double tied = meshError(1, withCells);
  EXPECT_LT(tied, 0.5 * free) << "points only " << free << ", with cell samples " << tied;
  EXPECT_EQ(pointsOnly.cellSamples, 0);
  EXPECT_EQ(withCells.cellSamples, static_cast<std::int64_t>(d.tets.size()));
  EXPECT_EQ(withCells.points, d.pointCount());
  EXPECT_EQ(pointsOnly.controlCounts, withCells.controlCounts);
}

}  // namespace
}  // namespace mfadvr
