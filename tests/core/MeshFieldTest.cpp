// A mesh's own field (core/mesh/TetLocator.h, core/field/MeshField.h, --method mesh): points found
// in their tetrahedra, the linear field there, and rays that sample exactly the mesh's chords.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "TestSupport.h"
#include "core/encode/Encoder.h"
#include "core/field/MeshField.h"
#include "core/image/ImageMetrics.h"
#include "core/render/RayCaster.h"
#include "core/render/ReconstructionMethod.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

double linear(const Vec3d& p) {
  return 1.0 + 2.0 * p.x() - 3.0 * p.y() + 0.5 * p.z();
}

// n^3 unit cubes but the hollow ones, each in 6 tetrahedra; interior points moved a little so
// that the tetrahedra differ in shape and size; values `f` at the points.
template <class F>
ScatteredData jitteredCubes(int n, const std::function<bool(int, int, int)>& hollow, F&& f) {
  const test::TetMesh m = test::cubeMesh(n, [&](int i, int j, int k) { return !hollow(i, j, k); });
  ScatteredData d;
  d.points = m.points;
  d.tets = m.tets;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  for (Vec3d& p : d.points)
    for (int a = 0; a < 3; ++a)
      if (p[a] > 0 && p[a] < n) p[a] += jitter(rng);
  for (const Vec3d& p : d.points) d.values.push_back(f(p));
  d.source = "test mesh";
  d.kind = "tetrahedral mesh";
  return d;
}

bool centreCube(int i, int j, int k) {
  return i == 2 && j == 2 && k == 2;
}

TEST(MeshField, EveryPointIsFoundInItsTetrahedronWithTheLinearField) {
  const ScatteredData d = jitteredCubes(5, centreCube, linear);
  const TetLocator mesh(d);
  EXPECT_EQ(mesh.tetCount(), 6 * (125 - 1));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.5, 5.5);
  int found = 0, outside = 0;
  std::int64_t hint = -1;
  for (int s = 0; s < 20000; ++s) {
    const Vec3d x(u(rng), u(rng), u(rng));
    const std::int64_t t = mesh.locate(x, hint);
    // Outside the box, or in the hollow cube (whose faces moved by the jitter: tested away from
    // them), nothing is found; elsewhere in the box something is.
    const bool inBox = (x.array() >= 0.0).all() && (x.array() <= 5.0).all();
    const bool deepInHole = (x.array() > 2.25).all() && (x.array() < 2.75).all();
    const bool nearHole = (x.array() > 1.75).all() && (x.array() < 3.25).all();
    if (!inBox || deepInHole) {
      EXPECT_EQ(t, -1) << x.transpose();
      ++outside;
      continue;
    }
    if (nearHole) continue;
    ASSERT_GE(t, 0) << x.transpose();
    ++found;
    const ValueGradient vg = mesh.linear(t, x);
    EXPECT_NEAR(vg.value, linear(x), 1e-4) << x.transpose();
    EXPECT_NEAR(vg.gradient[0], 2.0, 1e-4);
    EXPECT_NEAR(vg.gradient[1], -3.0, 1e-4);
    EXPECT_NEAR(vg.gradient[2], 0.5, 1e-4);
    // A hint in the wrong tetrahedron does not change the answer's field.
    hint = (t * 7919) % mesh.tetCount();
    EXPECT_NEAR(mesh.linear(mesh.locate(x, hint), x).value, vg.value, 1e-4);
  }
  EXPECT_GT(found, 5000);
  EXPECT_GT(outside, 2000);
  EXPECT_EQ(mesh.locate(Vec3d(std::nan(""), 1.0, 1.0)), -1);
}

TEST(MeshField, SampleMethodGivesTheMeshsFieldAndBadMeshesAreRefused) {
  const ScatteredData d = jitteredCubes(
      3, [](int, int, int) { return false; }, linear);
  const TetLocator mesh(d);
  SceneData scene;
  scene.mesh = &mesh;
  const std::vector<Vec3d> points{{0.5, 1.5, 2.5}, {2.9, 0.1, 1.0}};
  const auto got = sampleMethod(scene, ReconstructionMethod::Mesh, points);
  for (size_t i = 0; i < points.size(); ++i) EXPECT_NEAR(got[i].value, linear(points[i]), 1e-4);
  EXPECT_FALSE(isGridMethod(ReconstructionMethod::Mesh));
  EXPECT_EQ(parseReconstructionMethod("mesh"), ReconstructionMethod::Mesh);
  EXPECT_THROW(sampleMethod(SceneData{}, ReconstructionMethod::Mesh, points), Error);

  ScatteredData cloud = d;
  cloud.tets.clear();
  EXPECT_THROW(TetLocator{cloud}, Error);
  ScatteredData flat = d;
  flat.tets = {{0, 1, 2, 3}};  // four points on the line y = z = 0
  EXPECT_THROW(TetLocator{flat}, Error);
  ScatteredData withFlat = d;
  withFlat.tets.push_back({0, 1, 2, 3});
  EXPECT_EQ(TetLocator(withFlat).tetCount(), TetLocator(d).tetCount());
  ScatteredData bad = d;
  bad.tets.push_back({0, 1, 2, 1000});
  EXPECT_THROW(TetLocator{bad}, Error);
}

// A constant field over the octahedron |x|_1 <= 1 (8 tetrahedra): each ray's opacity is that of
// its chord through the mesh (as DomainBoundary's test asks of a model bounded by it).
TEST(MeshField, RaysSampleExactlyTheChordsOfTheMesh) {
  const test::TetMesh m = test::octahedronMesh(Vec3d::Zero(), 1.0);
  ScatteredData d;
  d.points = m.points;
  d.tets = m.tets;
  d.values.assign(d.points.size(), 1.0);
  const TetLocator mesh(d);
  RenderSettings s = test::octahedronView(48, 40);
  s.transferFunction.color = {{0.0, Vec3f(1, 1, 1)}, {2.0, Vec3f(1, 1, 1)}};
  s.transferFunction.opacity = {{0.0, 0.5f}, {2.0, 0.5f}};
  const int hit = test::expectChordTransmittance(renderVolume(MeshField(mesh), s), s);
  EXPECT_GT(hit, 400);
}

// A model of a linear field on a mesh whose box it fills reproduces the field, so the images of
// the model and of the mesh, through the same ray caster, agree closely.
TEST(MeshField, AModelOfALinearFieldRendersAsTheMeshDoes) {
  const ScatteredData d = jitteredCubes(
      4, [](int, int, int) { return false; }, linear);
  const TetLocator mesh(d);
  const Model model = encodeScattered(d, EncodeOptions{});
  RenderSettings s = test::viewOf(64, 64, Vec3d(9, 7, 11), Vec3d(2, 2, 2), 40, 0.05);
  s.transferFunction.color = {{-11.0, Vec3f(0, 0, 1)}, {11.0, Vec3f(1, 0.5, 0)}};
  s.transferFunction.opacity = {{-11.0, 0.05f}, {11.0, 0.3f}};
  SceneData scene;
  scene.model = &model;
  scene.mesh = &mesh;
  MethodSpec spec;
  const Image ofModel = renderMethod(scene, spec, s);
  spec.method = ReconstructionMethod::Mesh;
  const Image ofMesh = renderMethod(scene, spec, s);
  EXPECT_GT(compareImages(toImage8(ofModel), toImage8(ofMesh)).psnr, 45.0);
}

}  // namespace
}  // namespace mfadvr
