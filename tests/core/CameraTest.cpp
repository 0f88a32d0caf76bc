// Camera semantics follow vtkCamera / vtkRenderer::ResetCamera.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/render/Camera.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

void expectVec(const Vec3d& a, const Vec3d& b, double tol = 1e-9) {
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(a[i], b[i], tol) << a.transpose() << " vs " << b.transpose();
}

TEST(Camera, ResetFramesTheBoxLikeVtk) {
  Camera c;
  c.resetToBounds(Vec3d(-1, -2, 0), Vec3d(3, 2, 2));
  const double radius = 0.5 * std::sqrt(16.0 + 16.0 + 4.0);
  const double distance = radius / std::sin(15.0 * std::numbers::pi / 180.0);
  expectVec(c.focalPoint, Vec3d(1, 0, 1));
  expectVec(c.position, Vec3d(1, 0, 1 + distance));  // VTK's default looks down -z
  expectVec(c.viewUp, Vec3d(0, 1, 0));
  EXPECT_NEAR(c.parallelScale, radius, 1e-12);
}

TEST(Camera, AzimuthElevationZoom) {
  Camera c;
  c.resetToBounds(Vec3d(-1, -1, -1), Vec3d(1, 1, 1));
  const double d = c.distance();
  Camera a = c;
  a.azimuth(90);  // about +y: from +z to +x
  expectVec(a.position, Vec3d(d, 0, 0));
  Camera e = c;
  e.elevation(90);  // up over the top: from +z to +y, view-up turns to -z
  expectVec(e.position, Vec3d(0, d, 0));
  expectVec(e.viewUp, Vec3d(0, 0, -1));
  EXPECT_NEAR(e.viewUp.dot(e.directionOfProjection()), 0.0, 1e-12);
  Camera z = c;
  z.zoom(2.0);
  EXPECT_DOUBLE_EQ(z.viewAngle, 15.0);
  z.parallelProjection = true;
  z.zoom(2.0);
  EXPECT_DOUBLE_EQ(z.parallelScale, c.parallelScale / 2.0);
  EXPECT_THROW(z.zoom(0.0), Error);
}

TEST(Camera, RaysThroughPixelCentres) {
  Camera c;
  c.resetToBounds(Vec3d(-1, -1, -1), Vec3d(1, 1, 1));
  RayGenerator perspective(c, 3, 3);
  Vec3d o, d;
  perspective.ray(1, 1, o, d);  // the centre pixel looks at the focal point
  expectVec(o, c.position);
  expectVec(d, Vec3d(0, 0, -1));
  perspective.ray(1, 0, o, d);  // the top row looks up: vertical view angle 30 over 3 rows
  EXPECT_GT(d[1], 0.0);
  EXPECT_NEAR(std::atan2(d[1], -d[2]),
              std::atan(std::tan(15.0 * std::numbers::pi / 180) * 2.0 / 3.0), 1e-12);
  perspective.ray(2, 1, o, d);  // right of the image is +x
  EXPECT_GT(d[0], 0.0);

  c.parallelProjection = true;
  RayGenerator parallel(c, 4, 2);
  parallel.ray(0, 0, o, d);
  expectVec(d, Vec3d(0, 0, -1));
  // Half height = parallel scale; the top-left pixel centre is a quarter pixel in from the corner.
  EXPECT_NEAR(o[1], c.parallelScale * 0.5, 1e-12);
  EXPECT_NEAR(o[0], -c.parallelScale * 2.0 * 0.75, 1e-12);
}

TEST(Camera, ValidationNamesTheProblem) {
  Camera c;
  c.focalPoint = c.position;
  EXPECT_THROW(c.validate(), Error);
  Camera u;
  u.viewUp = Vec3d(0, 0, 1);  // parallel to the direction
  EXPECT_THROW(u.validate(), Error);
  Camera v;
  v.viewAngle = 180;
  EXPECT_THROW(v.validate(), Error);
  EXPECT_THROW(RayGenerator(Camera{}, 0, 10), Error);
}

}  // namespace
}  // namespace mfadvr
