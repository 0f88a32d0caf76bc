#pragma once
// A small VTK scene around an MFA model, rendered off screen, and the same scene described
// independently for the core ray caster, so that the mapper's image can be compared with the
// core renderer's.
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <cmath>
#include <memory>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/image/Image.h"
#include "core/model/Model.h"
#include "core/render/RenderSettings.h"
#include "vtkMFAModelData.h"
#include "vtkMFAVolumeMapper.h"
#include "vtkrender/LeakCheckPause.h"
#include "vtkrender/VtkSceneSetup.h"

namespace mfadvr::test {

// Marschner-Lobb sampled at 41^3 on [-1,1]^3 and interpolated by a cubic model.
inline std::shared_ptr<const Model> marschnerLobbModel() {
  static const auto model = [] {
    const auto ml = makeBuiltin("marschner-lobb");
    return std::make_shared<const Model>(
        fitStructured(sampleBuiltin(*ml, {41, 41, 41}), StructuredFitOptions{}));
  }();
  return model;
}

inline vtkSmartPointer<vtkImageData> imageOf(const StructuredGrid& grid,
                                             const char* name = "value") {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(int(grid.dims[0]), int(grid.dims[1]), int(grid.dims[2]));
  image->SetOrigin(grid.origin.data());
  image->SetSpacing(grid.spacing.data());
  vtkNew<vtkDoubleArray> values;
  values->SetName(name);
  values->SetNumberOfTuples(static_cast<vtkIdType>(grid.values.size()));
  std::copy(grid.values.begin(), grid.values.end(), values->GetPointer(0));
  image->GetPointData()->SetScalars(values);
  return image;
}

// Fraction of pixels that differ from the background colour by more than a few levels.
inline double coverage(const Image8& img, const Vec3f& background) {
  size_t covered = 0;
  for (size_t p = 0; p < img.data.size() / 3; ++p)
    for (int c = 0; c < 3; ++c)
      if (std::abs(img.data[3 * p + c] - background[c] * 255.0f) > 4.0f) {
        ++covered;
        break;
      }
  return static_cast<double>(covered) / (img.data.size() / 3);
}

struct VtkVolumeScene {
  static constexpr int kSize = 128;
  vtkNew<vtkMFAModelData> data;
  vtkNew<vtkMFAVolumeMapper> mapper;
  vtkNew<vtkColorTransferFunction> color;
  vtkNew<vtkPiecewiseFunction> opacity;
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkVolume> volume;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;

  explicit VtkVolumeScene(std::shared_ptr<const Model> model, bool shade = true) {
    data->SetModel(std::move(model));
    mapper->SetInputData(data.GetPointer());
    mapper->SetSampleDistance(0.02);
    color->AddRGBPoint(0.0, 0.23, 0.30, 0.75);
    color->AddRGBPoint(0.5, 0.87, 0.87, 0.87);
    color->AddRGBPoint(1.0, 0.71, 0.02, 0.15);
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(0.45, 0.0);
    opacity->AddPoint(0.55, 0.8);
    opacity->AddPoint(1.0, 0.8);
    property->SetColor(color);
    property->SetScalarOpacity(opacity);
    property->SetScalarOpacityUnitDistance(0.1);
    property->SetShade(shade ? 1 : 0);
    property->SetAmbient(0.2);
    property->SetDiffuse(0.7);
    property->SetSpecular(0.3);
    property->SetSpecularPower(16);
    volume->SetMapper(mapper);
    volume->SetProperty(property);
    renderer->AddVolume(volume);
    renderer->SetBackground(0.1, 0.2, 0.3);
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetSize(kSize, kSize);
    window->AddRenderer(renderer);
    vtkCamera* c = renderer->GetActiveCamera();
    c->SetPosition(2.2, 1.6, 3.4);
    c->SetFocalPoint(0.05, -0.05, 0.0);
    c->SetViewUp(0, 1, 0);
    c->SetViewAngle(35);
    renderer->ResetCameraClippingRange();
  }

  // Mesa keeps process-lifetime allocations inside VTK's window calls (LeakCheckPause.h).
  Image8 render() {
    renderer->ResetCameraClippingRange();
    {
      const LeakCheckPause pause;
      window->Render();
    }
    return readWindowRgb(window);
  }

  ~VtkVolumeScene() {
    const LeakCheckPause pause;
    window->Finalize();
  }

  // The same scene for the core renderer, written out by hand (not converted from VTK): the
  // renderer's automatic light is a white headlight of intensity 1.
  RenderSettings coreSettings() const {
    RenderSettings s;
    s.width = s.height = kSize;
    s.camera.position = Vec3d(2.2, 1.6, 3.4);
    s.camera.focalPoint = Vec3d(0.05, -0.05, 0.0);
    s.camera.viewUp = Vec3d(0, 1, 0);
    s.camera.viewAngle = 35;
    s.camera.orthogonalizeViewUp();
    s.transferFunction.space = TfSpace::Data;
    s.transferFunction.color = {{0.0, Vec3f(0.23f, 0.30f, 0.75f)},
                                {0.5, Vec3f(0.87f, 0.87f, 0.87f)},
                                {1.0, Vec3f(0.71f, 0.02f, 0.15f)}};
    s.transferFunction.opacity = {{0.0, 0.0f}, {0.45, 0.0f}, {0.55, 0.8f}, {1.0, 0.8f}};
    s.opacityUnitDistance = 0.1;
    s.sampleDistance = 0.02;
    s.shade = property->GetShade() != 0;
    s.lighting.ambient = 0.2f;
    s.lighting.diffuse = 0.7f;
    s.lighting.specular = 0.3f;
    s.lighting.specularPower = 16.0f;
    s.lighting.headlight = true;
    s.background = Vec3f(0.1f, 0.2f, 0.3f);
    return s;
  }
};

}  // namespace mfadvr::test
