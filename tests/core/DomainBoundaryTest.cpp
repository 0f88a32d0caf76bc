// The exact boundary of a mesh: extraction from tetrahedra (welding, orientation), inside tests
// of points, the stretches of lines through edges and vertices, the model file section, and
// renders whose rays sample exactly the chords of the mesh.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <random>

#include "TestSupport.h"
#include "core/field/ModelField.h"
#include "core/mask/DomainBoundary.h"
#include "core/model/ModelFile.h"
#include "core/render/Camera.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

using Mesh = test::TetMesh;

bool all(int, int, int) {
  return true;
}

// 4^3 cubes less a cavity (the central 2^3) and a notch (one corner cube).
bool holed(int i, int j, int k) {
  const bool cavity = i >= 1 && i <= 2 && j >= 1 && j <= 2 && k >= 1 && k <= 2;
  const bool notch = i == 3 && j == 3 && k == 3;
  return !cavity && !notch;
}

TEST(DomainBoundary, FacesOfOneTetrahedronOnlyOrientedOutward) {
  const Mesh m = test::cubeMesh(2, all);
  const DomainBoundary b = boundaryOfTetrahedra(m.points, m.tets);
  EXPECT_EQ(b.triangles().size(), 48u);  // 6 faces x 4 squares x 2 triangles
  EXPECT_EQ(b.vertices().size(), 26u);   // the 27 grid points less the centre
  for (const BoundaryTriangle& t : b.triangles()) {
    const Vec3d a = b.vertices()[t[0]].cast<double>(), p = b.vertices()[t[1]].cast<double>(),
                c = b.vertices()[t[2]].cast<double>();
    const Vec3d normal = (p - a).cross(c - a);
    EXPECT_GT(normal.dot((a + p + c) / 3.0 - Vec3d(1, 1, 1)), 0.0);
  }
}

TEST(DomainBoundary, PointsRepeatedWhereBlocksMeetAreWelded) {
  const Mesh m = test::cubeMesh(2, all, false);
  EXPECT_EQ(m.points.size(), 64u);
  const DomainBoundary b = boundaryOfTetrahedra(m.points, m.tets);
  EXPECT_EQ(b.triangles().size(), 48u);  // the faces between the cubes are not boundary
}

TEST(DomainBoundary, ContainsTheCubesAndNotTheCavityOrTheNotch) {
  for (bool shared : {true, false}) {
    const Mesh m = test::cubeMesh(4, holed, shared);
    const DomainBoundary b = boundaryOfTetrahedra(m.points, m.tets);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.5, 4.5);
    int in = 0, out = 0;
    for (int t = 0; t < 20000; ++t) {
      const Vec3d x(u(rng), u(rng), u(rng));
      bool nearPlane = false;
      for (int a = 0; a < 3; ++a) nearPlane = nearPlane || std::abs(x[a] - std::round(x[a])) < 1e-6;
      if (nearPlane) continue;
      const bool inGrid = (x.array() > 0.0).all() && (x.array() < 4.0).all();
      const bool expected = inGrid && holed(int(x[0]), int(x[1]), int(x[2]));
      ASSERT_EQ(b.contains(x), expected) << x.transpose() << " shared " << shared;
      (expected ? in : out) += 1;
    }
    EXPECT_GT(in, 5000);
    EXPECT_GT(out, 5000);
  }
}

TEST(DomainBoundary, LinesThroughEdgesAndVerticesCrossOnce) {
  const Mesh m = test::cubeMesh(3, all);
  const DomainBoundary b = boundaryOfTetrahedra(m.points, m.tets);
  const BoundaryView v = b.view();
  double intervals[2 * kMaxBoundaryIntervals];
  // Along x through every line of the grid (edges of boundary and inner faces) and between.
  for (int jy = 1; jy < 6; ++jy)
    for (int jz = 1; jz < 6; ++jz) {
      const double o[3] = {-1.0, 0.5 * jy, 0.5 * jz}, d[3] = {1.0, 0.0, 0.0};
      ASSERT_EQ(boundaryIntervals(v, o, d, intervals), 1) << jy << " " << jz;
      EXPECT_NEAR(intervals[0], 1.0, 1e-12);
      EXPECT_NEAR(intervals[1], 4.0, 1e-12);
    }
  // Along the main diagonal: through a vertex of the boundary at each end, and through the
  // grid's inner vertices.
  const double o[3] = {-1, -1, -1}, d[3] = {1, 1, 1};
  ASSERT_EQ(boundaryIntervals(v, o, d, intervals), 1);
  EXPECT_NEAR(intervals[0], 1.0, 1e-12);
  EXPECT_NEAR(intervals[1], 4.0, 1e-12);
  // Through an edge of the hull from outside: the line only touches the mesh.
  const double to[3] = {2, 4, 1.5}, td[3] = {1, -1, 0};  // meets (3, 3, 1.5) at t = 1
  const int n = boundaryIntervals(v, to, td, intervals);
  ASSERT_GE(n, 0);
  EXPECT_FALSE(inIntervals(intervals, n, 0.9));
  EXPECT_FALSE(inIntervals(intervals, n, 1.1));
  // Through a silhouette vertex.
  const double vo[3] = {4, 4, 2}, vd[3] = {-1, -1, 1};  // meets (3, 3, 3) at t = 1
  const int nv = boundaryIntervals(v, vo, vd, intervals);
  ASSERT_GE(nv, 0);
  EXPECT_FALSE(inIntervals(intervals, nv, 0.9));
  EXPECT_FALSE(inIntervals(intervals, nv, 1.1));
}

TEST(DomainBoundary, LinesInThePlaneOfASharedEdgeAreNeverLost) {
  // A fan of eight triangles about (0, 0, 1) in the plane z = 1, facing up; the edge from the
  // centre to vertex 1 lies in the plane x = y. Lines in that plane cross the fan on that edge:
  // its edge function is then zero in exact arithmetic, and a fused multiply-add of the two
  // products (which a compiler may make of them) leaves a rounding error of the same sign in both
  // triangles; both would reject the line. Each line must cross the fan exactly once.
  std::vector<Vec3f> vertices{Vec3f(0, 0, 1)};
  for (int k = 0; k < 8; ++k) {
    const double a = 2.0 * 3.14159265358979 * k / 8.0;
    vertices.emplace_back(static_cast<float>(1.7 * std::cos(a)),
                          static_cast<float>(1.7 * std::sin(a)), 1.0f);
  }
  vertices[2][1] = vertices[2][0];  // exactly on x = y
  std::vector<BoundaryTriangle> triangles;
  for (std::uint32_t k = 0; k < 8; ++k) triangles.push_back({0, 1 + k, 1 + (k + 1) % 8});
  const DomainBoundary b(vertices, triangles);
  const BoundaryView v = b.view();
  int lost = 0, lines = 0;
  for (int i = 1; i < 2000; ++i) {
    const double t = 1.2 * i / 2000.0;  // along the edge, whose far end is at x = y = 1.2
    for (const double tilt : {0.0, 1e-3, -3.7e-2}) {
      const double o[3] = {t + 5.0 * tilt, t + 5.0 * tilt, 6.0}, d[3] = {-tilt, -tilt, -1.0};
      BoundaryCrossing c[kMaxBoundaryCrossings];
      int n = 0;
      forEachCrossing(v, o, d, [&](double at, int step) {
        c[n++] = {at, step};
        return n < kMaxBoundaryCrossings;
      });
      n = mergeCrossings(c, n, v.scale);
      lost += n != 1;
      ++lines;
      if (n == 1) {
        EXPECT_EQ(c[0].step, 1);  // entering: against the upward normal
        EXPECT_NEAR(c[0].t, 5.0, 1e-9);
      }
    }
  }
  EXPECT_EQ(lost, 0) << "of " << lines << " lines";
}

TEST(DomainBoundary, BadTrianglesAreClearErrors) {
  EXPECT_THROW(DomainBoundary({Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0)}, {{0, 1, 3}}),
               Error);
  EXPECT_THROW(DomainBoundary({Vec3f(0, 0, 0), Vec3f(NAN, 0, 0), Vec3f(0, 1, 0)}, {{0, 1, 2}}),
               Error);
  Mesh m = test::cubeMesh(1, all);
  m.tets[0][2] = 99;
  EXPECT_THROW(boundaryOfTetrahedra(m.points, m.tets), Error);
}

// A constant model (value 1) over [-1, 1]^3 whose domain is the octahedron |x|+|y|+|z| <= 1,
// given as 8 tetrahedra around the centre.
Model octahedronModel() {
  std::array<KnotVector, 3> knots;
  for (auto& k : knots) k = KnotVector::clampedUniform(2, 4);
  Model m(TensorBSpline(knots, std::vector<float>(64, 1.0f)),
          DomainBox{Vec3d(-1, -1, -1), Vec3d(1, 1, 1)}, 1.0, 1.0);
  m.setBoundary(test::octahedronBoundary(Vec3d::Zero(), 1.0));
  return m;
}

TEST(DomainBoundary, ModelInsideAndFileRoundTrip) {
  const Model m = octahedronModel();
  ASSERT_NE(m.boundary(), nullptr);
  EXPECT_EQ(m.boundary()->triangles().size(), 8u);
  EXPECT_TRUE(m.inside(Vec3d(0.3, 0.3, 0.3)));
  EXPECT_FALSE(m.inside(Vec3d(0.4, 0.4, 0.3)));
  EXPECT_FALSE(m.inside(Vec3d(0.9, 0.9, 0.9)));

  const std::string bytes = serializeModel(m);
  EXPECT_EQ(static_cast<std::int64_t>(bytes.size()), modelFileSize(m));
  const Model back = parseModel({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()},
                                "octahedron.mfa");
  ASSERT_NE(back.boundary(), nullptr);
  EXPECT_EQ(back.boundary()->triangles(), m.boundary()->triangles());
  EXPECT_EQ(back.boundary()->vertices(), m.boundary()->vertices());
  EXPECT_FALSE(back.inside(Vec3d(0.4, 0.4, 0.3)));

  // Damaged files are clear errors, never crashes.
  std::mt19937 rng(5);
  int refused = 0;
  for (int t = 0; t < 300; ++t) {
    std::string damaged = bytes;
    const size_t at = std::uniform_int_distribution<size_t>(0, damaged.size() - 1)(rng);
    damaged[at] = static_cast<char>(damaged[at] ^ (1 + t % 255));
    if (t % 3 == 0) damaged.resize(at);
    try {
      parseModel({reinterpret_cast<const std::uint8_t*>(damaged.data()), damaged.size()}, "x");
    } catch (const Error&) {
      ++refused;
    }
  }
  EXPECT_EQ(refused, 300);  // every change breaks the checksum or the structure
}

TEST(DomainBoundary, RaysSampleExactlyTheChordsOfTheMesh) {
  RenderSettings s = test::octahedronView(48, 40);
  s.transferFunction.color = {{0.0, Vec3f(1, 1, 1)}, {2.0, Vec3f(1, 1, 1)}};
  s.transferFunction.opacity = {{0.0, 0.5f}, {2.0, 0.5f}};
  const Model m = octahedronModel();
  const ModelField field(m);
  RenderStats stats;
  const Image image = renderVolume(field, s, &stats);
  const int hit = test::expectChordTransmittance(image, s);
  EXPECT_GT(hit, 400);
  // The same through the generic field path (ModelField's sampler: Model::inside per sample).
  EXPECT_TRUE(field.sampler().masked());
  EXPECT_FALSE(field.sampler().inside(Vec3d(0.4, 0.4, 0.3)));
}

// Skipping leaves a mesh model's image unchanged: the march ahead through empty cells, which
// walks several rays at once, must not test samples against another ray's stretches inside the
// boundary (it did: 39.8 dB between the blunt fin's images with and without skipping).
TEST(DomainBoundary, SkippingLeavesTheImageOfABoundedModelUnchanged) {
  Model m = octahedronModel();
  Model bounded(test::patternedSpline(12), m.domain(), 0.0, 1.0);
  bounded.setBoundary(std::make_shared<const DomainBoundary>(*m.boundary()));
  RenderSettings s = test::octahedronView(96, 80);
  s.transferFunction.color = {{0.0, Vec3f(0, 0, 1)}, {1.0, Vec3f(1, 0.5, 0)}};
  s.transferFunction.opacity = {{0.0, 0.0f}, {0.6, 0.0f}, {0.7, 1.0f}, {1.0, 1.0f}};
  for (bool shade : {false, true}) {
    s.shade = shade;
    RenderStats on, off;
    const Image skipping = renderVolume(ModelField(bounded), s, &on);
    s.skipEmptySpace = false;
    const Image every = renderVolume(ModelField(bounded), s, &off);
    s.skipEmptySpace = true;
    EXPECT_GT(on.skipped, 0);
    EXPECT_EQ(skipping.rgba, every.rgba) << (shade ? "shaded" : "unshaded");
  }
}

}  // namespace
}  // namespace mfadvr
