// The stretches inside a mesh's boundary gathered a tile at a time by projecting its triangles
// (BoundaryRaster) against the per-ray query (boundaryIntervals): the same for every pixel, to
// the bit, from cameras outside, inside and behind the mesh, looking along its faces and edges,
// perspective and parallel, and for tiles of any size.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "TestSupport.h"
#include "core/field/ModelField.h"
#include "core/mask/DomainBoundary.h"
#include "core/render/BoundaryRaster.h"
#include "core/render/Camera.h"
#include "core/render/ModelKernelSwitch.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {
namespace {

struct Tally {
  std::int64_t rays = 0, inside = 0, notGathered = 0;
};

// Gathers every tile of `tile` x `tile` pixels and compares each pixel with its own query.
Tally expectTilesEqualQueries(const DomainBoundary& b, const CameraRays& rays, int tile) {
  const BoundaryView v = b.view();
  const BoundaryRaster raster(v, rays);
  BoundaryTileStretches out;
  Tally tally;
  for (int y0 = 0; y0 < rays.height; y0 += tile)
    for (int x0 = 0; x0 < rays.width; x0 += tile) {
      const int x1 = std::min(x0 + tile, rays.width), y1 = std::min(y0 + tile, rays.height);
      raster.gather(x0, y0, x1, y1, out);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          double o[3], d[3], expected[2 * kMaxBoundaryIntervals];
          primaryRay(rays, x, y, o, d);
          const int n = boundaryIntervals(v, o, d, expected);
          const double* got = nullptr;
          const int m = out.view.find(static_cast<std::int64_t>(y) * rays.width + x, got);
          ++tally.rays;
          if (m == kStretchesNotGathered) {
            ++tally.notGathered;
            continue;
          }
          bool same = m == n;
          for (int i = 0; same && i < 2 * n; ++i) same = got[i] == expected[i];
          if (!same) {
            ADD_FAILURE() << "pixel " << x << ", " << y << ": " << m << " stretches gathered, " << n
                          << " queried";
            return tally;  // one report is enough
          }
          if (n > 0) ++tally.inside;
        }
    }
  return tally;
}

CameraRays raysOf(const Camera& camera, int width, int height) {
  return RayGenerator(camera, width, height).rays();
}

Camera lookAt(const Vec3d& position, const Vec3d& focalPoint, double viewAngle = 40.0) {
  Camera c;
  c.position = position;
  c.focalPoint = focalPoint;
  c.viewUp = Vec3d(0, 1, 0);
  if (std::abs((focalPoint - position).normalized().dot(c.viewUp)) > 0.99)
    c.viewUp = Vec3d(0, 0, 1);
  c.viewAngle = viewAngle;
  return c;
}

// 4^3 unit cubes less a central cavity (2^3) and a corner notch: axis-aligned faces, so that
// the views along the axes send rays exactly through edges and vertices.
bool holed(int i, int j, int k) {
  const bool cavity = i >= 1 && i <= 2 && j >= 1 && j <= 2 && k >= 1 && k <= 2;
  return !cavity && !(i == 3 && j == 3 && k == 3);
}

TEST(BoundaryRaster, TilesEqualThePerRayQueryFromOutside) {
  for (bool shared : {true, false}) {
    const test::TetMesh m = test::cubeMesh(4, holed, shared);
    const DomainBoundary b = boundaryOfTetrahedra(m.points, m.tets);
    const Vec3d centre(2, 2, 2);
    // Along an axis through the grid's lines (pixel centres on them: 40 pixels over the
    // 4-unit face at the focal distance, through integer coordinates), and oblique.
    Camera axial = lookAt(Vec3d(2, 2, 12), centre, 2.0 * std::atan(2.0 / 10.0) * 180.0 / M_PI);
    for (const Camera& c :
         {axial, lookAt(Vec3d(9, 7, 11), centre), lookAt(Vec3d(-6, 3, -5), centre, 25.0)}) {
      for (int tile : {16, 7}) {
        const Tally t = expectTilesEqualQueries(b, raysOf(c, 41, 41), tile);
        EXPECT_EQ(t.notGathered, 0);
        EXPECT_GT(t.inside, t.rays / 4);
      }
    }
    const Tally skewed = expectTilesEqualQueries(
        b, test::skewedRays(raysOf(lookAt(Vec3d(9, 7, 11), centre), 37, 29)), 16);
    EXPECT_EQ(skewed.notGathered, 0);
    EXPECT_GT(skewed.inside, skewed.rays / 8);
  }
}

TEST(BoundaryRaster, TilesEqualThePerRayQueryInParallelProjection) {
  const test::TetMesh m = test::cubeMesh(4, holed);
  const DomainBoundary b = boundaryOfTetrahedra(m.points, m.tets);
  for (const Vec3d& from : {Vec3d(2, 2, 12), Vec3d(9, 7, 11), Vec3d(2, -8, 2.5)}) {
    Camera c = lookAt(from, Vec3d(2, 2, 2));
    c.parallelProjection = true;
    c.parallelScale = 2.5;
    const Tally t = expectTilesEqualQueries(b, raysOf(c, 40, 33), 16);
    EXPECT_EQ(t.notGathered, 0);
    EXPECT_GT(t.inside, t.rays / 4);
  }
}

TEST(BoundaryRaster, TilesEqualThePerRayQueryFromInsideAndFacingAway) {
  const test::TetMesh m = test::cubeMesh(4, holed);
  const DomainBoundary b = boundaryOfTetrahedra(m.points, m.tets);
  // In the cavity, in the solid, on a face's plane, and outside looking away (the mesh behind
  // the camera: its crossings lie at negative distances, and count all the same).
  const Camera cameras[] = {lookAt(Vec3d(1.7, 2.2, 2.4), Vec3d(4, 3, 3), 90.0),
                            lookAt(Vec3d(0.5, 3.4, 0.6), Vec3d(3, 1, 3), 100.0),
                            lookAt(Vec3d(2.3, 1.0, 1.6), Vec3d(2.9, 3.0, 4.0), 70.0),
                            lookAt(Vec3d(2, 2, 7), Vec3d(2.2, 2.1, 12), 30.0)};
  for (const Camera& c : cameras) {
    const BoundaryRaster raster(b.view(), raysOf(c, 48, 40));
    const Tally t = expectTilesEqualQueries(b, raysOf(c, 48, 40), 16);
    EXPECT_EQ(t.notGathered, 0);
    EXPECT_GT(t.inside, t.rays / 4);
  }
  // From inside, triangles reach across the camera's plane; they are tried per tile.
  EXPECT_GT(BoundaryRaster(b.view(), raysOf(cameras[0], 48, 40)).straddlingTriangles(), 0);
  EXPECT_GT(BoundaryRaster(b.view(), raysOf(cameras[3], 48, 40)).binnedTriangles(), 0);
}

TEST(BoundaryRaster, RaysOfManyCrossingsAreLeftToTheirOwnQuery) {
  // 24 slabs one cube thick along x: a ray along x crosses 48 faces, more than a tile gathers.
  const test::TetMesh m =
      test::cubeMesh(48, [](int i, int j, int k) { return i % 2 == 0 && j < 2 && k < 2; });
  const DomainBoundary b = boundaryOfTetrahedra(m.points, m.tets);
  Camera c = lookAt(Vec3d(-5, 1.02, 1.03), Vec3d(30, 1.0, 1.0), 10.0);
  const Tally t = expectTilesEqualQueries(b, raysOf(c, 16, 16), 16);
  EXPECT_GT(t.notGathered, 0);
  // Across the slabs, a ray crosses two faces.
  const Tally across =
      expectTilesEqualQueries(b, raysOf(lookAt(Vec3d(7.5, 1, 9), Vec3d(7.5, 1, 1)), 32, 32), 16);
  EXPECT_EQ(across.notGathered, 0);
  EXPECT_GT(across.inside, 0);
}

// A model's render, whose tiles gather their rays' stretches, against the same rays each
// querying the boundary alone (samplers made without the tile): the same image, to the bit.
TEST(BoundaryRaster, ARenderOfGatheredTilesEqualsOneOfRaysQueryingAlone) {
  const test::TetMesh mesh = test::cubeMesh(4, holed);
  Model model(test::patternedSpline(10), DomainBox{Vec3d::Zero(), Vec3d::Constant(4)}, 0.0, 1.0);
  model.setBoundary(
      std::make_shared<const DomainBoundary>(boundaryOfTetrahedra(mesh.points, mesh.tets)));
  const ModelField field(model);
  RenderSettings s = test::viewOf(53, 45, Vec3d(9, 7, 11), Vec3d(2, 2, 2), 30, 0.02);
  s.transferFunction.color = {{0.0, Vec3f(0, 0, 1)}, {1.0, Vec3f(1, 0.5, 0)}};
  s.transferFunction.opacity = {{0.0, 0.1f}, {1.0, 0.6f}};
  for (bool shade : {false, true}) {
    s.shade = shade;
    const Image gathered = renderVolume(field, s);
    const ModelRenderSetup setup(field, s);
    const ModelView& view = setup.view();
    ASSERT_NE(view.boundary.nodes, nullptr);
    Image alone(s.width, s.height);
    // Only the masked loops of the test spline's degree 2 (or the generic one, where 2 is not
    // unrolled) are compiled here: every degree's eight loops would cost minutes of compilation.
    constexpr int kDegree = kMaxUnrolledDegree < 2 ? 0 : 2;
    modelKernelSwitch<kDegree>(
        view, s.needsGradients(), [&]<int P, bool Masked, bool Shade, bool Skip>() {
          if constexpr (P == kDegree && Masked)
            castRays<Masked, Shade>(
                s, setup.params(), [&] { return SplineRaySampler<P, Skip, Shade>(view); }, alone,
                nullptr);
          else
            FAIL() << "expected the masked loop of degree " << kDegree << ", not P = " << P
                   << ", masked " << Masked;
        });
    EXPECT_EQ(gathered.rgba, alone.rgba) << (shade ? "shaded" : "unshaded");
    int seen = 0;
    for (int i = 3; i < static_cast<int>(alone.rgba.size()); i += 4) seen += alone.rgba[i] > 0.05f;
    EXPECT_GT(seen, s.width * s.height / 4);
  }
}

TEST(BoundaryRaster, WithoutABoundaryNothingIsGathered) {
  const BoundaryRaster raster(BoundaryView{}, raysOf(lookAt(Vec3d(0, 0, 5), Vec3d::Zero()), 8, 8));
  BoundaryTileStretches out;
  raster.gather(0, 0, 8, 8, out);
  const double* s = nullptr;
  EXPECT_EQ(out.view.find(9, s), kStretchesNotGathered);
  EXPECT_EQ(out.view.find(64, s), kStretchesNotGathered);  // beyond the tile
}

}  // namespace
}  // namespace mfadvr
