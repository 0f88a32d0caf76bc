#pragma once
// MFA models carried by a vtkImageData: the form in which ParaView's pipeline moves models
// between processes and ranks (it knows nothing of vtkMFAModelData). A carrier holds one or
// more models, each with the region it renders (the blocks of a multi-block file that one rank
// reads, or one piece of a partitioned volume):
//   field data "MFAModel0", "MFAModel1", ...: each model as the bytes of a .mfa file (unsigned
//     char), and "MFARegions" (double, 6 components: xmin, xmax, ymin, ymax, zmin, zmax, one
//     tuple per model);
//   geometry: 2 x 2 x 2 points spanning the union of the regions, so that a pipeline sees the
//     carrier where its models render;
//   point scalars: the value range at the corners (float, named after the model's field), so
//     that ParaView offers the array for colouring and scales its colour and opacity maps to
//     the data's range.
// Private to the module.
#include <memory>
#include <vector>

#include "vtkSmartPointer.h"

class vtkDataObject;
class vtkImageData;

namespace mfadvr {
class Model;
struct DomainBox;
}  // namespace mfadvr

namespace mfadvr::vtkglue {

struct CarriedModel {
  std::shared_ptr<const Model> model;
  double region[6];  // xmin, xmax, ymin, ymax, zmin, zmax
};

// regions: one per model, null entries (or an empty vector) for the model's box.
vtkSmartPointer<vtkImageData> imageOfModels(const std::vector<CarriedModel>& models);

// Whether `data` is an image carrying models (it has the regions array).
bool carriesModels(vtkDataObject* data);

// The models of a carrier, checked as a .mfa file is; throws mfadvr::Error for a damaged or
// inconsistent carrier.
std::vector<CarriedModel> modelsOfImage(vtkImageData* image);

}  // namespace mfadvr::vtkglue
