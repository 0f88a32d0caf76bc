// Principal curvatures of level sets (core/field/Curvature.h): the formula on exact gradients
// and Hessians of spheres, cylinders and planes, and on an interpolating cubic model of
// quadratic fields, which the model reproduces, so that its exact derivatives give the
// curvatures of the true surfaces.
#include <gtest/gtest.h>

#include <cmath>

#include "core/encode/StructuredEncoder.h"
#include "core/field/Curvature.h"
#include "core/grid/StructuredGrid.h"
#include "core/model/Model.h"

namespace mfadvr {
namespace {

// f = c - (x^2 + y^2 + z^2) (a bright blob) and f = c - (x^2 + y^2) (a bright rod along z):
// gradient and Hessian at p.
void blob(const double p[3], double g[3], double h[6], bool rod) {
  for (int a = 0; a < 3; ++a) g[a] = (rod && a == 2) ? 0.0 : -2.0 * p[a];
  const double d[6] = {-2.0, 0.0, 0.0, -2.0, 0.0, rod ? 0.0 : -2.0};
  for (int i = 0; i < 6; ++i) h[i] = d[i];
}

TEST(Curvature, SpheresCylindersAndPlanesExactly) {
  const double p[3] = {0.3, -0.4, 1.2};
  double g[3], h[6];
  blob(p, g, h, false);
  const double r = std::sqrt(0.09 + 0.16 + 1.44);
  PrincipalCurvatures k = principalCurvatures(g, h);
  EXPECT_NEAR(k.k1, 1.0 / r, 1e-12);
  EXPECT_NEAR(k.k2, 1.0 / r, 1e-12);
  // The same sphere around a minimum: the signs flip.
  for (double& v : g) v = -v;
  for (double& v : h) v = -v;
  k = principalCurvatures(g, h);
  EXPECT_NEAR(k.k1, -1.0 / r, 1e-12);
  blob(p, g, h, true);
  k = principalCurvatures(g, h);
  EXPECT_NEAR(k.k1, 1.0 / 0.5, 1e-12);  // radius 0.5 about the z axis
  EXPECT_NEAR(k.k2, 0.0, 1e-12);
  // A linear field: planes, no curvature; no gradient: none at all.
  const double flat[3] = {1, 2, 3}, none[6] = {0, 0, 0, 0, 0, 0};
  k = principalCurvatures(flat, none);
  EXPECT_NEAR(k.k1, 0.0, 1e-15);
  EXPECT_NEAR(k.k2, 0.0, 1e-15);
  const double zero[3] = {0, 0, 0};
  EXPECT_TRUE(std::isnan(principalCurvatures(zero, h).k1));
}

StructuredGrid sampled(bool rod) {
  StructuredGrid g;
  g.dims = {17, 15, 13};
  g.origin = Vec3d(-1.1, -0.9, -1.0);
  g.spacing = Vec3d(0.14, 0.13, 0.17);
  g.values.resize(size_t(g.sampleCount()));
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i) {
        const Vec3d x = g.position(i, j, k);
        g.at(i, j, k) = 2.0 - x[0] * x[0] - x[1] * x[1] - (rod ? 0.0 : x[2] * x[2]);
      }
  return g;
}

// The interpolating cubic reproduces a quadratic: its curvatures are the surfaces' to 1e-3.
TEST(Curvature, ModelOfQuadraticFieldsGivesExactCurvatures) {
  for (bool rod : {false, true}) {
    const Model model = fitStructured(sampled(rod), StructuredFitOptions{});
    const std::vector<Vec3d> points{{0.3, -0.2, 0.4}, {-0.5, 0.35, -0.3}, {0.7, 0.1, 0.05}};
    std::vector<float> values(points.size());
    std::vector<Vec3f> gradients(points.size());
    std::vector<Sym3f> hessians(points.size());
    model.evaluate(points, values, gradients, hessians);
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec3d& p = points[i];
      const double r = rod ? std::hypot(p[0], p[1]) : p.norm();
      const PrincipalCurvatures k = principalCurvatures(gradients[i].data(), hessians[i].data());
      EXPECT_NEAR(k.k1, 1.0 / r, 1e-3 / r) << (rod ? "rod" : "blob") << " at point " << i;
      EXPECT_NEAR(k.k2, rod ? 0.0 : 1.0 / r, 1e-3 / r) << (rod ? "rod" : "blob") << " " << i;
    }
  }
}

}  // namespace
}  // namespace mfadvr
