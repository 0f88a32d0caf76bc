#include "vtkMFAVolumeRepresentation.h"

#include "vtkMFAVolumeMapper.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkMFAVolumeRepresentation);

vtkMFAVolumeRepresentation::vtkMFAVolumeRepresentation() {
  // The superclass does everything else: caching the input, bounds for ordered compositing,
  // the property (colour, opacity, shading) and the scalar array selection.
  this->VolumeMapper = vtkSmartPointer<vtkMFAVolumeMapper>::New();
}

vtkMFAVolumeRepresentation::~vtkMFAVolumeRepresentation() = default;

void vtkMFAVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
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
