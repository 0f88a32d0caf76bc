#pragma once
// Helpers shared by the test programs: where the real data lives, scratch folders.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image/Image.h"
#include "core/mask/DomainBoundary.h"
#include "core/mask/DomainMask.h"
#include "core/render/RenderSettings.h"
#include "core/render/kernel/CameraRays.h"
#include "core/spline/TensorBSpline.h"
#include "core/util/Error.h"

namespace mfadvr::test {

// Folder of the shared real volumes ($MFADVR_DATA_DIR overrides the configured default).
// A copy of `s` as a vector, for comparisons (spans have no ==).
inline std::vector<float> values(std::span<const float> s) {
  return {s.begin(), s.end()};
}

// The rays `r` as a host's skewed frustum may give them: right, up and forward neither unit nor
// orthogonal.
inline CameraRays skewedRays(CameraRays r) {
  for (int a = 0; a < 3; ++a) {
    r.right[a] = 1.3 * r.right[a] + 0.2 * r.up[a];
    r.up[a] = 0.8 * r.up[a] + 0.1 * r.forward[a];
    r.forward[a] = 1.7 * r.forward[a] + 0.05 * r.right[a];
  }
  return r;
}

inline std::filesystem::path dataDir() {
  if (const char* env = std::getenv("MFADVR_DATA_DIR")) return env;
  return MFADVR_DEFAULT_DATA_DIR;
}

// Path of a shared data file, or empty when it is absent (callers GTEST_SKIP()).
inline std::filesystem::path dataFile(const std::string& name) {
  const auto p = dataDir() / name;
  return std::filesystem::exists(p) ? p : std::filesystem::path();
}

// A fresh, empty scratch folder per test.
inline std::filesystem::path scratchDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::path(MFADVR_TEST_TMP_DIR) /
             (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Fails the test unless `f` throws mfadvr::Error whose message contains every one of `parts`.
template <typename F>
void expectError(F&& f, const std::vector<std::string>& parts) {
  try {
    f();
    FAIL() << "no mfadvr::Error thrown";
  } catch (const Error& e) {
    for (const auto& p : parts)
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
          << "missing '" << p << "' in: " << e.what();
  }
}

// A domain mask of 17^3 nodes: the ball of radius 7 nodes about the centre is inside.
inline DomainMask ballMask() {
  const Index3 dims{17, 17, 17};
  std::vector<std::uint8_t> nodes(17 * 17 * 17);
  for (int k = 0; k < 17; ++k)
    for (int j = 0; j < 17; ++j)
      for (int i = 0; i < 17; ++i)
        nodes[i + 17 * (j + 17 * k)] =
            (i - 8) * (i - 8) + (j - 8) * (j - 8) + (k - 8) * (k - 8) <= 49 ? 1 : 0;
  return DomainMask(MaskKind::PointCoverage, dims, nodes);
}

struct TetMesh {
  std::vector<Vec3d> points;
  std::vector<Tetrahedron> tets;
};

// Writes m as a legacy VTK unstructured grid (ASCII) with the point scalar v = value(point).
inline void writeLegacyTetMesh(const std::filesystem::path& path, const TetMesh& m,
                               const std::function<double(const Vec3d&)>& value) {
  std::ofstream f(path);
  f << "# vtk DataFile Version 3.0\ntetrahedra\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  f << "POINTS " << m.points.size() << " double\n";
  for (const Vec3d& p : m.points) f << p.x() << " " << p.y() << " " << p.z() << "\n";
  f << "CELLS " << m.tets.size() << " " << 5 * m.tets.size() << "\n";
  for (const auto& t : m.tets)
    f << "4 " << t[0] << " " << t[1] << " " << t[2] << " " << t[3] << "\n";
  f << "CELL_TYPES " << m.tets.size() << "\n";
  for (size_t c = 0; c < m.tets.size(); ++c) f << "10\n";
  f << "POINT_DATA " << m.points.size() << "\nSCALARS v double 1\nLOOKUP_TABLE default\n";
  for (const Vec3d& p : m.points) f << value(p) << "\n";
}

// The octahedron |x - c|_1 <= r as 8 tetrahedra around c.
inline TetMesh octahedronMesh(const Vec3d& c, double r) {
  TetMesh m;
  m.points.push_back(c);
  for (int a = 0; a < 3; ++a)
    for (double side : {r, -r}) m.points.push_back(c + side * Vec3d::Unit(a));
  for (int sx : {1, 2})
    for (int sy : {3, 4})
      for (int sz : {5, 6}) m.tets.push_back({0, sx, sy, sz});
  return m;
}

// Its boundary.
inline std::shared_ptr<const DomainBoundary> octahedronBoundary(const Vec3d& c, double r) {
  const TetMesh m = octahedronMesh(c, r);
  return std::make_shared<const DomainBoundary>(boundaryOfTetrahedra(m.points, m.tets));
}

// The length of the chord of the ray o + t d through the octahedron |x|_1 <= 1 (a convex body:
// 8 half-spaces).
inline double octahedronChord(const Vec3d& o, const Vec3d& d) {
  double t0 = -INFINITY, t1 = INFINITY;
  for (int s = 0; s < 8; ++s) {
    const Vec3d n(s & 1 ? -1 : 1, s & 2 ? -1 : 1, s & 4 ? -1 : 1);  // n . x <= 1
    const double dn = n.dot(d), on = n.dot(o);
    if (dn == 0.0) {
      if (on > 1.0) return 0.0;
      continue;
    }
    const double t = (1.0 - on) / dn;
    if (dn > 0)
      t1 = std::min(t1, t);
    else
      t0 = std::max(t0, t);
  }
  return t1 > t0 ? (t1 - t0) * d.norm() : 0.0;
}

// A perspective view (view-up +y) with steps of `step` and a data-space transfer function.
inline RenderSettings viewOf(int width, int height, const Vec3d& position, const Vec3d& focalPoint,
                             double viewAngle, double step) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.camera.position = position;
  s.camera.focalPoint = focalPoint;
  s.camera.viewUp = Vec3d(0, 1, 0);
  s.camera.viewAngle = viewAngle;
  s.sampleDistance = step;
  s.transferFunction.space = TfSpace::Data;
  return s;
}

// A camera on the octahedron |x|_1 <= 1, steps of 0.01.
inline RenderSettings octahedronView(int width, int height) {
  return viewOf(width, height, Vec3d(0.7, 0.4, 5), Vec3d::Zero(), 30, 0.01);
}

// For an image of a field that is 1 in that octahedron, with opacity 0.5 per unit distance
// (white): each pixel's alpha is the transmittance of its ray's chord, within one step, and rays
// that miss stay empty. Returns the number of rays that hit.
inline int expectChordTransmittance(const Image& image, const RenderSettings& s) {
  const RayGenerator rays(s.camera, s.width, s.height);
  int hit = 0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      Vec3d o, d;
      rays.ray(x, y, o, d);
      const double chord = octahedronChord(o, d);
      const double alpha = image.pixel(x, y)[3];
      if (chord == 0.0) {
        EXPECT_EQ(alpha, 0.0) << x << " " << y;
        continue;
      }
      ++hit;
      const double low = 1.0 - std::pow(0.5, std::max(chord - s.sampleDistance, 0.0));
      const double high = 1.0 - std::pow(0.5, chord + s.sampleDistance);
      EXPECT_GE(alpha, low - 1e-5) << x << " " << y << " chord " << chord;
      EXPECT_LE(alpha, high + 1e-5) << x << " " << y << " chord " << chord;
    }
  return hit;
}

// A quadratic spline of n^3 control points over the unit cube whose values (0 to 1) jump from
// control point to control point: a field with structure everywhere, for comparing renders.
inline TensorBSpline patternedSpline(int n) {
  std::array<KnotVector, 3> knots;
  for (auto& k : knots) k = KnotVector::clampedUniform(2, n);
  std::vector<float> ctrl(static_cast<size_t>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        ctrl[static_cast<size_t>(i + n * (j + n * k))] =
            float((7 * i + 3 * j + 5 * k) % 11) / 10.0f;
  return TensorBSpline(knots, std::move(ctrl));
}

// Appends the 6 tetrahedra around the main diagonal of the cube with lowest corner (i, j, k) (the
// monotone paths from its corner 000 to 111), with id(x, y, z) the index of the point (x, y, z):
// neighbouring cubes split this way share their faces' diagonals (a conforming mesh).
template <class Id>
void appendCubeTetrahedra(std::int64_t i, std::int64_t j, std::int64_t k, Id&& id,
                          std::vector<Tetrahedron>& tets) {
  const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& path : paths) {
    std::int64_t at[3] = {i, j, k};
    Tetrahedron t;
    t[0] = id(at[0], at[1], at[2]);
    for (int s = 0; s < 3; ++s) {
      ++at[path[s]];
      t[s + 1] = id(at[0], at[1], at[2]);
    }
    tets.push_back(t);
  }
}

// Unit cubes [i, i+1] x [j, j+1] x [k, k+1] of an n^3 grid where keep(i, j, k), each split into
// the 6 tetrahedra around its main diagonal (a conforming mesh). shared = false: every cube has
// points of its own, as the blocks of a multi-block mesh repeat the points where they meet.
inline TetMesh cubeMesh(int n, const std::function<bool(int, int, int)>& keep, bool shared = true) {
  TetMesh m;
  const int np = n + 1;
  if (shared)
    for (int k = 0; k < np; ++k)
      for (int j = 0; j < np; ++j)
        for (int i = 0; i < np; ++i) m.points.emplace_back(i, j, k);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (!keep(i, j, k)) continue;
        std::int64_t base = 0;
        if (!shared) {
          base = static_cast<std::int64_t>(m.points.size());
          for (int c = 0; c < 8; ++c)
            m.points.emplace_back(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2));
        }
        auto id = [&](std::int64_t x, std::int64_t y, std::int64_t z) -> std::int64_t {
          if (shared) return x + np * (y + std::int64_t(np) * z);
          return base + (x - i) + 2 * (y - j) + 4 * (z - k);
        };
        appendCubeTetrahedra(i, j, k, id, m.tets);
      }
  return m;
}

}  // namespace mfadvr::test
