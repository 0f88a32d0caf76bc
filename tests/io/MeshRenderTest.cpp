// Real meshes through the whole MFA path: read, encode with a domain mask, render. The images
// must be non-empty and show nothing outside the mesh, judged against the mesh's own silhouette
// (every tetrahedron projected and rasterized), which does not depend on the mask.
#include <gtest/gtest.h>

#include <cmath>

#include "TestSupport.h"
#include "core/encode/Encoder.h"
#include "core/field/ModelField.h"
#include "core/render/RayCaster.h"
#include "io/ScatteredLoader.h"

namespace mfadvr {
namespace {

struct Silhouette {
  int width = 0, height = 0;
  std::vector<std::uint8_t> covered;
  bool at(int x, int y) const {
    return x >= 0 && y >= 0 && x < width && y < height && covered[size_t(y * width + x)];
  }
  // Covered within `r` pixels (the mask's boundary may lie half a mask node outside the mesh).
  bool near(int x, int y, int r) const {
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx)
        if (at(x + dx, y + dy)) return true;
    return false;
  }
};

// Pixels whose centre lies in the parallel projection of some tetrahedron.
Silhouette meshSilhouette(const ScatteredData& mesh, const Camera& camera, int w, int h) {
  const RayGenerator rays(camera, w, h);
  Vec3d o00, o10, o01, d;
  rays.ray(0, 0, o00, d);
  rays.ray(1, 0, o10, d);
  rays.ray(0, 1, o01, d);
  const Vec3d ex = o10 - o00, ey = o01 - o00;
  auto project = [&](const Vec3d& p) {
    return Eigen::Vector2d((p - o00).dot(ex) / ex.squaredNorm(),
                           (p - o00).dot(ey) / ey.squaredNorm());
  };
  Silhouette s{w, h, std::vector<std::uint8_t>(size_t(w * h), 0)};
  const int faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (const Tetrahedron& t : mesh.tets) {
    Eigen::Vector2d q[4];
    for (int i = 0; i < 4; ++i) q[i] = project(mesh.points[size_t(t[i])]);
    for (const auto& f : faces) {
      const Eigen::Vector2d &a = q[f[0]], &b = q[f[1]], &c = q[f[2]];
      const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
      if (std::abs(area) < 1e-12) continue;
      const int x0 = std::max(0, int(std::floor(std::min({a.x(), b.x(), c.x()}))));
      const int x1 = std::min(w - 1, int(std::ceil(std::max({a.x(), b.x(), c.x()}))));
      const int y0 = std::max(0, int(std::floor(std::min({a.y(), b.y(), c.y()}))));
      const int y1 = std::min(h - 1, int(std::ceil(std::max({a.y(), b.y(), c.y()}))));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const Eigen::Vector2d p(x, y);
          auto edge = [&](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
            return ((v - u).x() * (p - u).y() - (v - u).y() * (p - u).x()) / area;
          };
          if (edge(a, b) >= -1e-9 && edge(b, c) >= -1e-9 && edge(c, a) >= -1e-9)
            s.covered[size_t(y * w + x)] = 1;
        }
    }
  }
  return s;
}

RenderSettings settingsFor(const Model& model, double azimuth, double elevation) {
  RenderSettings s;
  s.width = s.height = 64;
  s.camera.parallelProjection = true;
  s.camera.resetToBounds(model.domain().min, model.domain().max);
  s.camera.azimuth(azimuth);
  s.camera.elevation(elevation);
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{model.valueMin(), Vec3f(1, 1, 1)},
                              {model.valueMax(), Vec3f(1, 1, 1)}};
  s.transferFunction.opacity = {{model.valueMin(), 0.5f}, {model.valueMax(), 0.5f}};
  const Vec3d extent = model.domain().extent();
  s.sampleDistance = extent.minCoeff() / 100.0;
  s.opacityUnitDistance = extent.minCoeff() / 10.0;
  return s;
}

struct Counts {
  int visible = 0, outside = 0, silhouette = 0;
};

Counts countPixels(const Image& image, const Silhouette& s) {
  Counts c;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      c.silhouette += s.at(x, y);
      if (image.pixel(x, y)[3] > 0.01f) {
        ++c.visible;
        c.outside += !s.near(x, y, 1);
      }
    }
  return c;
}

void checkMesh(const std::string& file, const std::string& field, Index3 ctrl) {
  const auto path = test::dataFile(file);
  if (path.empty()) GTEST_SKIP() << file << " not present";
  ScatteredLoadOptions load;
  load.field.name = field;
  const ScatteredData mesh = loadScatteredData(path.string(), load);
  ASSERT_TRUE(mesh.hasCells());
  EncodeOptions options;
  options.controlCounts = ctrl;
  options.mask.longestAxisNodes = 96;  // the default 128 works too; this keeps the test quick
  FitReport report;
  Model model = encodeScattered(mesh, options, &report);
  ASSERT_FALSE(model.mask().empty());
  EXPECT_EQ(model.mask().kind(), MaskKind::MeshOccupancy);
  EXPECT_GT(report.maskInsideFraction, 0.0);
  EXPECT_LT(report.maskInsideFraction, 1.0);
  ASSERT_NE(model.boundary(), nullptr);  // the exact boundary, which the renderer follows
  Model maskOnly = model;
  maskOnly.setBoundary(nullptr);
  Model unmasked = maskOnly;
  unmasked.setMask(DomainMask());

  bool maskMattered = false;
  for (const auto& [azimuth, elevation] : {std::pair{0.0, 0.0}, {100.0, 35.0}}) {
    const RenderSettings s = settingsFor(model, azimuth, elevation);
    const Silhouette silhouette = meshSilhouette(mesh, s.camera, s.width, s.height);
    SCOPED_TRACE(file + " azimuth " + std::to_string(azimuth));
    for (const Model* m : {&model, &maskOnly}) {
      const Counts masked = countPixels(renderVolume(ModelField(*m), s), silhouette);
      EXPECT_GT(masked.silhouette, 50);
      EXPECT_GT(masked.visible, masked.silhouette / 2);  // non-empty where the mesh is
      EXPECT_EQ(masked.outside, 0);                      // nothing outside the mesh
    }
    const Counts plain = countPixels(renderVolume(ModelField(unmasked), s), silhouette);
    maskMattered = maskMattered || plain.outside > 0;
  }
  // Without its mask and boundary the model fills its whole box: the test above can fail.
  EXPECT_TRUE(maskMattered);
}

TEST(MeshRender, SpxShowsNothingOutsideTheMesh) {
  checkMesh("spx.vtk", "", {12, 12, 12});
}

TEST(MeshRender, BluntfinShowsNothingOutsideTheMesh) {
  checkMesh("bluntfin_tets.vtu", "Density", {16, 16, 16});
}

}  // namespace
}  // namespace mfadvr
