#include "vtkMFAVolumeMapper.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCamera.h"
#include "vtkContourValues.h"
#include "vtkDataSet.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMFAEncoder.h"
#include "vtkMFAModelData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <exception>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "VtkModelImage.h"
#include "VtkSceneConversion.h"
#include "core/field/ModelField.h"
#include "core/image/ImageResize.h"
#include "core/model/Model.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/PieceCompositor.h"
#include "core/render/RayCaster.h"
#include "device/RenderDevice.h"

vtkStandardNewMacro(vtkMFAVolumeMapper);

struct vtkMFAVolumeMapper::Internals {
  vtkNew<vtkMFAEncoder> Encoder;
  vtkSmartPointer<vtkMFAModelData> Model;
  // An image carrying models (ParaView's form, VtkModelImage.h): the models and their regions,
  // parsed once per carrier, each rendered in its region and composited in visibility order.
  std::vector<mfadvr::vtkglue::CarriedModel> Carried;
  vtkImageData* CarrierImage = nullptr;  // identity only, never dereferenced
  vtkMTimeType CarrierTime = 0;
  std::deque<mfadvr::EmptySpaceCache> CarriedEmptySpace;
  // The first carried model, standing for them all where one model is asked for.
  vtkSmartPointer<vtkMFAModelData> CarrierModel;

  void ForgetCarrier() {
    this->Carried.clear();
    this->CarriedEmptySpace.clear();
    this->CarrierImage = nullptr;
    this->CarrierModel = nullptr;
  }
  std::set<std::string> Warned;
  // The curvature transfer function, read once per specification and scale.
  std::string CurvatureSpec;
  double CurvatureDefault = 0.0, CurvatureScale = 0.0;
  std::optional<mfadvr::CurvatureTransferFunction> Curvature;
  std::vector<float> Depth;
  std::vector<float> VolumeDepth;  // the depth buffer with the volume's depth written in
  std::vector<unsigned char> Pixels;
  std::function<mfadvr::Image(const mfadvr::RenderSettings&)> FieldRenderer;
  double LastSeconds = 0.0;
  // Empty-space flags of the current model and transfer function, kept between frames.
  mfadvr::EmptySpaceCache EmptySpace;
  // GPU renderers, one per model rendered (the single model, or each carried one), so that each
  // keeps its model in GPU memory; made for the Device in GpuFor. With DeviceAuto and no usable
  // GPU the answer is remembered until the Device changes.
  std::vector<std::unique_ptr<mfadvr::DeviceRenderer>> Gpu;
  int GpuFor = -1;
  bool NoGpu = false;
  std::string DeviceDescription;

  // Renders model `i` (0 for a single model) on `device`; `used` receives DeviceCPU or
  // DeviceCUDA. Throws for DeviceCUDA without a usable GPU.
  mfadvr::Image RenderModel(int device, size_t i, const mfadvr::ModelField& field,
                            const mfadvr::RenderSettings& settings, int& used) {
    if (device != this->GpuFor) {
      this->Gpu.clear();
      this->GpuFor = device;
      this->NoGpu = device == vtkMFAVolumeMapper::DeviceCPU;
      this->DeviceDescription = this->NoGpu ? "CPU" : "";
    }
    if (!this->NoGpu && (i >= this->Gpu.size() || !this->Gpu[i])) {
      mfadvr::MethodSpec spec;  // the model, analytic gradients
      mfadvr::RenderDevice opened = mfadvr::openRenderDevice(
          device == vtkMFAVolumeMapper::DeviceCUDA ? "cuda" : "auto", spec);
      this->DeviceDescription = opened.description;
      this->NoGpu = !opened.renderer;
      if (opened.renderer) {
        this->Gpu.resize(std::max(this->Gpu.size(), i + 1));
        this->Gpu[i] = std::move(opened.renderer);
      }
    }
    if (this->NoGpu) {
      used = vtkMFAVolumeMapper::DeviceCPU;
      return mfadvr::renderVolume(field, settings);
    }
    used = vtkMFAVolumeMapper::DeviceCUDA;
    return this->Gpu[i]->renderModel(field, settings, nullptr);
  }
};

vtkMFAVolumeMapper::vtkMFAVolumeMapper() : Internal(new Internals) {}

vtkMFAVolumeMapper::~vtkMFAVolumeMapper() {
  this->SetCurvatureTransferFunction(nullptr);
}

void vtkMFAVolumeMapper::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "MinimumImageSampleDistance: " << this->MinimumImageSampleDistance << "\n";
  os << indent << "MaximumImageSampleDistance: " << this->MaximumImageSampleDistance << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "EarlyRayTerminationOpacity: " << this->EarlyRayTerminationOpacity << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "CurvatureTransferFunction: "
     << (this->CurvatureTransferFunction ? this->CurvatureTransferFunction : "(none)") << "\n";
  os << indent << "ContourWidth: " << this->ContourWidth << "\n";
  os << indent << "WriteDepth: " << this->WriteDepth << "\n";
  os << indent << "ContourColor: " << this->ContourColor[0] << " " << this->ContourColor[1] << " "
     << this->ContourColor[2] << "\n";
  os << indent << "Device: " << this->Device << "\n";
  os << indent << "LastDevice: " << this->LastDevice << " (" << this->Internal->DeviceDescription
     << ")\n";
}

const char* vtkMFAVolumeMapper::GetLastDeviceDescription() {
  return this->Internal->DeviceDescription.c_str();
}

int vtkMFAVolumeMapper::FillInputPortInformation(int, vtkInformation* info) {
  // Either type passes the executive's check; UpdateModel tells them apart.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkMFAModelData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

void vtkMFAVolumeMapper::SetInputData(vtkMFAModelData* model) {
  this->SetInputDataInternal(0, model);
}

void vtkMFAVolumeMapper::SetMFAInputConnection(vtkAlgorithmOutput* output) {
  this->SetInputConnection(0, output);
}

void vtkMFAVolumeMapper::SetMFAInputData(vtkMFAModelData* model) {
  this->SetInputData(model);
}

vtkMFAEncoder* vtkMFAVolumeMapper::GetEncoder() {
  return this->Internal->Encoder;
}

void vtkMFAVolumeMapper::SetFieldRenderer(
    std::function<mfadvr::Image(const mfadvr::RenderSettings&)> render) {
  this->Internal->FieldRenderer = std::move(render);
  this->Modified();
}

vtkDataObject* vtkMFAVolumeMapper::GetDataObjectInput() {
  return this->GetNumberOfInputConnections(0) > 0 ? this->GetInputDataObject(0, 0) : nullptr;
}

vtkMFAModelData* vtkMFAVolumeMapper::GetMFAInput() {
  return this->Internal->Model;
}

bool vtkMFAVolumeMapper::CarriesModels(vtkDataObject* data) {
  return mfadvr::vtkglue::carriesModels(data);
}

vtkMFAModelData* vtkMFAVolumeMapper::UpdateModel() {
  vtkSmartPointer<vtkMFAModelData> model;
  bool carrier = false;
  if (this->GetNumberOfInputConnections(0) > 0) {
    vtkAlgorithmOutput* connection = this->GetInputConnection(0, 0);
    connection->GetProducer()->Update(connection->GetIndex());
    vtkDataObject* input = this->GetInputDataObject(0, 0);
    model = vtkMFAModelData::SafeDownCast(input);
    auto* image = vtkImageData::SafeDownCast(input);
    carrier = image && mfadvr::vtkglue::carriesModels(image);
    auto& in = *this->Internal;
    if (carrier) {
      if (in.CarrierImage != image || in.CarrierTime != image->GetMTime()) {
        in.ForgetCarrier();
        in.CarrierImage = image;
        in.CarrierTime = image->GetMTime();
        try {
          in.Carried = mfadvr::vtkglue::modelsOfImage(image);
          in.CarriedEmptySpace.resize(in.Carried.size());
          in.CarrierModel = vtkSmartPointer<vtkMFAModelData>::New();
          in.CarrierModel->SetModel(in.Carried.front().model);
        } catch (const std::exception& e) {
          vtkErrorMacro(<< "cannot render the carried models: " << e.what());
        }
      }
      model = in.CarrierModel;
    } else if (auto* dataSet = vtkDataSet::SafeDownCast(input)) {
      // The encoder's pipeline re-fits only when the data set or the options change.
      in.Encoder->SetInputData(dataSet);
      in.Encoder->Update();
      model = in.Encoder->GetOutput();
    }
  }
  if (!carrier) {
    this->Internal->ForgetCarrier();
  }
  this->Internal->Model = (model && model->HasModel()) ? model : nullptr;
  return this->Internal->Model;
}

double* vtkMFAVolumeMapper::GetBounds() {
  vtkMFAModelData* model = this->UpdateModel();
  if (model && !this->Internal->Carried.empty()) {
    // The union of the regions the carried models render.
    mfadvr::DomainBox all = this->Internal->Carried.front().region;
    for (const auto& c : this->Internal->Carried) {
      all.min = all.min.cwiseMin(c.region.min);
      all.max = all.max.cwiseMax(c.region.max);
    }
    for (int a = 0; a < 3; ++a) {
      this->Bounds[2 * a] = all.min[a];
      this->Bounds[2 * a + 1] = all.max[a];
    }
  } else if (model) {
    model->GetBounds(this->Bounds);
  } else {
    vtkMath::UninitializeBounds(this->Bounds);
  }
  return this->Bounds;
}

void vtkMFAVolumeMapper::GetBounds(double bounds[6]) {
  const double* b = this->GetBounds();
  std::copy(b, b + 6, bounds);
}

void vtkMFAVolumeMapper::WarnOnce(const std::string& note) {
  if (this->Internal->Warned.insert(note).second) {
    vtkWarningMacro(<< note);
  }
}

double vtkMFAVolumeMapper::ChooseImageSampleDistance(vtkVolume* vol) {
  const double lo = std::min(this->MinimumImageSampleDistance, this->MaximumImageSampleDistance);
  const double hi = std::max(this->MinimumImageSampleDistance, this->MaximumImageSampleDistance);
  const double allocated = vol->GetAllocatedRenderTime();
  // Still frames get allocated very long times (1 / the still update rate).
  if (!this->AutoAdjustSampleDistances || !(allocated > 0.0) || allocated >= 1.0 ||
      this->Internal->LastSeconds <= 0.0) {
    return this->ImageSampleDistance;
  }
  // Frame time scales with the number of rays, i.e. with 1 / distance^2.
  const double wanted =
      this->LastImageSampleDistance * std::sqrt(this->Internal->LastSeconds / allocated);
  return std::clamp(wanted, lo, hi);
}

namespace {

// The mapper's blend mode, clipping planes and cropping box in `s`, in model coordinates.
void applyBlendAndClipping(vtkVolumeMapper* m, vtkVolumeProperty* property,
                           mfadvr::RenderSettings& s,
                           const mfadvr::vtkglue::WorldToModel& toModel) {
  switch (m->GetBlendMode()) {
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      s.blend = mfadvr::BlendMode::Maximum;
      break;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      s.blend = mfadvr::BlendMode::Minimum;
      break;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND: {
      s.blend = mfadvr::BlendMode::Average;
      const double* r = m->GetAverageIPScalarRange();
      // VTK's default range is the whole of double's: all values count.
      if (std::isfinite(r[0]) && std::isfinite(r[1]) && r[0] <= r[1] &&
          (r[0] > -1e300 || r[1] < 1e300)) {
        s.averageRange = std::pair(r[0], r[1]);
      }
      break;
    }
    case vtkVolumeMapper::ADDITIVE_BLEND:
      s.blend = mfadvr::BlendMode::Additive;
      break;
    case vtkVolumeMapper::ISOSURFACE_BLEND: {
      // The property's isosurface values (ParaView's IsosurfaceValues), coloured and made
      // opaque as the transfer function says at each value, as VTK's GPU mapper does.
      vtkContourValues* values = property->GetIsoSurfaceValues();
      const int n = std::min(values ? values->GetNumberOfContours() : 0, mfadvr::kMaxIsoValues);
      for (int i = 0; i < n; ++i) {
        s.isoSurfaces.push_back({values->GetValue(i), {}, {}});
      }
      s.blend = n > 0 ? mfadvr::BlendMode::Iso : mfadvr::BlendMode::Composite;
      break;
    }
    default:
      s.blend = mfadvr::BlendMode::Composite;
  }
  // Clipping planes are in world coordinates; the normals turn with the volume's matrix (the
  // inverse transpose of a similarity is the matrix up to scale).
  if (m->GetClippingPlanes()) {
    const int n = std::min(m->GetClippingPlanes()->GetNumberOfItems(), mfadvr::kMaxClipPlanes);
    for (int i = 0; i < n; ++i) {
      vtkPlane* plane = m->GetClippingPlanes()->GetItem(i);
      const mfadvr::Vec3d origin(plane->GetOrigin()), normal(plane->GetNormal());
      if (!(normal.norm() > 0.0)) {
        continue;
      }
      s.clipPlanes.push_back({toModel.point(origin), toModel.vector(normal)});
    }
  }
  // Cropping planes are in the data's coordinates: the model's.
  if (m->GetCropping()) {
    const double* c = m->GetCroppingRegionPlanes();
    mfadvr::DomainBox box;
    for (int a = 0; a < 3; ++a) {
      box.min[a] = std::min(c[2 * a], c[2 * a + 1]);
      box.max[a] = std::max(c[2 * a], c[2 * a + 1]);
    }
    s.crop = box;
  }
}

}  // namespace

void vtkMFAVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol) {
  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  vtkMFAModelData* data = this->UpdateModel();
  if (!data) {
    return;
  }
  const std::shared_ptr<const mfadvr::Model> model = data->GetModel();

  // ParaView (and SelectScalarArray) name the array the maps belong to; the volume is always
  // drawn from the model's values, so say so when the name is another field's.
  if (this->ArrayAccessMode == VTK_GET_ARRAY_BY_NAME && this->ArrayName && *this->ArrayName) {
    const std::string field = mfadvr::vtkglue::carrierArrayName(*model);
    if (field != this->ArrayName) {
      this->WarnOnce(std::string("the volume is coloured by '") + this->ArrayName +
                     "', but the model's field is '" + field + "': the model's values are " +
                     "mapped through the colour and opacity maps of '" + this->ArrayName +
                     "'; colour by '" + field + "' to use its maps");
    }
  }
  if (this->BlendMode == vtkVolumeMapper::SLICE_BLEND) {
    this->WarnOnce("the slice blend mode is not supported yet; rendering with composite blending");
  }
  if (this->BlendMode == vtkVolumeMapper::ISOSURFACE_BLEND) {
    vtkContourValues* values = vol->GetProperty()->GetIsoSurfaceValues();
    const int n = values ? values->GetNumberOfContours() : 0;
    if (n == 0) {
      this->WarnOnce(
          "the isosurface blend mode needs isosurface values (vtkVolumeProperty::"
          "GetIsoSurfaceValues()->SetValue); rendering with composite blending");
    } else if (n > mfadvr::kMaxIsoValues) {
      this->WarnOnce("at most " + std::to_string(mfadvr::kMaxIsoValues) +
                     " isosurface values are rendered; the others are ignored");
    }
  }
  if (this->Cropping && this->CroppingRegionFlags != VTK_CROP_SUBVOLUME) {
    this->WarnOnce(
        "only sub-volume cropping (SetCroppingRegionFlagsToSubVolume) is supported; "
        "the central region of the cropping planes is rendered");
  }
  if (this->ClippingPlanes && this->ClippingPlanes->GetNumberOfItems() > mfadvr::kMaxClipPlanes) {
    this->WarnOnce("at most " + std::to_string(mfadvr::kMaxClipPlanes) +
                   " clipping planes are honoured; the others are ignored");
  }

  int width = 0, height = 0, originX = 0, originY = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &originX, &originY);
  if (width <= 0 || height <= 0) {
    return;
  }
  const double isd = this->ChooseImageSampleDistance(vol);
  const int rw = std::max(1, static_cast<int>(std::lround(width / isd)));
  const int rh = std::max(1, static_cast<int>(std::lround(height / isd)));

  const mfadvr::vtkglue::WorldToModel toModel = mfadvr::vtkglue::worldToModelOf(vol->GetMatrix());
  if (!toModel.similarity) {
    this->WarnOnce(
        "the volume's matrix scales its axes unequally or shears them; the image is "
        "approximate (rotations, translations and uniform scales are exact)");
  }
  vtkVolumeProperty* property = vol->GetProperty();
  std::vector<std::string> notes;

  mfadvr::RenderSettings s;
  try {
    s.width = rw;
    s.height = rh;
    s.camera = mfadvr::vtkglue::cameraFromVtk(ren->GetActiveCamera(), toModel);
    s.rays = mfadvr::vtkglue::raysFromVtk(ren, toModel, rw, rh);
    s.transferFunction = mfadvr::vtkglue::transferFunctionFromVtk(property, notes);
    s.opacityUnitDistance = property->GetScalarOpacityUnitDistance(0) * toModel.scale;
    // Gradient opacity and 2-D transfer functions classify composite renders only, as in
    // VTK's GPU mapper.
    if (this->BlendMode == vtkVolumeMapper::COMPOSITE_BLEND) {
      s.gradientOpacity = mfadvr::vtkglue::gradientOpacityFromVtk(property, toModel);
      s.transferFunction2D = mfadvr::vtkglue::transferFunction2DFromVtk(property, toModel, notes);
    }
    s.sampleDistance = this->SampleDistance > 0.0 ? this->SampleDistance * toModel.scale
                                                  : 0.5 * model->dataSpacing().minCoeff();
    s.earlyTerminationOpacity = this->EarlyRayTerminationOpacity;
    s.shade = property->GetShade(0) != 0;
    if (s.shade) {
      s.lighting = mfadvr::vtkglue::lightingFromVtk(ren, property, toModel, notes);
    }
    s.background = mfadvr::Vec3f::Zero();  // premultiplied colour over nothing
    s.threads = this->NumberOfThreads;
    applyBlendAndClipping(this, property, s, toModel);
    if (this->BlendMode == vtkVolumeMapper::COMPOSITE_BLEND ||
        this->BlendMode == vtkVolumeMapper::ISOSURFACE_BLEND) {
      const std::string spec =
          this->CurvatureTransferFunction ? this->CurvatureTransferFunction : "";
      if (!spec.empty()) {
        // Curvatures in the model's units: world ones divided by the world-to-model scale.
        auto& in = *this->Internal;
        const double defaultK = toModel.scale / (8.0 * model->dataSpacing().minCoeff());
        if (!in.Curvature || in.CurvatureSpec != spec || in.CurvatureDefault != defaultK ||
            in.CurvatureScale != toModel.scale) {
          in.Curvature.reset();
          mfadvr::CurvatureTransferFunction tf =
              mfadvr::readCurvatureTransferFunction(spec, defaultK);
          tf.k1Lo /= toModel.scale;
          tf.k1Hi /= toModel.scale;
          tf.k2Lo /= toModel.scale;
          tf.k2Hi /= toModel.scale;
          in.Curvature = std::move(tf);
          in.CurvatureSpec = spec;
          in.CurvatureDefault = defaultK;
          in.CurvatureScale = toModel.scale;
        }
        s.curvatureTransferFunction = in.Curvature;
      }
      // The width in pixels of the image rendered (the viewport's over the sample distance).
      s.contourPixels = this->ContourWidth / isd;
      for (int a = 0; a < 3; ++a) s.contourColor[a] = static_cast<float>(this->ContourColor[a]);
    }

    s.depth = this->WriteDepth == WriteDepthAlways ||
              (this->WriteDepth == WriteDepthIsosurfaces && s.blend == mfadvr::BlendMode::Iso);

    // Ray ends from the depth buffer: the opaque geometry drawn so far.
    auto& depth = this->Internal->Depth;
    depth.resize(static_cast<size_t>(width) * height);
    ren->GetRenderWindow()->GetZbufferData(originX, originY, originX + width - 1,
                                           originY + height - 1, depth.data());
    vtkMatrix4x4* worldToClip = ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
        static_cast<double>(width) / height, -1, 1);
    vtkNew<vtkMatrix4x4> clipToWorld;
    vtkMatrix4x4::Invert(worldToClip, clipToWorld);
    const mfadvr::CameraRays rays = s.primaryRays();
    s.rayEnd.assign(static_cast<size_t>(rw) * rh, INFINITY);
    bool anyGeometry = false;
    for (int y = 0; y < rh; ++y) {
      // Our row 0 is the top; the depth buffer's is the bottom.
      const int py = std::min(height - 1, static_cast<int>((rh - 1 - y + 0.5) * height / rh));
      for (int x = 0; x < rw; ++x) {
        const int px = std::min(width - 1, static_cast<int>((x + 0.5) * width / rw));
        const float z = depth[static_cast<size_t>(py) * width + px];
        if (!(z < 1.0f)) {
          continue;
        }
        anyGeometry = true;
        const double clip[4] = {2.0 * (px + 0.5) / width - 1.0, 2.0 * (py + 0.5) / height - 1.0,
                                2.0 * z - 1.0, 1.0};
        double world[4];
        clipToWorld->MultiplyPoint(clip, world);
        const mfadvr::Vec3d p =
            toModel.point(mfadvr::Vec3d(world[0], world[1], world[2]) / world[3]);
        double o[3], d[3];
        mfadvr::primaryRay(rays, x, y, o, d);
        s.rayEnd[static_cast<size_t>(y) * rw + x] = static_cast<float>(std::max(
            0.0, (p - mfadvr::Vec3d(o[0], o[1], o[2])).dot(mfadvr::Vec3d(d[0], d[1], d[2]))));
      }
    }
    if (!anyGeometry) {
      s.rayEnd.clear();
    }

    mfadvr::Image image;
    if (this->Internal->FieldRenderer) {
      image = this->Internal->FieldRenderer(s);
    } else if (!this->Internal->Carried.empty()) {
      // Each carried model in its region (regions are in the data's coordinates, like the
      // models' boxes), sampled as the pieces on other ranks are.
      auto& in = *this->Internal;
      std::vector<mfadvr::DomainBox> regions;
      for (const auto& c : in.Carried) regions.push_back(c.region);
      if (regions.size() > 1 && s.depth) {
        s.depth = false;
        this->WarnOnce("a volume of several pieces writes no depth (WriteDepth): its pieces' "
                       "depths would need their opacities in order");
      }
      image = mfadvr::renderPieces(
          s, regions, [&](size_t i, const mfadvr::RenderSettings& piece, mfadvr::RenderStats*) {
            return in.RenderModel(
                this->Device, i, mfadvr::ModelField(*in.Carried[i].model, &in.CarriedEmptySpace[i]),
                piece, this->LastDevice);
          });
    } else {
      image = this->Internal->RenderModel(this->Device, 0,
                                          mfadvr::ModelField(*model, &this->Internal->EmptySpace),
                                          s, this->LastDevice);
    }
    if (image.width != rw || image.height != rh) {
      throw std::runtime_error("the field renderer returned an image of the wrong size");
    }
    // The rays' depths as window depths, nearest ray per viewport pixel, over the depth buffer.
    if (s.depth && image.depth.size() == static_cast<size_t>(rw) * rh) {
      vtkNew<vtkMatrix4x4> modelToClip;
      vtkMatrix4x4::Multiply4x4(worldToClip, vol->GetMatrix(), modelToClip);
      auto& out = this->Internal->VolumeDepth;
      out = depth;
      for (int py = 0; py < height; ++py) {
        const int y = std::min(rh - 1, static_cast<int>((height - 1 - py + 0.5) * rh / height));
        for (int px = 0; px < width; ++px) {
          const int x = std::min(rw - 1, static_cast<int>((px + 0.5) * rw / width));
          const float t = image.depth[static_cast<size_t>(y) * rw + x];
          if (!std::isfinite(t)) {
            continue;
          }
          double o[3], d[3];
          mfadvr::primaryRay(rays, x, y, o, d);
          const double p[4] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2], 1.0};
          double clip[4];
          modelToClip->MultiplyPoint(p, clip);
          const float z = static_cast<float>(std::clamp(0.5 * clip[2] / clip[3] + 0.5, 0.0, 1.0));
          float& here = out[static_cast<size_t>(py) * width + px];
          here = std::min(here, z);
        }
      }
    }
    // A coarse (interactive) frame is magnified smoothly to the viewport, not in blocks.
    if (rw != width || rh != height) {
      image = mfadvr::resizeBilinear(image, width, height);
    }

    // 8-bit premultiplied RGBA, row 0 at the bottom as OpenGL wants it.
    auto& pixels = this->Internal->Pixels;
    pixels.resize(static_cast<size_t>(4) * width * height);
    for (int y = 0; y < height; ++y) {
      unsigned char* row = pixels.data() + static_cast<size_t>(4) * width * (height - 1 - y);
      for (int x = 0; x < width; ++x) {
        const float* p = image.pixel(x, y);
        for (int c = 0; c < 4; ++c) {
          row[4 * x + c] =
              static_cast<unsigned char>(std::lround(std::clamp(p[c], 0.0f, 1.0f) * 255.0f));
        }
      }
    }
  } catch (const std::exception& e) {
    vtkErrorMacro(<< "cannot render the model: " << e.what());
    return;
  }
  for (const std::string& note : notes) {
    this->WarnOnce(note);
  }

  // Drawn pixel for pixel over the viewport (a coarse frame was magnified bilinearly above),
  // blended as premultiplied colour: out = image + (1 - alpha) * frame. The image already
  // accounts for the geometry in front, so the depth test is off; the GL state is restored.
  auto* glWindow = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!glWindow) {
    this->WarnOnce("the render window is not an OpenGL window; nothing is drawn");
    return;
  }
  vtkOpenGLState* state = glWindow->GetState();
  vtkOpenGLState::ScopedglBlendFuncSeparate blendFunction(state);
  vtkOpenGLState::ScopedglEnableDisable blend(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglEnableDisable scissorTest(state, GL_SCISSOR_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  state->vtkglDepthMask(GL_FALSE);
  glWindow->DrawPixels(originX, originY, originX + width - 1, originY + height - 1, 0, 0, width - 1,
                       height - 1, width, height, 4, VTK_UNSIGNED_CHAR,
                       this->Internal->Pixels.data());
  if (s.depth) {
    // Depths only: the colour buffer is left as drawn; the depth test passes every pixel.
    vtkOpenGLState::ScopedglColorMask colorMask(state);
    vtkOpenGLState::ScopedglDepthFunc depthFunction(state);
    vtkOpenGLState::ScopedglViewport viewport(state);
    vtkOpenGLState::ScopedglScissor scissor(state);
    state->vtkglDepthMask(GL_TRUE);
    glWindow->SetZbufferData(originX, originY, originX + width - 1, originY + height - 1,
                             this->Internal->VolumeDepth.data());
  }

  timer->StopTimer();
  this->TimeToDraw = timer->GetElapsedTime();
  this->Internal->LastSeconds = this->TimeToDraw;
  this->LastImageSampleDistance = isd;
}
