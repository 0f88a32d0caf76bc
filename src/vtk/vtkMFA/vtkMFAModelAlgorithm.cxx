#include "vtkMFAModelAlgorithm.h"

#include "vtkDataObject.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMFAModelData.h"

vtkMFAModelAlgorithm::vtkMFAModelAlgorithm() {
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
}

vtkMFAModelAlgorithm::~vtkMFAModelAlgorithm() = default;

void vtkMFAModelAlgorithm::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
}

vtkMFAModelData* vtkMFAModelAlgorithm::GetOutput() {
  return vtkMFAModelData::SafeDownCast(this->GetOutputDataObject(0));
}

int vtkMFAModelAlgorithm::FillOutputPortInformation(int, vtkInformation* info) {
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkMFAModelData");
  return 1;
}

vtkTypeBool vtkMFAModelAlgorithm::ProcessRequest(vtkInformation* request,
                                                 vtkInformationVector** inInfo,
                                                 vtkInformationVector* outInfo) {
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT())) {
    for (int i = 0; i < this->GetNumberOfOutputPorts(); ++i) {
      vtkInformation* info = outInfo->GetInformationObject(i);
      if (!vtkMFAModelData::SafeDownCast(info->Get(vtkDataObject::DATA_OBJECT()))) {
        vtkMFAModelData* output = vtkMFAModelData::New();
        info->Set(vtkDataObject::DATA_OBJECT(), output);
        output->FastDelete();
      }
    }
    return 1;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION())) {
    return this->RequestInformation(request, inInfo, outInfo);
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA())) {
    return this->RequestData(request, inInfo, outInfo);
  }
  return this->Superclass::ProcessRequest(request, inInfo, outInfo);
}

int vtkMFAModelAlgorithm::RequestInformation(vtkInformation*, vtkInformationVector**,
                                             vtkInformationVector*) {
  return 1;
}
