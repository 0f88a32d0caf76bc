// Blend modes, clipping planes and cropping against VTK's fixed-point ray caster: our trilinear
// filter renders the same scene as vtkFixedPointVolumeRayCastMapper with the mode, planes or box
// set on it (VtkBaselineRenderer), and the images agree; each setting visibly changes the
// image, so agreement is not that of two unchanged pictures. Under a virtual X display.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/image/ImageMetrics.h"
#include "core/render/ReconstructionMethod.h"
#include "core/render/TransferFunction.h"
#include "core/util/Error.h"
#include "vtkrender/VtkBaselineRenderer.h"

namespace mfadvr {
namespace {

// A smooth field with structure off the centre: a wide blob and a narrow one beside it.
struct Scene {
  StructuredGrid grid;
  Scene() {
    grid.dims = {28, 24, 20};
    grid.origin = Vec3d(-1, -1, -1);
    grid.spacing = Vec3d(2.0 / 27, 2.0 / 23, 2.0 / 19);
    grid.source = "two blobs";
    grid.values.resize(size_t(grid.sampleCount()));
    const Vec3d c(0.45, -0.3, 0.2);
    for (std::int64_t k = 0; k < grid.dims[2]; ++k)
      for (std::int64_t j = 0; j < grid.dims[1]; ++j)
        for (std::int64_t i = 0; i < grid.dims[0]; ++i) {
          const Vec3d x = grid.position(i, j, k);
          grid.at(i, j, k) = 0.7 * std::exp(-2.0 * x.squaredNorm()) +
                             0.3 * std::exp(-10.0 * (x - c).squaredNorm());
        }
  }
};

RenderSettings sceneSettings(const StructuredGrid& g) {
  RenderSettings s;
  s.width = s.height = 96;
  s.camera.resetToBounds(g.boxMin(), g.boxMax());
  s.camera.azimuth(30);
  s.camera.elevation(20);
  s.camera.validate();
  s.transferFunction = parseTransferFunction("ramp", "cool-to-warm").resolved(0.0, 1.0);
  s.opacityUnitDistance = g.spacing[0];
  s.sampleDistance = 0.5 * g.spacing[0];
  return s;
}

Image8 ours(const Scene& scene, const RenderSettings& s) {
  SceneData data;
  data.grid = &scene.grid;
  data.differenceStep = scene.grid.spacing;
  MethodSpec spec;
  spec.method = ReconstructionMethod::Trilinear;
  return toImage8(renderMethod(data, spec, s));
}

Image8 vtk(const Scene& scene, const RenderSettings& s) {
  VtkBaselineRenderer r(VtkMethod::FixedPoint, {&scene.grid, nullptr}, s);
  r.renderFrames(1);
  return r.readBack();
}

// ours vs VTK under `s`, and ours under `s` vs ours under `plain` (the setting's effect).
void expectAgreement(const Scene& scene, const RenderSettings& s, const RenderSettings& plain,
                     const std::string& what) {
  const Image8 a = ours(scene, s);
  const ImageComparison withVtk = compareImages(a, vtk(scene, s));
  const ImageComparison effect = compareImages(a, ours(scene, plain));
  std::printf(
      "%s: trilinear vs vtk-fixedpoint %.2f dB (SSIM %.4f); against the plain render "
      "%.2f dB\n",
      what.c_str(), withVtk.psnr, withVtk.ssim, effect.psnr);
  EXPECT_GE(withVtk.psnr, 35.0) << what;
  EXPECT_LT(effect.psnr, withVtk.psnr - 8.0) << what << ": the setting barely changes the image";
}

TEST(VtkBlendModes, MaxAndMinAgreeWithFixedPoint) {
  const Scene scene;
  const RenderSettings plain = sceneSettings(scene.grid);
  for (BlendMode m : {BlendMode::Maximum, BlendMode::Minimum}) {
    RenderSettings s = plain;
    s.blend = m;
    expectAgreement(scene, s, plain, blendModeName(m));
  }
}

TEST(VtkBlendModes, ClippingPlanesAgreeWithFixedPoint) {
  const Scene scene;
  const RenderSettings plain = sceneSettings(scene.grid);
  RenderSettings s = plain;
  s.clipPlanes.push_back({Vec3d(0.1, 0.0, 0.0), Vec3d(1.0, 0.4, 0.2)});
  s.clipPlanes.push_back({Vec3d(0.0, 0.0, 0.5), Vec3d(0.0, 0.0, -1.0)});
  expectAgreement(scene, s, plain, "two clipping planes");
  // And with MIP: the extreme of what is left.
  RenderSettings mip = s;
  mip.blend = BlendMode::Maximum;
  RenderSettings plainMip = plain;
  plainMip.blend = BlendMode::Maximum;
  expectAgreement(scene, mip, plainMip, "max, clipped");
}

TEST(VtkBlendModes, CroppingAgreesWithFixedPoint) {
  const Scene scene;
  const RenderSettings plain = sceneSettings(scene.grid);
  RenderSettings s = plain;
  s.crop = DomainBox{Vec3d(-0.6, -1.0, -0.7), Vec3d(0.8, 0.5, 0.6)};
  expectAgreement(scene, s, plain, "cropped");
}

TEST(VtkBlendModes, FixedPointRefusesWhatItCannotBlend) {
  const Scene scene;
  RenderSettings s = sceneSettings(scene.grid);
  for (BlendMode m : {BlendMode::Average, BlendMode::Additive}) {
    s.blend = m;
    try {
      VtkBaselineRenderer r(VtkMethod::FixedPoint, {&scene.grid, nullptr}, s);
      ADD_FAILURE() << blendModeName(m) << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(blendModeName(m)), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace mfadvr
