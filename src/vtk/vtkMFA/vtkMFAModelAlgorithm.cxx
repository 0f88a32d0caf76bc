#include "vtkMFAModelAlgorithm.h"

#include "vtkDataObject.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMFAModelData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "VtkModelImage.h"
#include "core/model/Model.h"

vtkMFAModelAlgorithm::vtkMFAModelAlgorithm() {
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(1);
}

vtkMFAModelAlgorithm::~vtkMFAModelAlgorithm() = default;

void vtkMFAModelAlgorithm::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutputImageData: " << this->OutputImageData << "\n";
}

vtkMFAModelData* vtkMFAModelAlgorithm::GetOutput() {
  return vtkMFAModelData::SafeDownCast(this->GetOutputDataObject(0));
}

int vtkMFAModelAlgorithm::FillOutputPortInformation(int, vtkInformation* info) {
  // A model or an image carrying one, decided at REQUEST_DATA_OBJECT.
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkDataObject");
  return 1;
}

vtkTypeBool vtkMFAModelAlgorithm::ProcessRequest(vtkInformation* request,
                                                 vtkInformationVector** inInfo,
                                                 vtkInformationVector* outInfo) {
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_OBJECT())) {
    for (int i = 0; i < this->GetNumberOfOutputPorts(); ++i) {
      vtkInformation* info = outInfo->GetInformationObject(i);
      vtkDataObject* current = info->Get(vtkDataObject::DATA_OBJECT());
      const bool fits = this->OutputImageData ? vtkImageData::SafeDownCast(current) != nullptr
                                              : vtkMFAModelData::SafeDownCast(current) != nullptr;
      if (!fits) {
        vtkDataObject* output = this->OutputImageData
                                    ? static_cast<vtkDataObject*>(vtkImageData::New())
                                    : static_cast<vtkDataObject*>(vtkMFAModelData::New());
        info->Set(vtkDataObject::DATA_OBJECT(), output);
        output->FastDelete();
      }
    }
    return 1;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION())) {
    // Each piece of a partitioned pipeline makes its own model: piece requests come through
    // as pieces, never as extents of a whole image.
    for (int i = 0; i < this->GetNumberOfOutputPorts(); ++i) {
      outInfo->GetInformationObject(i)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
    }
    return this->RequestInformation(request, inInfo, outInfo);
  }
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT())) {
    return this->RequestUpdateExtent(request, inInfo, outInfo);
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

int vtkMFAModelAlgorithm::RequestUpdateExtent(vtkInformation*, vtkInformationVector**,
                                              vtkInformationVector*) {
  return 1;
}

void vtkMFAModelAlgorithm::SetOutputModel(vtkInformationVector* outInfo,
                                          std::shared_ptr<const mfadvr::Model> model,
                                          const double* renderBounds, const int* firstIndex,
                                          const mfadvr::vtkglue::CarrierValues& values,
                                          const int* reach) {
  vtkDataObject* output = outInfo->GetInformationObject(0)->Get(vtkDataObject::DATA_OBJECT());
  if (auto* image = vtkImageData::SafeDownCast(output)) {
    mfadvr::vtkglue::CarriedModel carried{nullptr, model->domain()};
    if (renderBounds) {
      carried.region.min = mfadvr::Vec3d(renderBounds[0], renderBounds[2], renderBounds[4]);
      carried.region.max = mfadvr::Vec3d(renderBounds[1], renderBounds[3], renderBounds[5]);
    }
    // Moved on, so that the carrier can free this copy once it holds the model's bytes.
    carried.model = std::move(model);
    std::vector<mfadvr::vtkglue::CarriedModel> models;
    models.push_back(std::move(carried));
    image->ShallowCopy(
        mfadvr::vtkglue::imageOfModels(std::move(models), firstIndex, values, reach));
  } else if (auto* data = vtkMFAModelData::SafeDownCast(output)) {
    data->SetModel(std::move(model));
  }
}
