// The domain mask: its trilinear inside test, the builders (mesh occupancy, point coverage,
// default resolutions), and rendering a masked model.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <random>

#include "TestSupport.h"
#include "core/field/DerivedFields.h"
#include "core/field/ModelField.h"
#include "core/mask/MaskVoxelizer.h"
#include "core/render/Camera.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

TEST(DomainMask, TrilinearThresholdIsOneHalf) {
  // One corner set: the interpolant is (1-u)(1-v)(1-w).
  std::vector<std::uint8_t> nodes(8, 0);
  nodes[0] = 1;
  const DomainMask corner(MaskKind::MeshOccupancy, {2, 2, 2}, nodes);
  EXPECT_TRUE(corner.insideParameter(Vec3d(0, 0, 0)));
  EXPECT_TRUE(corner.insideParameter(Vec3d(0.5, 0, 0)));  // exactly 1/2 counts as inside
  EXPECT_FALSE(corner.insideParameter(Vec3d(0.5001, 0, 0)));
  EXPECT_TRUE(corner.insideParameter(Vec3d(0.2, 0.2, 0.2)));      // 0.512
  EXPECT_FALSE(corner.insideParameter(Vec3d(0.25, 0.25, 0.25)));  // 0.42
  EXPECT_FALSE(corner.insideParameter(Vec3d(0.5, 0.5, 0.5)));     // 1/8
  EXPECT_TRUE(corner.insideParameter(Vec3d(-3, -1, -2)));         // clamped onto the corner
  EXPECT_FALSE(corner.insideParameter(Vec3d(2, 2, 2)));
  EXPECT_DOUBLE_EQ(corner.insideFraction(), 1.0 / 8.0);

  // The x = 0 face set: inside exactly for u <= 1/2, whatever v and w.
  std::vector<std::uint8_t> face(8, 0);
  face[0] = face[2] = face[4] = face[6] = 1;
  const DomainMask half(MaskKind::PointCoverage, {2, 2, 2}, face);
  for (double v : {0.0, 0.3, 1.0})
    for (double w : {0.0, 0.7, 1.0}) {
      EXPECT_TRUE(half.insideParameter(Vec3d(0.5, v, w)));
      EXPECT_FALSE(half.insideParameter(Vec3d(0.51, v, w)));
      EXPECT_TRUE(half.insideParameter(Vec3d(0.1, v, w)));
    }

  const DomainMask none;
  EXPECT_TRUE(none.empty());
  EXPECT_TRUE(none.insideParameter(Vec3d(5, -5, 0.5)));
  EXPECT_DOUBLE_EQ(none.insideFraction(), 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  (void)half.insideParameter(Vec3d(nan, nan, nan));  // defined, no crash

  EXPECT_THROW(DomainMask(MaskKind::MeshOccupancy, {1, 2, 2}, std::vector<std::uint8_t>(4)), Error);
  EXPECT_THROW(DomainMask(MaskKind::MeshOccupancy, {2, 2, 2}, std::vector<std::uint8_t>(7)), Error);
  EXPECT_THROW(DomainMask::validateDims({4097, 2, 2}), Error);
  EXPECT_THROW(DomainMask::validateDims({4096, 4096, 4096}), Error);
  EXPECT_NO_THROW(DomainMask::validateDims({4096, 4096, 2}));
  EXPECT_EQ(parseMaskKind(maskKindName(MaskKind::PointCoverage)), MaskKind::PointCoverage);
  EXPECT_EQ(parseMaskKind(maskKindName(MaskKind::MeshOccupancy)), MaskKind::MeshOccupancy);
  EXPECT_THROW(parseMaskKind("voxels"), Error);
}

// A tetrahedralized ball: the cubes of a grid of spacing `s` over [-r, r]^3 whose 8 corners lie
// within radius r, each split into the 6 tetrahedra around its main diagonal (the Kuhn
// triangulation, conforming across cubes).
test::TetMesh tetrahedralizedBall(double r, int cells) {
  test::TetMesh b;
  const double s = 2 * r / cells;
  const int n = cells + 1;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) b.points.emplace_back(-r + i * s, -r + j * s, -r + k * s);
  auto id = [&](std::int64_t i, std::int64_t j, std::int64_t k) { return i + n * (j + n * k); };
  for (int k = 0; k < cells; ++k)
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i) {
        bool inside = true;
        for (int c = 0; c < 8; ++c)
          inside = inside && b.points[id(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2))].norm() <= r;
        if (inside) test::appendCubeTetrahedra(i, j, k, id, b.tets);
      }
  return b;
}

Vec3d nodePosition(const DomainBox& box, const Index3& dims, std::int64_t i, std::int64_t j,
                   std::int64_t k) {
  const Vec3d u(double(i) / double(dims[0] - 1), double(j) / double(dims[1] - 1),
                double(k) / double(dims[2] - 1));
  return box.min + u.cwiseProduct(box.extent());
}

bool insideAt(const DomainMask& m, const DomainBox& box, const Vec3d& x) {
  return m.insideParameter(box.toParameter(x));
}

TEST(MaskVoxelizer, MeshOccupancyOfATetrahedralizedBall) {
  const double r = 1.0;
  const int cells = 12;
  const test::TetMesh ball = tetrahedralizedBall(r, cells);
  ASSERT_GT(ball.tets.size(), 1000u);
  const DomainBox box{Vec3d(-1, -1, -1), Vec3d(1, 1, 1)};
  const Index3 dims{41, 37, 33};  // non-cubic, spacings that do not match the mesh
  const DomainMask m = meshOccupancyMask(ball.points, ball.tets, box, dims);
  EXPECT_EQ(m.kind(), MaskKind::MeshOccupancy);
  EXPECT_EQ(m.dims(), dims);

  for (int c = 0; c < 8; ++c)
    EXPECT_FALSE(insideAt(m, box, Vec3d(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1))) << c;
  EXPECT_TRUE(insideAt(m, box, Vec3d::Zero()));

  const double spacing = (box.extent().array() / (Eigen::Array3d(40, 36, 32))).maxCoeff();
  // The kept cubes cover the ball of radius r minus one cube diagonal.
  const double covered = r - std::sqrt(3.0) * 2 * r / cells;
  std::int64_t set = 0;
  for (std::int64_t k = 0; k < dims[2]; ++k)
    for (std::int64_t j = 0; j < dims[1]; ++j)
      for (std::int64_t i = 0; i < dims[0]; ++i) {
        const Vec3d x = nodePosition(box, dims, i, j, k);
        const bool node = m.nodes()[size_t(i + dims[0] * (j + dims[1] * k))] != 0;
        set += node;
        if (node) {
          EXPECT_LE(x.norm(), r + spacing) << x.transpose();
        }
        if (x.norm() < covered - 1e-9) {
          EXPECT_TRUE(node) << x.transpose();
        }
      }
  EXPECT_GT(set, 0);

  // Points inside in the interpolated sense are within a node spacing of the ball too.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int t = 0; t < 20000; ++t) {
    const Vec3d x(u(rng), u(rng), u(rng));
    if (insideAt(m, box, x)) {
      EXPECT_LE(x.norm(), r + spacing) << x.transpose();
    }
    if (x.norm() < covered - spacing) {
      EXPECT_TRUE(insideAt(m, box, x)) << x.transpose();
    }
  }
}

TEST(MaskVoxelizer, NodesOnTheMeshBoundaryAreInside) {
  // One cube exactly filling the box, as 6 tetrahedra: every node lies in or on the mesh.
  const test::TetMesh cube = tetrahedralizedBall(1.0, 1);  // no cube has all corners within radius 1
  ASSERT_TRUE(cube.tets.empty());
  std::vector<Vec3d> points;
  for (int c = 0; c < 8; ++c) points.emplace_back(c & 1, c >> 1 & 1, c >> 2);
  const std::vector<Tetrahedron> tets = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                                         {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  const DomainBox box{Vec3d::Zero(), Vec3d::Ones()};
  const DomainMask m = meshOccupancyMask(points, tets, box, {9, 5, 7});
  EXPECT_DOUBLE_EQ(m.insideFraction(), 1.0);

  // Degenerate tetrahedra are skipped; bad indices are errors.
  const std::vector<Tetrahedron> flat = {{0, 1, 2, 3}};  // the z = 0 face
  EXPECT_DOUBLE_EQ(meshOccupancyMask(points, flat, box, {5, 5, 5}).insideFraction(), 0.0);
  const std::vector<Tetrahedron> bad = {{0, 1, 2, 8}};
  EXPECT_THROW(meshOccupancyMask(points, bad, box, {5, 5, 5}), Error);
  EXPECT_THROW(meshOccupancyMask(points, tets, box, {1, 5, 5}), Error);
}

TEST(MaskVoxelizer, ResultDoesNotDependOnThreadCount) {
  const test::TetMesh ball = tetrahedralizedBall(1.0, 10);
  const DomainBox box{Vec3d(-1, -1, -1), Vec3d(1, 1, 1)};
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 0.4);
  std::vector<Vec3d> cloud;
  for (int i = 0; i < 5000; ++i)
    cloud.emplace_back(Vec3d(g(rng), g(rng), g(rng)).cwiseMax(-1.0).cwiseMin(1.0));
  const Index3 dims{29, 31, 30};
  DomainMask mesh1, cloud1;
  tbb::task_arena one(1);
  one.execute([&] {
    mesh1 = meshOccupancyMask(ball.points, ball.tets, box, dims);
    cloud1 = pointCoverageMask(cloud, box, dims);
  });
  for (int threads : {2, 3, 8}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      EXPECT_EQ(meshOccupancyMask(ball.points, ball.tets, box, dims).nodes(), mesh1.nodes());
      EXPECT_EQ(pointCoverageMask(cloud, box, dims).nodes(), cloud1.nodes());
    });
  }
}

TEST(MaskVoxelizer, PointCoverageOfABall) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3d> points;
  while (points.size() < 20000) {
    const Vec3d x(u(rng), u(rng), u(rng));
    if (x.norm() <= 1.0) points.push_back(x);
  }
  const DomainBox box{Vec3d(-1, -1, -1), Vec3d(1, 1, 1)};
  const int res = defaultCoverageResolution(static_cast<std::int64_t>(points.size()));
  EXPECT_EQ(res, 27);
  const Index3 dims = defaultMaskDims(box, res);
  EXPECT_EQ(dims, (Index3{27, 27, 27}));
  const DomainMask m = pointCoverageMask(points, box, dims);
  EXPECT_EQ(m.kind(), MaskKind::PointCoverage);
  for (int c = 0; c < 8; ++c)
    EXPECT_FALSE(insideAt(m, box, Vec3d(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1))) << c;
  EXPECT_TRUE(insideAt(m, box, Vec3d::Zero()));
  // No holes inside the cloud, and not far beyond it.
  const double spacing = 2.0 / 26;
  for (std::int64_t k = 0; k < dims[2]; ++k)
    for (std::int64_t j = 0; j < dims[1]; ++j)
      for (std::int64_t i = 0; i < dims[0]; ++i) {
        const Vec3d x = nodePosition(box, dims, i, j, k);
        const bool node = m.nodes()[size_t(i + dims[0] * (j + dims[1] * k))] != 0;
        if (x.norm() < 0.85) {
          EXPECT_TRUE(node) << x.transpose();
        }
        // A splatted node is within a cell diagonal of a point; the closing adds nodes within
        // one node of those (along the box faces, where erosion sees fewer neighbours).
        if (node) {
          EXPECT_LE(x.norm(), 1.0 + 2 * std::sqrt(3.0) * spacing) << x.transpose();
        }
      }
  const double ballFraction = 4.0 / 3.0 * M_PI / 8.0;  // 0.52
  EXPECT_GT(m.insideFraction(), ballFraction * 0.9);
  EXPECT_LT(m.insideFraction(), ballFraction * 1.5);
}

TEST(MaskVoxelizer, ClosingFillsSmallGapsOnly) {
  // Points on two planes: x = 0.2 and x = 0.2 + gap, spread over y and z.
  const DomainBox box{Vec3d::Zero(), Vec3d::Ones()};
  const Index3 dims{21, 6, 6};  // x spacing 0.05
  auto maskFor = [&](double gap) {
    std::vector<Vec3d> pts;
    for (double y = 0.01; y < 1; y += 0.1)
      for (double z = 0.01; z < 1; z += 0.1) {
        pts.emplace_back(0.21, y, z);
        pts.emplace_back(0.21 + gap, y, z);
      }
    return pointCoverageMask(pts, box, dims);
  };
  auto node = [&](const DomainMask& m, int i) { return m.nodes()[size_t(i + 21 * (2 + 6 * 3))]; };
  // Each plane sets x nodes 4, 5 (resp. the next pair). Two unset nodes between are filled...
  const DomainMask two = maskFor(0.20);  // sets 4,5 and 8,9: 6 and 7 filled
  for (int i = 4; i <= 9; ++i) EXPECT_EQ(node(two, i), 1) << i;
  EXPECT_EQ(node(two, 3), 0);
  EXPECT_EQ(node(two, 10), 0);
  // ...three are not.
  const DomainMask three = maskFor(0.25);  // sets 4,5 and 9,10
  EXPECT_EQ(node(three, 7), 0);
  EXPECT_EQ(node(three, 5), 1);
  EXPECT_EQ(node(three, 9), 1);
}

TEST(MaskVoxelizer, DefaultResolutions) {
  EXPECT_EQ(defaultCoverageResolution(0), 8);
  EXPECT_EQ(defaultCoverageResolution(100), 8);
  EXPECT_EQ(defaultCoverageResolution(1000), 10);
  EXPECT_EQ(defaultCoverageResolution(1000000), 100);
  EXPECT_EQ(defaultCoverageResolution(std::int64_t(1) << 40), 256);

  const DomainBox flat{Vec3d(0, 0, 0), Vec3d(2, 1, 0.001)};
  const Index3 d = defaultMaskDims(flat, kDefaultMeshMaskNodes);
  EXPECT_EQ(d[0], 128);
  EXPECT_GE(d[1], 64);
  EXPECT_LE(d[1], 65);
  EXPECT_EQ(d[2], 2);
  EXPECT_EQ(defaultMaskDims(flat, 1), (Index3{2, 2, 2}));
  const DomainBox cube{Vec3d::Zero(), Vec3d::Ones()};
  const Index3 big = defaultMaskDims(cube, 4096);  // capped by the total node count
  EXPECT_NO_THROW(DomainMask::validateDims(big));
  EXPECT_GT(big[0], 1000);
}

// A constant model (every control point 1) over [-1,1]^3, masked to x <= 0.
Model halfMaskedConstantModel(bool masked) {
  std::array<KnotVector, 3> knots;
  for (auto& k : knots) k = KnotVector::clampedUniform(2, 4);
  Model m(TensorBSpline(knots, std::vector<float>(64, 1.0f)),
          DomainBox{Vec3d(-1, -1, -1), Vec3d(1, 1, 1)}, 1.0, 1.0);
  if (masked) {
    std::vector<std::uint8_t> nodes(8, 0);
    nodes[0] = nodes[2] = nodes[4] = nodes[6] = 1;  // x = -1 face; boundary at x = 0
    m.setMask(DomainMask(MaskKind::MeshOccupancy, {2, 2, 2}, nodes));
  }
  return m;
}

TEST(MaskedRender, SamplesOutsideTheMaskAreEmpty) {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.camera.position = Vec3d(0.3, 0.2, 5);  // slightly oblique: some rays cross x = 0
  s.camera.focalPoint = Vec3d(0, 0, 0);
  s.camera.viewUp = Vec3d(0, 1, 0);
  s.camera.viewAngle = 30;
  s.sampleDistance = 0.02;
  s.background = Vec3f(0.1f, 0.2f, 0.3f);
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{0.0, Vec3f(1, 1, 1)}, {2.0, Vec3f(1, 1, 1)}};
  s.transferFunction.opacity = {{0.0, 0.5f}, {2.0, 0.5f}};

  const Model plain = halfMaskedConstantModel(false);
  const Model masked = halfMaskedConstantModel(true);
  const ModelField plainField(plain), maskedField(masked);
  EXPECT_TRUE(plainField.sampler().inside(Vec3d(0.9, 0, 0)));
  EXPECT_FALSE(maskedField.sampler().inside(Vec3d(0.9, 0, 0)));
  EXPECT_TRUE(maskedField.sampler().inside(Vec3d(-0.9, 0, 0)));
  RenderStats plainStats, maskedStats;
  const Image a = renderVolume(plainField, s, &plainStats);
  const Image b = renderVolume(maskedField, s, &maskedStats);
  EXPECT_LT(maskedStats.samples, plainStats.samples);  // masked samples are not evaluated
  // Central-difference gradients keep the inner model's mask.
  const CentralDifferenceField central(maskedField, Vec3d::Constant(0.05));
  EXPECT_FALSE(central.sampler().inside(Vec3d(0.9, 0, 0)));
  EXPECT_EQ(renderVolume(central, s).rgba, b.rgba);

  const RayGenerator rays(s.camera, s.width, s.height);
  int background = 0, coloured = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      Vec3d o, d;
      rays.ray(x, y, o, d);
      double t0, t1;
      if (!intersectBox(o.data(), d.data(), masked.domain().min.data(), masked.domain().max.data(),
                        t0, t1))
        continue;
      if (t1 - t0 < 0.05) continue;       // grazes an edge of the box
      EXPECT_GT(a.pixel(x, y)[3], 0.0f);  // unmasked: every ray through the box is coloured
      const double xIn = (o + t0 * d)[0], xOut = (o + t1 * d)[0];
      const float* p = b.pixel(x, y);
      if (std::min(xIn, xOut) > 0.01) {  // only the excluded half
        EXPECT_EQ(p[3], 0.0f) << x << " " << y;
        EXPECT_EQ(p[0], 0.1f);
        EXPECT_EQ(p[2], 0.3f);
        ++background;
      } else if (std::max(xIn, xOut) < -0.01) {  // only the kept half: as without the mask
        EXPECT_GT(p[3], 0.0f) << x << " " << y;
        EXPECT_EQ(p[3], a.pixel(x, y)[3]);
        ++coloured;
      } else if (std::min(xIn, xOut) < -0.1) {  // crosses the kept half for a while
        EXPECT_GT(p[3], 0.0f) << x << " " << y;
      }
    }
  EXPECT_GT(background, 100);
  EXPECT_GT(coloured, 100);
}

}  // namespace
}  // namespace mfadvr
