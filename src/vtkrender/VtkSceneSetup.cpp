#include "vtkrender/VtkSceneSetup.h"

#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkColorTransferFunction.h>
#include <vtkDataSetTriangleFilter.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/util/Error.h"
#include "vtkrender/LeakCheckPause.h"

namespace mfadvr {

namespace {

template <typename T>
vtkSmartPointer<vtkFloatArray> floatScalars(const std::vector<T>& values) {
  auto scalars = vtkSmartPointer<vtkFloatArray>::New();
  scalars->SetName("value");
  scalars->SetNumberOfComponents(1);
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (size_t i = 0; i < values.size(); ++i)
    scalars->SetValue(static_cast<vtkIdType>(i), static_cast<float>(values[i]));
  return scalars;
}

// x of each point, with a repeated x (a jump) turned into a jump over `eps` by moving the earlier
// point left.
template <typename Point>
std::vector<double> separatedX(const std::vector<Point>& points, double eps) {
  std::vector<double> x;
  for (const Point& p : points) x.push_back(p.x);
  for (size_t i = x.size() - 1; i-- > 0;)
    if (x[i] > x[i + 1] - eps) x[i] = x[i + 1] - eps;
  return x;
}

}  // namespace

vtkSmartPointer<vtkImageData> makeImageData(const StructuredGrid& grid) {
  grid.validate();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(static_cast<int>(grid.dims[0]), static_cast<int>(grid.dims[1]),
                       static_cast<int>(grid.dims[2]));
  image->SetOrigin(grid.origin[0], grid.origin[1], grid.origin[2]);
  image->SetSpacing(grid.spacing[0], grid.spacing[1], grid.spacing[2]);
  image->GetPointData()->SetScalars(floatScalars(grid.values));  // both are x fastest
  return image;
}

vtkSmartPointer<vtkUnstructuredGrid> makeTetrahedralMesh(const ScatteredData& data) {
  if (!data.hasCells())
    throw Error(data.source + " is a " + (data.kind.empty() ? "point cloud" : data.kind) +
                " without cells: VTK's unstructured volume mappers need tetrahedra (a mesh such "
                "as .vtu or unstructured legacy .vtk)");
  data.validate();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(data.pointCount());
  for (std::int64_t i = 0; i < data.pointCount(); ++i) {
    const Vec3d& p = data.points[static_cast<size_t>(i)];
    points->SetPoint(i, p[0], p[1], p[2]);
  }
  vtkNew<vtkCellArray> cells;
  cells->AllocateExact(static_cast<vtkIdType>(data.tets.size()),
                       static_cast<vtkIdType>(4 * data.tets.size()));
  for (const Tetrahedron& t : data.tets) {
    vtkIdType ids[4] = {t[0], t[1], t[2], t[3]};
    // VTK's orientation: the first three points counter-clockwise seen from the fourth.
    const Vec3d& p0 = data.points[size_t(t[0])];
    const Vec3d a = data.points[size_t(t[1])] - p0, b = data.points[size_t(t[2])] - p0,
                c = data.points[size_t(t[3])] - p0;
    if (a.cross(b).dot(c) < 0.0) std::swap(ids[2], ids[3]);
    cells->InsertNextCell(4, ids);
  }
  auto mesh = vtkSmartPointer<vtkUnstructuredGrid>::New();
  mesh->SetPoints(points);
  mesh->SetCells(VTK_TETRA, cells);
  mesh->GetPointData()->SetScalars(floatScalars(data.values));
  return mesh;
}

vtkSmartPointer<vtkUnstructuredGrid> tetrahedralize(vtkImageData* image) {
  vtkNew<vtkDataSetTriangleFilter> filter;
  filter->SetInputData(image);
  filter->TetrahedraOnlyOn();
  filter->Update();
  auto mesh = vtkSmartPointer<vtkUnstructuredGrid>::New();
  mesh->ShallowCopy(filter->GetOutput());
  if (mesh->GetNumberOfCells() == 0)
    throw Error("tetrahedralizing the grid gave no cells (it needs at least 2 samples per axis)");
  return mesh;
}

void applyCamera(const Camera& camera, vtkRenderer* renderer) {
  vtkCamera* c = renderer->GetActiveCamera();
  c->SetPosition(camera.position.data());
  c->SetFocalPoint(camera.focalPoint.data());
  c->SetViewUp(camera.viewUp.data());
  c->SetViewAngle(camera.viewAngle);
  c->SetParallelProjection(camera.parallelProjection ? 1 : 0);
  c->SetParallelScale(camera.parallelScale);
  renderer->ResetCameraClippingRange();  // not ResetCamera: keep our framing exactly
}

void applyTransferFunction(const RenderSettings& s, vtkVolumeProperty* property,
                           VtkOpacityReading reading) {
  const TransferFunction& tf = s.transferFunction;
  double lo = tf.opacity.front().x, hi = tf.opacity.back().x;
  lo = std::min(lo, tf.color.front().x);
  hi = std::max(hi, tf.color.back().x);
  const double eps = 1e-6 * std::max(hi - lo, 1e-300);

  vtkNew<vtkColorTransferFunction> color;
  color->SetColorSpaceToRGB();
  const std::vector<double> cx = separatedX(tf.color, eps);
  for (size_t i = 0; i < cx.size(); ++i) {
    const Vec3f& rgb = tf.color[i].rgb;
    color->AddRGBPoint(cx[i], rgb[0], rgb[1], rgb[2]);
  }
  vtkNew<vtkPiecewiseFunction> opacity;
  const std::vector<double> ox = separatedX(tf.opacity, eps);
  if (reading == VtkOpacityReading::PerUnitDistance) {
    for (size_t i = 0; i < ox.size(); ++i) opacity->AddPoint(ox[i], tf.opacity[i].alpha);
  } else {
    // -ln(1 - a) is not linear in a: the TF's points keep its jumps and kinks, the points
    // between follow the curve.
    auto attenuation = [](double a) { return -std::log1p(-std::min(a, 1.0 - 1e-6)); };
    auto near = [&](const std::vector<double>& xs, double x) {
      return std::any_of(xs.begin(), xs.end(), [&](double p) { return std::abs(p - x) < 2 * eps; });
    };
    std::vector<double> used = ox;
    for (size_t i = 0; i < ox.size(); ++i)
      opacity->AddPoint(ox[i], attenuation(tf.opacity[i].alpha));
    const int between = 256;
    const double olo = ox.front(), ohi = ox.back();
    for (int k = 1; k < between; ++k) {
      const double x = olo + (ohi - olo) * k / between;
      if (near(ox, x)) continue;
      opacity->AddPoint(x, attenuation(tf.opacityAt(x)));
      used.push_back(x);
    }
    // VTK's partial pre-integration (Bunyk's and ZSweep's integrator) splits a ray segment only
    // at the colour function's points and the scalar range's ends: of the opacity function it
    // keeps just the first point, and is linear in between. So every opacity point is also a
    // colour point, with the colour the function has there (which leaves it unchanged).
    for (const double x : used)
      if (!near(cx, x)) {
        const Vec3f rgb = tf.colorAt(x);
        color->AddRGBPoint(x, rgb[0], rgb[1], rgb[2]);
      }
  }

  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->SetScalarOpacityUnitDistance(s.opacityUnitDistance);
  // Gradient opacity and the 2-D table, as vtkMFAVolumeMapper reads them (|grad f| per world
  // unit; the table placed by its origin and spacing).
  property->SetTransferFunctionMode(vtkVolumeProperty::TF_1D);
  property->SetDisableGradientOpacity(s.gradientOpacity.empty() ? 1 : 0);
  if (!s.gradientOpacity.empty()) {
    vtkNew<vtkPiecewiseFunction> gradient;
    const std::vector<double> gx = separatedX(
        s.gradientOpacity,
        1e-6 * std::max(s.gradientOpacity.back().x - s.gradientOpacity.front().x, 1e-300));
    for (size_t i = 0; i < gx.size(); ++i) gradient->AddPoint(gx[i], s.gradientOpacity[i].alpha);
    property->SetGradientOpacity(gradient);
  }
  if (s.transferFunction2D) {
    const TransferFunction2D& t = *s.transferFunction2D;
    vtkNew<vtkImageData> image;
    image->SetDimensions(t.width, t.height, 1);
    image->SetOrigin(t.valueLo, t.gradientLo, 0.0);
    image->SetSpacing((t.valueHi - t.valueLo) / (t.width - 1),
                      (t.gradientHi - t.gradientLo) / (t.height - 1), 1.0);
    vtkNew<vtkFloatArray> rgba;
    rgba->SetNumberOfComponents(4);
    rgba->SetNumberOfTuples(static_cast<vtkIdType>(t.width) * t.height);
    std::copy(t.rgba.begin(), t.rgba.end(), rgba->GetPointer(0));
    image->GetPointData()->SetScalars(rgba);
    property->SetTransferFunction2D(image);
    property->SetTransferFunctionMode(vtkVolumeProperty::TF_2D);
  }
  property->SetShade(s.shade ? 1 : 0);
  property->SetAmbient(s.lighting.ambient);
  property->SetDiffuse(s.lighting.diffuse);
  property->SetSpecular(s.lighting.specular);
  property->SetSpecularPower(s.lighting.specularPower);
}

void applyLighting(const Lighting& lighting, vtkRenderer* renderer) {
  renderer->AutomaticLightCreationOff();
  renderer->RemoveAllLights();
  renderer->TwoSidedLightingOn();  // ours is two-sided: a volume has no outside

  // The ambient term, once.
  vtkNew<vtkLight> ambient;
  ambient->SetLightTypeToHeadlight();
  ambient->SetAmbientColor(1.0, 1.0, 1.0);
  ambient->SetDiffuseColor(0.0, 0.0, 0.0);
  ambient->SetSpecularColor(0.0, 0.0, 0.0);
  ambient->SetIntensity(1.0);
  renderer->AddLight(ambient);

  if (lighting.headlight) {
    vtkNew<vtkLight> head;
    head->SetLightTypeToHeadlight();
    head->SetAmbientColor(0.0, 0.0, 0.0);
    head->SetDiffuseColor(1.0, 1.0, 1.0);
    head->SetSpecularColor(1.0, 1.0, 1.0);
    head->SetIntensity(1.0);
    renderer->AddLight(head);
  }
  for (const DirectionalLight& l : lighting.lights) {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->PositionalOff();
    // Shines from its position towards its focal point.
    light->SetPosition(-l.direction[0], -l.direction[1], -l.direction[2]);
    light->SetFocalPoint(0.0, 0.0, 0.0);
    light->SetAmbientColor(0.0, 0.0, 0.0);
    light->SetDiffuseColor(l.color[0], l.color[1], l.color[2]);
    light->SetSpecularColor(l.color[0], l.color[1], l.color[2]);
    light->SetIntensity(l.intensity);
    renderer->AddLight(light);
  }
}

void applyBackground(const Vec3f& background, vtkRenderer* renderer) {
  renderer->SetBackground(background[0], background[1], background[2]);
}

Image8 readWindowRgb(vtkRenderWindow* window) {
  const LeakCheckPause pause;
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkImageData* out = grab->GetOutput();
  int dims[3];
  out->GetDimensions(dims);
  auto* data = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetScalars());
  if (!data || data->GetNumberOfComponents() != 3 ||
      data->GetNumberOfTuples() != vtkIdType(dims[0]) * dims[1])
    throw Error("VTK read-back did not give 8-bit RGB");
  Image8 img;
  img.width = dims[0];
  img.height = dims[1];
  img.channels = 3;
  img.data.resize(size_t(3) * dims[0] * dims[1]);
  // VTK's row 0 is at the bottom; ours at the top.
  const unsigned char* src = data->GetPointer(0);
  const size_t row = size_t(3) * dims[0];
  for (int y = 0; y < dims[1]; ++y)
    std::copy_n(src + size_t(dims[1] - 1 - y) * row, row, img.data.data() + size_t(y) * row);
  return img;
}

}  // namespace mfadvr
