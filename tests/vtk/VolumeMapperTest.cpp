// vtkMFAVolumeMapper inside real VTK scenes (off screen, under xvfb-run): its image against the
// core renderer's image of the same scene, written out independently; blending with opaque
// geometry; volume transforms; image sample distance; models and data sets on the standard
// input port.
#include <gtest/gtest.h>

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkContourValues.h>
#include <vtkDataSetTriangleFilter.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include "TestSupport.h"
#include "VtkSceneFixture.h"
#include "core/field/ModelField.h"
#include "core/image/ImageMetrics.h"
#include "core/image/PngFile.h"
#include "core/model/ModelFile.h"
#include "core/render/RayCaster.h"
#include "vtkMFAEncoder.h"
#include "vtkMFAReader.h"

namespace mfadvr::test {
namespace {

Image8 coreImage(const Model& model, const RenderSettings& s) {
  const ModelField field(model);
  return toImage8(renderVolume(field, s));
}

TEST(VolumeMapper, ShadedImageMatchesTheCoreRenderer) {
  VtkVolumeScene scene(marschnerLobbModel(), true);
  const Image8 mapped = scene.render();
  const Image8 core = coreImage(*marschnerLobbModel(), scene.coreSettings());
  EXPECT_GT(coverage(core, scene.coreSettings().background), 0.3);
  const ImageComparison c = compareImages(mapped, core);
  if (std::getenv("MFADVR_DEBUG_IMAGES")) {
    writePng("/tmp/mapped.png", mapped);
    writePng("/tmp/core.png", core);
    writePng("/tmp/diff.png", differenceImage(mapped, core, 8.0));
  }
  // Only 8-bit rounding of the mapper's premultiplied image and of the window's blending
  // separate them.
  EXPECT_GT(c.psnr, 45.0);
  EXPECT_GT(c.ssim, 0.995);
  std::printf("mapper vs core, shaded: PSNR %.2f dB, SSIM %.4f\n", c.psnr, c.ssim);

  // The bound can fail: a slightly different camera is far below it.
  RenderSettings moved = scene.coreSettings();
  moved.camera.azimuth(2.0);
  EXPECT_LT(compareImages(mapped, coreImage(*marschnerLobbModel(), moved)).psnr, 35.0);
}

TEST(VolumeMapper, UnshadedImageMatchesTheCoreRenderer) {
  VtkVolumeScene scene(marschnerLobbModel(), false);
  const Image8 mapped = scene.render();
  EXPECT_GT(compareImages(mapped, coreImage(*marschnerLobbModel(), scene.coreSettings())).psnr,
            40.0);
  EXPECT_GT(scene.mapper->GetTimeToDraw(), 0.0);
}

// VTK's blend modes, clipping planes and cropping box reach the ray caster: each mapped image
// matches the core renderer given the same mode, planes or box, and differs from the plain one.
TEST(VolumeMapper, HonoursBlendModesClippingAndCropping) {
  VtkVolumeScene scene(marschnerLobbModel(), false);
  const Image8 plain = scene.render();
  struct Case {
    const char* what;
    std::function<void(VtkVolumeScene&, RenderSettings&)> set;
  };
  const Case cases[] = {
      {"max",
       [](VtkVolumeScene& v, RenderSettings& s) {
         v.mapper->SetBlendModeToMaximumIntensity();
         s.blend = BlendMode::Maximum;
       }},
      {"min",
       [](VtkVolumeScene& v, RenderSettings& s) {
         v.mapper->SetBlendModeToMinimumIntensity();
         s.blend = BlendMode::Minimum;
       }},
      {"average in [0.3, 0.9]",
       [](VtkVolumeScene& v, RenderSettings& s) {
         v.mapper->SetBlendModeToAverageIntensity();
         v.mapper->SetAverageIPScalarRange(0.3, 0.9);
         s.blend = BlendMode::Average;
         s.averageRange = std::pair(0.3, 0.9);
       }},
      {"additive",
       [](VtkVolumeScene& v, RenderSettings& s) {
         v.mapper->SetBlendModeToAdditive();
         s.blend = BlendMode::Additive;
       }},
      {"isosurfaces 0.5 and 0.7",
       [](VtkVolumeScene& v, RenderSettings& s) {
         v.mapper->SetBlendModeToIsoSurface();
         v.property->GetIsoSurfaceValues()->SetValue(0, 0.5);
         v.property->GetIsoSurfaceValues()->SetValue(1, 0.7);
         s.blend = BlendMode::Iso;
         s.isoSurfaces = {{0.5, {}, {}}, {0.7, {}, {}}};
       }},
      {"clipping plane",
       [](VtkVolumeScene& v, RenderSettings& s) {
         vtkNew<vtkPlane> plane;
         plane->SetOrigin(0.1, 0.0, 0.0);
         plane->SetNormal(-1.0, 0.2, 0.3);
         v.mapper->AddClippingPlane(plane);
         s.clipPlanes.push_back({Vec3d(0.1, 0, 0), Vec3d(-1.0, 0.2, 0.3)});
       }},
      {"cropping",
       [](VtkVolumeScene& v, RenderSettings& s) {
         v.mapper->CroppingOn();
         v.mapper->SetCroppingRegionPlanes(-0.8, 0.6, -1.0, 0.4, -0.5, 1.0);
         v.mapper->SetCroppingRegionFlagsToSubVolume();
         s.crop = DomainBox{Vec3d(-0.8, -1.0, -0.5), Vec3d(0.6, 0.4, 1.0)};
       }},
      {"gradient opacity",
       [](VtkVolumeScene& v, RenderSettings& s) {
         vtkNew<vtkPiecewiseFunction> g;
         g->AddPoint(1.5, 0.0);
         g->AddPoint(3.0, 1.0);
         v.property->SetGradientOpacity(g);
         s.gradientOpacity = {{1.5, 0.0f}, {3.0, 1.0f}};
       }},
      {"2-D transfer function",
       [](VtkVolumeScene& v, RenderSettings& s) {
         // Opaque orange at high |grad f| and values above 0.4, faint blue elsewhere.
         TransferFunction2D t;
         t.width = 16;
         t.height = 8;
         t.valueLo = 0.0;
         t.valueHi = 1.0;
         t.gradientLo = 0.0;
         t.gradientHi = 4.0;
         vtkNew<vtkImageData> image;
         image->SetDimensions(t.width, t.height, 1);
         image->SetSpacing(1.0 / (t.width - 1), 4.0 / (t.height - 1), 1.0);
         vtkNew<vtkFloatArray> rgba;
         rgba->SetNumberOfComponents(4);
         rgba->SetNumberOfTuples(t.width * t.height);
         for (int j = 0; j < t.height; ++j)
           for (int i = 0; i < t.width; ++i) {
             const bool edge = j >= 3 && i >= 6;
             const float e[4] = {edge ? 1.0f : 0.2f, edge ? 0.6f : 0.4f, edge ? 0.1f : 1.0f,
                                 edge ? 0.8f : 0.02f};
             rgba->SetTypedTuple(j * t.width + i, e);
             t.rgba.insert(t.rgba.end(), e, e + 4);
           }
         image->GetPointData()->SetScalars(rgba);
         v.property->SetTransferFunction2D(image);
         v.property->SetTransferFunctionMode(vtkVolumeProperty::TF_2D);
         s.transferFunction2D = t;
       }},
  };
  for (const Case& c : cases) {
    VtkVolumeScene v(marschnerLobbModel(), false);
    RenderSettings s = v.coreSettings();
    c.set(v, s);
    const Image8 mapped = v.render();
    const double withCore = compareImages(mapped, coreImage(*marschnerLobbModel(), s)).psnr;
    const double effect = compareImages(mapped, plain).psnr;
    std::printf("mapper vs core, %s: PSNR %.2f dB (against the plain image %.2f dB)\n", c.what,
                withCore, effect);
    EXPECT_GT(withCore, 40.0) << c.what;
    EXPECT_LT(effect, 30.0) << c.what;
  }
}

// An opaque sphere half inside the volume: the volume in front of it is composited over it,
// the volume behind it is hidden. The expected image is the core renderer's volume, with rays
// ending on the exact sphere, composited over VTK's image of the sphere alone.
TEST(VolumeMapper, BlendsWithOpaqueGeometryByDepth) {
  VtkVolumeScene scene(marschnerLobbModel(), false);
  const Vec3d centre(0.4, 0.0, 0.5);
  const double radius = 0.55;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(centre[0], centre[1], centre[2]);
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(256);
  sphere->SetPhiResolution(256);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(sphereMapper);
  actor->GetProperty()->SetColor(0.9, 0.8, 0.2);
  scene.renderer->AddActor(actor);

  scene.renderer->RemoveVolume(scene.volume);
  const Image8 sphereOnly = scene.render();
  scene.renderer->AddVolume(scene.volume);
  const Image8 both = scene.render();

  RenderSettings s = scene.coreSettings();
  s.background = Vec3f::Zero();
  const RayGenerator rays(s.camera, s.width, s.height);
  std::vector<float> ends(static_cast<size_t>(s.width) * s.height, INFINITY);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      Vec3d o, d;
      rays.ray(x, y, o, d);
      const Vec3d oc = o - centre;
      const double b = oc.dot(d), disc = b * b - (oc.squaredNorm() - radius * radius);
      if (disc >= 0) ends[static_cast<size_t>(y) * s.width + x] = float(-b - std::sqrt(disc));
    }
  auto composite = [&](bool withEnds) {
    RenderSettings t = s;
    if (withEnds) t.rayEnd = ends;
    const Image volume = renderVolume(ModelField(*marschnerLobbModel()), t);
    Image8 out = sphereOnly;
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const float* v = volume.pixel(x, y);
        for (int c = 0; c < 3; ++c) {
          uint8_t& o = out.data[3 * (static_cast<size_t>(y) * s.width + x) + c];
          o = static_cast<uint8_t>(
              std::lround(255.0f * std::clamp(v[c] + (1 - v[3]) * o / 255.0f, 0.0f, 1.0f)));
        }
      }
    return out;
  };
  const double cut = compareImages(both, composite(true)).psnr;
  const double uncut = compareImages(both, composite(false)).psnr;
  std::printf("opaque sphere: PSNR %.2f dB with ray ends, %.2f dB without\n", cut, uncut);
  // Polygonal vs exact sphere silhouettes and 8-bit rounding separate the first pair.
  EXPECT_GT(cut, 40.0);
  // Ignoring the depth (the volume drawn over the whole sphere) is clearly worse.
  EXPECT_LT(uncut, cut - 6.0) << "cut " << cut << " uncut " << uncut;
}

// The window depth buffer after a frame, row 0 at the bottom (VTK's order).
std::vector<float> windowDepth(VtkVolumeScene& v) {
  const int n = VtkVolumeScene::kSize;
  std::vector<float> z(static_cast<size_t>(n) * n);
  const LeakCheckPause pause;
  v.window->GetZbufferData(0, 0, n - 1, n - 1, z.data());
  return z;
}

// What the mapper writes into the depth buffer: isosurface hits by default, nothing with
// WriteDepthNever, the composite depth (opacity 0.5) with WriteDepthAlways. Each written pixel,
// taken back to a distance along its ray, is the core renderer's depth of that ray; the others
// keep the cleared buffer (1).
TEST(VolumeMapper, WritesItsDepthIntoTheDepthBuffer) {
  struct Case {
    const char* what;
    bool iso;
    int write;
  };
  for (const Case c : {Case{"iso, default", true, -1}, Case{"iso, never", true, 0},
                       Case{"composite, default", false, -1}, Case{"composite, always", false, 2}}) {
    VtkVolumeScene v(marschnerLobbModel(), false);
    RenderSettings s = v.coreSettings();
    if (c.iso) {
      v.mapper->SetBlendModeToIsoSurface();
      v.property->GetIsoSurfaceValues()->SetValue(0, 0.5);
      s.blend = BlendMode::Iso;
      s.isoSurfaces = {{0.5, {}, {}}};
    }
    if (c.write >= 0) v.mapper->SetWriteDepth(c.write);
    const bool writes = c.write == 2 || (c.write < 0 && c.iso);
    v.render();
    const std::vector<float> z = windowDepth(v);
    s.depth = true;
    const Image core = renderVolume(ModelField(*marschnerLobbModel()), s);
    vtkMatrix4x4* worldToClip =
        v.renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(1.0, -1, 1);
    vtkNew<vtkMatrix4x4> clipToWorld;
    vtkMatrix4x4::Invert(worldToClip, clipToWorld);
    const RayGenerator rays(s.camera, s.width, s.height);
    const int n = VtkVolumeScene::kSize;
    int written = 0, hits = 0;
    double worst = 0.0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float t = core.depth[static_cast<size_t>(y) * n + x];
        const float zw = z[static_cast<size_t>(n - 1 - y) * n + x];
        if (zw < 1.0f) ++written;
        if (!std::isfinite(t)) {
          EXPECT_EQ(zw, 1.0f) << c.what << " pixel " << x << "," << y;
          continue;
        }
        ++hits;
        if (!writes) {
          EXPECT_EQ(zw, 1.0f) << c.what;
          continue;
        }
        const double clip[4] = {2.0 * (x + 0.5) / n - 1.0, 2.0 * (n - 1 - y + 0.5) / n - 1.0,
                                2.0 * zw - 1.0, 1.0};
        double world[4];
        clipToWorld->MultiplyPoint(clip, world);
        Vec3d o, d;
        rays.ray(x, y, o, d);
        const Vec3d p = Vec3d(world[0], world[1], world[2]) / world[3];
        worst = std::max(worst, std::abs((p - o).dot(d) - t));
      }
    std::printf("depth buffer, %s: %d pixels written, %d rays with a depth, worst %.2e\n", c.what,
                written, hits, worst);
    EXPECT_GT(hits, n * n / 10) << c.what;
    EXPECT_EQ(written, writes ? hits : 0) << c.what;
    EXPECT_LT(worst, 2e-3) << c.what;  // the box is 2 wide; the buffer has 24 bits
  }
}

// Moving the volume and the camera together, or scaling both (with the world-unit distances),
// leaves the image unchanged.
TEST(VolumeMapper, FollowsTheVolumeTransform) {
  VtkVolumeScene reference(marschnerLobbModel(), true);
  const Image8 base = reference.render();

  VtkVolumeScene moved(marschnerLobbModel(), true);
  const Vec3d shift(5.0, -2.0, 1.0);
  moved.volume->SetPosition(shift[0], shift[1], shift[2]);
  vtkCamera* c = moved.renderer->GetActiveCamera();
  const Vec3d position = Vec3d(2.2, 1.6, 3.4) + shift, focal = Vec3d(0.05, -0.05, 0.0) + shift;
  c->SetPosition(position[0], position[1], position[2]);
  c->SetFocalPoint(focal[0], focal[1], focal[2]);
  EXPECT_GT(compareImages(base, moved.render()).psnr, 45.0);
  double b[6];
  moved.volume->GetBounds(b);
  EXPECT_NEAR(b[0], -1.0 + shift[0], 1e-9);
  EXPECT_NEAR(b[5], 1.0 + shift[2], 1e-9);

  VtkVolumeScene scaled(marschnerLobbModel(), true);
  scaled.volume->SetScale(2.0);
  scaled.mapper->SetSampleDistance(0.04);
  scaled.property->SetScalarOpacityUnitDistance(0.2);
  c = scaled.renderer->GetActiveCamera();
  c->SetPosition(4.4, 3.2, 6.8);
  c->SetFocalPoint(0.1, -0.1, 0.0);
  EXPECT_GT(compareImages(base, scaled.render()).psnr, 40.0);
}

// Off-axis frusta (a shifted window centre, as ParaView's client-server rendering and VTK's
// tiled screenshots use) come from VTK's own projection: the picture moves with the window.
TEST(VolumeMapper, FollowsAShiftedWindowCenter) {
  VtkVolumeScene scene(marschnerLobbModel(), true);
  const Image8 centred = scene.render();
  scene.renderer->GetActiveCamera()->SetWindowCenter(0.25, 0.0);  // a quarter of the width
  const Image8 shifted = scene.render();
  // Columns [shift, size) of one image against columns [0, size - shift) of the other.
  constexpr int kShift = VtkVolumeScene::kSize / 8;
  auto compareShifted = [&](const Image8& a, const Image8& b) {
    Image8 ca, cb;
    ca.width = cb.width = VtkVolumeScene::kSize - kShift;
    ca.height = cb.height = VtkVolumeScene::kSize;
    for (int y = 0; y < VtkVolumeScene::kSize; ++y)
      for (int x = 0; x < ca.width; ++x)
        for (int c = 0; c < 3; ++c) {
          ca.data.push_back(a.data[3 * (y * VtkVolumeScene::kSize + x + kShift) + c]);
          cb.data.push_back(b.data[3 * (y * VtkVolumeScene::kSize + x) + c]);
        }
    return compareImages(ca, cb).psnr;
  };
  // A window centre of 0.25 (normalized device units) moves the picture by 0.25 / 2 of the
  // width, one way; the other way does not match.
  const double oneWay = compareShifted(centred, shifted),
               otherWay = compareShifted(shifted, centred);
  EXPECT_GT(std::max(oneWay, otherWay), 40.0) << oneWay << " " << otherWay;
  EXPECT_LT(std::min(oneWay, otherWay), 30.0) << oneWay << " " << otherWay;
}

TEST(VolumeMapper, ImageSampleDistanceRendersFewerRays) {
  VtkVolumeScene scene(marschnerLobbModel(), true);
  const Image8 full = scene.render();
  scene.mapper->AutoAdjustSampleDistancesOff();
  scene.mapper->SetImageSampleDistance(2.0);
  const Image8 coarse = scene.render();
  EXPECT_DOUBLE_EQ(scene.mapper->GetLastImageSampleDistance(), 2.0);
  const double psnr = compareImages(full, coarse).psnr;
  EXPECT_GT(psnr, 20.0);  // the same picture, magnified
  EXPECT_LT(psnr, 40.0);  // but not the full-resolution one

  // Magnified smoothly, not in blocks: with one ray per 4x4 pixels, a blocky magnification
  // would repeat each colour over whole 4-pixel runs; bilinear magnification changes the
  // colour between most horizontal neighbours where the full image does.
  scene.mapper->SetImageSampleDistance(4.0);
  const Image8 coarser = scene.render();
  int changing = 0, equal = 0;
  for (int y = 0; y < coarser.height; ++y)
    for (int x = 0; x + 1 < coarser.width; ++x) {
      const std::uint8_t* a = &coarser.data[(static_cast<size_t>(y) * coarser.width + x) * 3];
      const std::uint8_t* f = &full.data[(static_cast<size_t>(y) * full.width + x) * 3];
      if (f[0] == f[3] && f[1] == f[4] && f[2] == f[5]) continue;  // flat in the full image
      ++changing;
      if (a[0] == a[3] && a[1] == a[4] && a[2] == a[5]) ++equal;
    }
  ASSERT_GT(changing, 1000);
  EXPECT_LT(equal, changing / 3);  // blocky: about 3 in 4 neighbours would be equal
}

TEST(VolumeMapper, EncodesImageDataOnTheStandardPort) {
  const auto ml = makeBuiltin("marschner-lobb");
  const StructuredGrid grid = sampleBuiltin(*ml, {41, 41, 41});
  const vtkSmartPointer<vtkImageData> image = imageOf(grid);

  VtkVolumeScene scene(marschnerLobbModel(), true);
  const Image8 viaModel = scene.render();
  scene.mapper->SetInputData(image);
  const Image8 viaImage = scene.render();
  ASSERT_NE(scene.mapper->GetMFAInput(), nullptr);
  int counts[3];
  scene.mapper->GetMFAInput()->GetNumberOfControlPoints(counts);
  EXPECT_EQ(counts[0], 41);  // the default fit interpolates
  EXPECT_GT(compareImages(viaModel, viaImage).psnr, 45.0);
  double b[6];
  scene.mapper->GetBounds(b);
  EXPECT_DOUBLE_EQ(b[0], -1.0);
  EXPECT_DOUBLE_EQ(b[3], 1.0);
}

// The idiom of every VTK program: a producer's output port on the mapper's standard port, for
// a reader's model, an encoder's model and a data set to encode; the old MFA-port names alias it.
TEST(VolumeMapper, TakesModelsOnTheStandardInputPort) {
  const auto path = scratchDir() / "mapper-port.mfa";
  saveModel(*marschnerLobbModel(), path);
  VtkVolumeScene scene(marschnerLobbModel(), true);
  const Image8 reference = scene.render();

  vtkNew<vtkMFAReader> reader;
  reader->SetFileName(path.c_str());
  scene.mapper->SetInputConnection(reader->GetOutputPort());
  EXPECT_EQ(scene.mapper->GetNumberOfInputPorts(), 1);
  const Image8 viaReader = scene.render();
  EXPECT_EQ(compareImages(reference, viaReader).mse, 0.0);
  EXPECT_EQ(scene.mapper->GetDataObjectInput(), reader->GetOutput());

  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputData(imageOf(sampleBuiltin(*makeBuiltin("marschner-lobb"), {41, 41, 41})));
  scene.mapper->SetInputConnection(encoder->GetOutputPort());
  EXPECT_GT(compareImages(reference, scene.render()).psnr, 45.0);

  scene.mapper->SetMFAInputConnection(reader->GetOutputPort());
  EXPECT_EQ(compareImages(reference, scene.render()).mse, 0.0);
  EXPECT_EQ(scene.mapper->GetNumberOfInputConnections(0), 1);
}

// Any data set goes to the encoder: here a tetrahedral mesh, fitted with a domain mask.
TEST(VolumeMapper, EncodesAMeshOnTheStandardPort) {
  vtkNew<vtkDataSetTriangleFilter> tets;
  tets->SetInputData(imageOf(sampleBuiltin(*makeBuiltin("marschner-lobb"), {15, 15, 15})));
  VtkVolumeScene scene(marschnerLobbModel(), true);
  scene.mapper->GetEncoder()->SetNumberOfControlPoints(12, 12, 12);
  scene.mapper->SetInputConnection(tets->GetOutputPort());
  const Image8 image = scene.render();
  ASSERT_NE(scene.mapper->GetMFAInput(), nullptr);
  EXPECT_TRUE(scene.mapper->GetMFAInput()->HasDomainMask());
  EXPECT_GT(coverage(image, scene.coreSettings().background), 0.2);
}

TEST(VolumeMapper, RendersNothingWithoutInput) {
  VtkVolumeScene scene(marschnerLobbModel(), true);
  scene.mapper->RemoveAllInputConnections(0);
  const Image8 empty = scene.render();
  EXPECT_EQ(coverage(empty, scene.coreSettings().background), 0.0);
}

// SetDevice: the device used is reported; DeviceAuto falls back to the CPU with the reason when
// no GPU is usable, and DeviceCUDA then reports an error and draws nothing. Where a GPU is
// usable, its image agrees with the CPU's.
TEST(VolumeMapper, DeviceChoiceIsReportedAndCudaWithoutAGpuDrawsNothing) {
  VtkVolumeScene scene(marschnerLobbModel(), true);
  scene.mapper->SetDeviceToCPU();
  const Image8 cpu = scene.render();
  EXPECT_EQ(scene.mapper->GetLastDevice(), vtkMFAVolumeMapper::DeviceCPU);
  EXPECT_GT(coverage(cpu, scene.coreSettings().background), 0.3);

  scene.mapper->SetDeviceToAuto();
  const Image8 automatic = scene.render();
  const bool gpu = scene.mapper->GetLastDevice() == vtkMFAVolumeMapper::DeviceCUDA;
  const std::string description = scene.mapper->GetLastDeviceDescription();
  if (gpu) {
    EXPECT_GT(compareImages(automatic, cpu).psnr, 45.0) << description;
  } else {
    EXPECT_EQ(automatic.data, cpu.data);
    EXPECT_NE(description.find("; "), std::string::npos) << "no reason given: " << description;
  }

  int errors = 0;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&errors);
  onError->SetCallback(
      [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
  scene.mapper->AddObserver(vtkCommand::ErrorEvent, onError);
  scene.mapper->SetDeviceToCUDA();
  const Image8 cuda = scene.render();
  if (gpu) {
    EXPECT_EQ(errors, 0);
    EXPECT_GT(compareImages(cuda, cpu).psnr, 45.0);
  } else {
    EXPECT_GE(errors, 1);
    EXPECT_EQ(coverage(cuda, scene.coreSettings().background), 0.0);
  }
}

}  // namespace
}  // namespace mfadvr::test
