#include "vtkMFAEncoder.h"

#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMFAModelData.h"
#include "vtkObjectFactory.h"

#include <exception>
#include <memory>
#include <string>

#include "core/encode/Encoder.h"
#include "core/encode/FitReport.h"
#include "core/model/Model.h"
#include "io/VtkDataConversion.h"

vtkStandardNewMacro(vtkMFAEncoder);

vtkMFAEncoder::vtkMFAEncoder() {
  this->SetNumberOfInputPorts(1);
  // Active point scalars unless the caller picks an array.
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
                               vtkDataSetAttributes::SCALARS);
}

vtkMFAEncoder::~vtkMFAEncoder() = default;

void vtkMFAEncoder::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Degree: " << this->Degree << "\n";
  os << indent << "NumberOfControlPoints: " << this->NumberOfControlPoints[0] << " "
     << this->NumberOfControlPoints[1] << " " << this->NumberOfControlPoints[2] << "\n";
  os << indent << "MaxError: " << this->MaxError << "\n";
  os << indent << "MaxNumberOfControlPoints: " << this->MaxNumberOfControlPoints[0] << " "
     << this->MaxNumberOfControlPoints[1] << " " << this->MaxNumberOfControlPoints[2] << "\n";
  os << indent << "MaxRounds: " << this->MaxRounds << "\n";
  os << indent << "Smoothing: " << this->Smoothing << "\n";
  os << indent << "DomainMask: " << this->DomainMask << "\n";
  os << indent << "MaskResolution: " << this->MaskResolution << "\n";
}

int vtkMFAEncoder::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkMFAEncoder::RequestData(vtkInformation*, vtkInformationVector** inInfo,
                               vtkInformationVector* outInfo) {
  vtkDataSet* input = vtkDataSet::GetData(inInfo[0]);
  vtkMFAModelData* output = vtkMFAModelData::GetData(outInfo);
  output->Initialize();
  if (!input) {
    vtkErrorMacro("no input data set");
    return 0;
  }

  // A named array from SetInputArrayToProcess; an attribute type (the default) means the
  // active scalars, which is what an empty field name asks the conversions for.
  std::string field;
  if (vtkInformation* array = this->GetInputArrayInformation(0)) {
    if (array->Has(vtkDataObject::FIELD_NAME())) {
      field = array->Get(vtkDataObject::FIELD_NAME());
    }
  }

  mfadvr::EncodeOptions options;
  options.degree = {this->Degree, this->Degree, this->Degree};
  for (int a = 0; a < 3; ++a) {
    options.controlCounts[a] = this->NumberOfControlPoints[a];
  }
  options.smoothing = this->Smoothing;
  if (this->MaxError > 0.0) {
    mfadvr::AdaptiveOptions adaptive;
    adaptive.maxRelativeError = this->MaxError;
    for (int a = 0; a < 3; ++a) {
      adaptive.maxControlCounts[a] = this->MaxNumberOfControlPoints[a];
    }
    adaptive.maxRounds = this->MaxRounds;
    options.adaptive = adaptive;
  }
  options.mask.enabled = this->DomainMask;
  options.mask.longestAxisNodes = this->MaskResolution;
  options.progress = [this](double fraction, const std::string&) {
    this->UpdateProgress(fraction);
  };

  const std::string source = std::string("VTK ") + input->GetClassName();
  try {
    mfadvr::FitReport report;
    mfadvr::Model model;
    if (auto* image = vtkImageData::SafeDownCast(input)) {
      mfadvr::StructuredGrid grid = mfadvr::gridFromVtkImage(image, field, source);
      grid.validate();
      model = mfadvr::encodeStructured(grid, options, &report);
    } else {
      model = mfadvr::encodeScattered(mfadvr::scatteredFromVtkDataSet(input, field, source),
                                      options, &report);
    }
    const double range =
        report.valueMax > report.valueMin ? report.valueMax - report.valueMin : 1.0;
    this->LastMaxRelativeError = report.maxError / range;
    this->LastRMSRelativeError = report.rmsError / range;
    this->LastFitSeconds = report.seconds;
    if (options.adaptive && !report.reachedTarget) {
      vtkWarningMacro("the error bound " << this->MaxError << " was not reached ("
                                         << report.stopReason << "); the best model has max error "
                                         << this->LastMaxRelativeError);
    }
    output->SetModel(std::make_shared<const mfadvr::Model>(std::move(model)));
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
