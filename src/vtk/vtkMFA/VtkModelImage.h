#pragma once
// An MFA model carried by a vtkImageData, the form in which ParaView's pipeline moves a model
// between processes and ranks (it knows nothing of vtkMFAModelData). The carrier holds:
//   point data: the control points (float, x fastest), named after the model's field, so that
//     ParaView offers the array for colouring and keys its colour and opacity maps by the name;
//   field data "MFAModelDescription": the model without its control points (unsigned char,
//     serializeModelWithoutControlPoints: knots, degrees, box, value range, mask, provenance).
// Its dimensions are the control-point counts and its bounds are the region this piece renders:
// the model's box for a whole model, a rank's own part of the domain for one piece of a
// partitioned volume (whose model also covers the ghost layers around it). Private to the
// module.
#include <memory>

#include "vtkSmartPointer.h"

class vtkDataObject;
class vtkImageData;

namespace mfadvr {
class Model;
}

namespace mfadvr::vtkglue {

inline constexpr const char* kModelDescriptionArray = "MFAModelDescription";

// renderBounds (xmin, xmax, ymin, ymax, zmin, zmax): null for the model's box.
vtkSmartPointer<vtkImageData> imageOfModel(const Model& model, const double* renderBounds);

// Whether `data` is an image carrying a model (it has the description array).
bool carriesModel(vtkDataObject* data);

// The model of a carrier; throws mfadvr::Error when the description is damaged or the control
// points are missing, of another type or count.
std::shared_ptr<const Model> modelOfImage(vtkImageData* image);

}  // namespace mfadvr::vtkglue
