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

void vtkMFAVolumeRepresentation::SetSampleDistance(double distance) {
  vtkMFAVolumeMapper::SafeDownCast(this->VolumeMapper)->SetSampleDistance(distance);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetEarlyRayTerminationOpacity(double opacity) {
  vtkMFAVolumeMapper::SafeDownCast(this->VolumeMapper)->SetEarlyRayTerminationOpacity(opacity);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetImageSampleDistance(double distance) {
  vtkMFAVolumeMapper::SafeDownCast(this->VolumeMapper)->SetImageSampleDistance(distance);
  this->Modified();
}

void vtkMFAVolumeRepresentation::SetMaximumImageSampleDistance(double distance) {
  vtkMFAVolumeMapper::SafeDownCast(this->VolumeMapper)->SetMaximumImageSampleDistance(distance);
  this->Modified();
}
