#include "vtkrender/VtkBaselineRenderer.h"

#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkDataSet.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkProjectedTetrahedraMapper.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridVolumeRayCastMapper.h>
#include <vtkUnstructuredGridVolumeZSweepMapper.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "core/util/Error.h"
#include "vtkrender/DisplayCheck.h"
#include "vtkrender/LeakCheckPause.h"
#include "vtkrender/VtkSceneSetup.h"

namespace mfadvr {

namespace {

using Clock = std::chrono::steady_clock;

// The CPU mappers' image-space settings, which share names but no base class: one ray per pixel
// in every frame (no interactive coarsening), so that frames are comparable with ours.
template <class Mapper>
void castEveryPixel(Mapper* m, vtkDataObject* data) {
  m->SetInputDataObject(data);
  m->AutoAdjustSampleDistancesOff();
  m->SetImageSampleDistance(1.0f);
  m->SetMinimumImageSampleDistance(1.0f);
  m->SetMaximumImageSampleDistance(1.0f);
}

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Collects the error messages VTK objects report (instead of printing them), so that a failed
// render becomes an mfadvr::Error.
class ErrorCollector : public vtkCommand {
 public:
  static ErrorCollector* New() { return new ErrorCollector; }
  void Execute(vtkObject*, unsigned long, void* callData) override {
    if (messages.empty() && callData) messages = static_cast<const char*>(callData);
  }
  std::string messages;
};

// The renderers of finished pipelines, kept (without their props) for the life of the process.
// With Debian's VTK 9.1, a vtkRenderer allocated at the address of a destroyed one sometimes
// renders with the aspect ratio of a square viewport: the CPU mappers' images come out
// stretched sideways (seen in the silhouette tests, 1 run in 3). Keeping the old renderer
// alive prevents the address reuse; an empty renderer costs about a kilobyte.
void retireRenderer(vtkSmartPointer<vtkRenderer> renderer) {
  static auto* retired = new std::vector<vtkSmartPointer<vtkRenderer>>;  // never destroyed
  retired->push_back(std::move(renderer));
}

}  // namespace

double medianSeconds(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct VtkBaselineRenderer::Impl {
  VtkMethod method;
  vtkSmartPointer<vtkDataSet> data;
  vtkSmartPointer<vtkAbstractVolumeMapper> mapper;
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkVolume> volume;
  vtkSmartPointer<vtkRenderer> renderer = vtkSmartPointer<vtkRenderer>::New();
  vtkNew<vtkRenderWindow> window;
  vtkNew<ErrorCollector> errors;
  std::int64_t cells = 0;
  bool tetrahedralized = false;
  double preparationSeconds = 0.0;
};

namespace {

// The blend mode, clipping planes and cropping box of `settings` on the mapper. VTK 9.1's
// fixed-point ray caster has composite, MIP and MinIP (its "additive" composites with
// uncorrected opacities: not an additive blend), clipping planes and cropping; its tetrahedral
// mappers have none of them.
void applyBlendAndClipping(VtkMethod method, const RenderSettings& settings,
                           vtkAbstractVolumeMapper* mapper) {
  const std::string name = vtkMethodName(method);
  const bool fixedPoint = method == VtkMethod::FixedPoint;
  // VTK's mappers scale the gradient their own way: the same function would not be the same
  // classification, so the comparison is refused rather than made unfair.
  if (settings.classifiesCurvature())
    throw Error(name +
                ": VTK's mappers have no curvature transfer functions or contours; render them "
                "with our methods (mfa, or a grid filter for comparison)");
  if (settings.classifiesGradients())
    throw Error(name +
                ": gradient opacity and 2-D transfer functions are not compared with "
                "VTK's mappers (they scale |grad f| their own way); render them with our methods");
  if (settings.blend != BlendMode::Composite &&
      !(fixedPoint &&
        (settings.blend == BlendMode::Maximum || settings.blend == BlendMode::Minimum)))
    throw Error(name + " has no " + blendModeName(settings.blend) + " blend" +
                (fixedPoint ? " (VTK 9.1's fixed-point ray caster blends composite, max and min)"
                            : " (it blends composite only)"));
  if (!fixedPoint && (!settings.clipPlanes.empty() || settings.crop))
    throw Error(name + " takes no clipping planes or cropping box; vtk-fixedpoint does");
  if (!fixedPoint) return;
  auto* m = vtkVolumeMapper::SafeDownCast(mapper);
  if (settings.blend == BlendMode::Maximum) m->SetBlendModeToMaximumIntensity();
  if (settings.blend == BlendMode::Minimum) m->SetBlendModeToMinimumIntensity();
  for (const ClipPlane& c : settings.clipPlanes) {
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(c.point.data());
    plane->SetNormal(c.normal.data());
    m->AddClippingPlane(plane);
  }
  if (settings.crop) {
    const DomainBox& b = *settings.crop;
    m->CroppingOn();
    m->SetCroppingRegionPlanes(b.min[0], b.max[0], b.min[1], b.max[1], b.min[2], b.max[2]);
    m->SetCroppingRegionFlagsToSubVolume();
  }
}

}  // namespace

VtkBaselineRenderer::VtkBaselineRenderer(VtkMethod method, const VtkBaselineInput& input,
                                         const RenderSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.method = method;
  const std::string name = vtkMethodName(method);
  settings.validate();
  if (!input.grid && !input.mesh) throw Error(name + ": no grid or mesh to render");

  const auto prepareStart = Clock::now();
  if (method == VtkMethod::FixedPoint) {
    if (!input.grid) {
      const ScatteredData& m = *input.mesh;
      throw Error(name + " (" + vtkMapperClassName(method) + ") renders regular grids; " +
                  m.source + " is a " + (m.kind.empty() ? "mesh" : m.kind) +
                  ": use vtk-bunyk, vtk-zsweep or vtk-pt for meshes");
    }
    auto image = makeImageData(*input.grid);
    d.cells = image->GetNumberOfCells();
    d.data = image;
  } else if (input.mesh) {
    auto mesh = makeTetrahedralMesh(*input.mesh);
    d.cells = mesh->GetNumberOfCells();
    d.data = mesh;
  } else {
    auto mesh = tetrahedralize(makeImageData(*input.grid));
    d.cells = mesh->GetNumberOfCells();
    d.data = mesh;
    d.tetrahedralized = true;
  }
  d.preparationSeconds = secondsSince(prepareStart);

  switch (method) {
    case VtkMethod::FixedPoint: {
      vtkNew<vtkFixedPointVolumeRayCastMapper> m;
      castEveryPixel(m.Get(), d.data);
      m->LockSampleDistanceToInputSpacingOff();
      m->SetSampleDistance(static_cast<float>(settings.sampleDistance));
      m->SetInteractiveSampleDistance(static_cast<float>(settings.sampleDistance));
      if (settings.threads > 0) m->SetNumberOfThreads(settings.threads);
      d.mapper = m;
      break;
    }
    case VtkMethod::Bunyk: {
      vtkNew<vtkUnstructuredGridVolumeRayCastMapper> m;
      castEveryPixel(m.Get(), d.data);
      if (settings.threads > 0) m->SetNumberOfThreads(settings.threads);
      d.mapper = m;
      break;
    }
    case VtkMethod::ZSweep: {
      vtkNew<vtkUnstructuredGridVolumeZSweepMapper> m;
      castEveryPixel(m.Get(), d.data);
      d.mapper = m;
      break;
    }
    case VtkMethod::ProjectedTetrahedra: {
      // The object factory gives vtkOpenGLProjectedTetrahedraMapper.
      vtkSmartPointer<vtkProjectedTetrahedraMapper> m =
          vtkSmartPointer<vtkProjectedTetrahedraMapper>::New();
      if (!m) throw Error(name + ": VTK has no OpenGL projected tetrahedra mapper");
      m->SetInputData(d.data);
      d.mapper = m;
      break;
    }
  }
  d.mapper->AddObserver(vtkCommand::ErrorEvent, d.errors);
  applyBlendAndClipping(method, settings, d.mapper);

  // The tetrahedral renderers read the TF's opacity as attenuation; give them the coefficient of
  // the optical model every other renderer here uses (VtkSceneSetup.h).
  applyTransferFunction(settings, d.property,
                        method == VtkMethod::FixedPoint ? VtkOpacityReading::PerUnitDistance
                                                        : VtkOpacityReading::Attenuation);
  d.volume->SetMapper(d.mapper);
  d.volume->SetProperty(d.property);
  d.renderer->AddVolume(d.volume);
  applyBackground(settings.background, d.renderer);
  applyLighting(settings.lighting, d.renderer);
  applyCamera(settings.camera, d.renderer);

  requireRenderDisplay();  // before the window touches X, which aborts without a display
  d.window->SetOffScreenRendering(1);
  d.window->SetMultiSamples(0);
  d.window->SetSize(settings.width, settings.height);
  d.window->AddRenderer(d.renderer);
  // Open the window and its OpenGL context now, with nothing to draw, so that the first timed
  // frame measures the mapper (its tables, gradients, cell structures) and not the window.
  d.volume->VisibilityOff();
  {
    const LeakCheckPause pause;  // Mesa keeps process-lifetime allocations from here on
    d.window->Render();
    d.window->WaitForCompletion();
  }
  d.volume->VisibilityOn();
  // An OpenGL context without what projected tetrahedra need makes the mapper report an error
  // on the first frame, which renderFrame turns into an mfadvr::Error.
}

VtkBaselineRenderer::~VtkBaselineRenderer() {
  const LeakCheckPause pause;  // closing the window and its context
  Impl& d = *impl_;
  d.window->RemoveRenderer(d.renderer);
  d.renderer->RemoveAllViewProps();
  retireRenderer(d.renderer);
  impl_.reset();  // the window closes here, inside the pause
}

VtkMethod VtkBaselineRenderer::method() const {
  return impl_->method;
}

void VtkBaselineRenderer::setShade(bool shade) {
  impl_->property->SetShade(shade ? 1 : 0);
}

double VtkBaselineRenderer::renderFrame() {
  Impl& d = *impl_;
  d.renderer->GetActiveCamera()->Modified();
  d.renderer->ResetCameraClippingRange();
  d.errors->messages.clear();
  const LeakCheckPause pause;
  const auto start = Clock::now();
  d.window->Render();
  d.window->WaitForCompletion();  // the frame is drawn, not just queued
  const double seconds = secondsSince(start);
  if (!d.errors->messages.empty())
    throw Error(vtkMethodName(d.method) + ": VTK failed to render: " + d.errors->messages);
  return seconds;
}

VtkFrameTimes VtkBaselineRenderer::renderFrames(int frames) {
  if (frames < 1) throw Error("frames must be at least 1, got " + std::to_string(frames));
  VtkFrameTimes t;
  for (int i = 0; i < frames; ++i) t.seconds.push_back(renderFrame());
  t.firstSeconds = t.seconds.front();
  t.medianSeconds =
      frames == 1 ? t.firstSeconds
                  : medianSeconds(std::vector<double>(t.seconds.begin() + 1, t.seconds.end()));
  return t;
}

Image8 VtkBaselineRenderer::readBack() {
  return readWindowRgb(impl_->window);
}

std::int64_t VtkBaselineRenderer::pointCount() const {
  return impl_->data->GetNumberOfPoints();
}

std::int64_t VtkBaselineRenderer::cellCount() const {
  return impl_->cells;
}

bool VtkBaselineRenderer::tetrahedralized() const {
  return impl_->tetrahedralized;
}

double VtkBaselineRenderer::preparationSeconds() const {
  return impl_->preparationSeconds;
}

}  // namespace mfadvr
