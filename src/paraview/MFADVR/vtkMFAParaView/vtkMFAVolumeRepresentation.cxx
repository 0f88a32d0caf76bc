#include "vtkMFAVolumeRepresentation.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMFAVolumeMapper.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOutlineSource.h"
#include "vtkPVLODVolume.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

vtkStandardNewMacro(vtkMFAVolumeRepresentation);

vtkMFAVolumeRepresentation::vtkMFAVolumeRepresentation() {
  // The superclass does everything else: caching the input, bounds for ordered compositing,
  // the property (colour, opacity, shading) and the scalar array selection.
  this->VolumeMapper = vtkSmartPointer<vtkMFAVolumeMapper>::New();
}

vtkMFAVolumeRepresentation::~vtkMFAVolumeRepresentation() = default;

void vtkMFAVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ParaViewBlendMode: " << this->ParaViewBlendMode << "\n";
  os << indent << "MFABlendMode: " << this->MFABlendMode << "\n";
}

vtkMFAVolumeMapper* vtkMFAVolumeRepresentation::GetMFAMapper() {
  return vtkMFAVolumeMapper::SafeDownCast(this->VolumeMapper);
}

void vtkMFAVolumeRepresentation::SetSampleDistance(double distance) {
  this->GetMFAMapper()->SetSampleDistance(distance);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetEarlyRayTerminationOpacity(double opacity) {
  this->GetMFAMapper()->SetEarlyRayTerminationOpacity(opacity);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetImageSampleDistance(double distance) {
  this->GetMFAMapper()->SetImageSampleDistance(distance);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetMaximumImageSampleDistance(double distance) {
  this->GetMFAMapper()->SetMaximumImageSampleDistance(distance);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetCurvatureTransferFunction(const char* spec) {
  this->GetMFAMapper()->SetCurvatureTransferFunction(spec && *spec ? spec : nullptr);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetContourWidth(double pixels) {
  this->GetMFAMapper()->SetContourWidth(pixels);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetContourColor(double r, double g, double b) {
  this->GetMFAMapper()->SetContourColor(r, g, b);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetDevice(int device) {
  if (this->GetMFAMapper()->GetDevice() != device) {
    this->GetMFAMapper()->SetDevice(device);
    this->Modified();
  }
}

const char* vtkMFAVolumeRepresentation::GetLastDeviceDescription() {
  return this->GetMFAMapper()->GetLastDeviceDescription();
}

void vtkMFAVolumeRepresentation::SetBlendMode(int mode) {
  this->ParaViewBlendMode = mode;
  this->ApplyBlendMode();
}

void vtkMFAVolumeRepresentation::SetMFABlendMode(int mode) {
  this->MFABlendMode = mode;
  this->ApplyBlendMode();
}

void vtkMFAVolumeRepresentation::ApplyBlendMode() {
  const int mode = this->MFABlendMode >= 0 ? this->MFABlendMode : this->ParaViewBlendMode;
  if (this->VolumeMapper->GetBlendMode() != mode) {
    this->VolumeMapper->SetBlendMode(mode);
    this->Modified();
  }
}

void vtkMFAVolumeRepresentation::UpdateMapperParameters() {
  this->Superclass::UpdateMapperParameters();
  this->ApplyBlendMode();
}

int vtkMFAVolumeRepresentation::RequestData(vtkInformation* request,
                                            vtkInformationVector** inputVector,
                                            vtkInformationVector* outputVector) {
  vtkImageData* input = inputVector[0]->GetNumberOfInformationObjects() == 1
                            ? vtkImageData::GetData(inputVector[0], 0)
                            : nullptr;
  if (!input || this->UseSeparateOpacityArray || !input->HasAnyGhostCells() ||
      !vtkMFAVolumeMapper::CarriesModels(input)) {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  auto cache = vtkSmartPointer<vtkImageData>::New();
  cache->ShallowCopy(input);
  this->Actor->SetEnableLOD(0);
  this->VolumeMapper->SetInputData(cache);
  double bounds[6];
  this->GetMFAMapper()->GetBounds(bounds);
  if (!vtkMath::AreBoundsInitialized(bounds)) {
    cache->GetBounds(bounds);  // a damaged carrier: the mapper reports it and renders nothing
  }
  this->OutlineSource->SetBounds(bounds);
  this->OutlineSource->GetBounds(this->DataBounds);
  this->OutlineSource->Update();
  this->DataSize = cache->GetActualMemorySize();
  vtkStreamingDemandDrivenPipeline::GetWholeExtent(inputVector[0]->GetInformationObject(0),
                                                   this->WholeExtent);
  this->Cache = cache;
  // The superclass's own work is done above; its superclass's (the property, the time) remains.
  return this->vtkVolumeRepresentation::RequestData(request, inputVector, outputVector);
}
