#include "VtkModelImage.h"

#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "core/model/Model.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"

namespace mfadvr::vtkglue {
namespace {

std::string arrayNameOf(const Model& model) {
  const std::string& field = model.provenance().field;
  return field.empty() ? std::string("MFA control points") : field;
}

}  // namespace

vtkSmartPointer<vtkImageData> imageOfModel(const Model& model, const double* renderBounds) {
  const Index3 n = model.spline().counts();
  double bounds[6];
  for (int a = 0; a < 3; ++a) {
    bounds[2 * a] = renderBounds ? renderBounds[2 * a] : model.domain().min[a];
    bounds[2 * a + 1] = renderBounds ? renderBounds[2 * a + 1] : model.domain().max[a];
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2]));
  image->SetOrigin(bounds[0], bounds[2], bounds[4]);
  image->SetSpacing((bounds[1] - bounds[0]) / static_cast<double>(n[0] - 1),
                    (bounds[3] - bounds[2]) / static_cast<double>(n[1] - 1),
                    (bounds[5] - bounds[4]) / static_cast<double>(n[2] - 1));

  const std::vector<float>& ctrl = model.spline().controlPoints();
  vtkNew<vtkFloatArray> points;
  points->SetName(arrayNameOf(model).c_str());
  points->SetNumberOfTuples(static_cast<vtkIdType>(ctrl.size()));
  std::copy(ctrl.begin(), ctrl.end(), points->GetPointer(0));
  image->GetPointData()->SetScalars(points);

  const std::string description = serializeModelWithoutControlPoints(model);
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetName(kModelDescriptionArray);
  bytes->SetNumberOfTuples(static_cast<vtkIdType>(description.size()));
  std::memcpy(bytes->GetPointer(0), description.data(), description.size());
  image->GetFieldData()->AddArray(bytes);
  return image;
}

bool carriesModel(vtkDataObject* data) {
  auto* image = vtkImageData::SafeDownCast(data);
  return image && image->GetFieldData() &&
         image->GetFieldData()->GetAbstractArray(kModelDescriptionArray) != nullptr;
}

std::shared_ptr<const Model> modelOfImage(vtkImageData* image) {
  if (!carriesModel(image)) throw Error("the image data does not carry an MFA model");
  auto* bytes = vtkUnsignedCharArray::SafeDownCast(
      image->GetFieldData()->GetAbstractArray(kModelDescriptionArray));
  if (!bytes || bytes->GetNumberOfComponents() != 1)
    throw Error(std::string("the ") + kModelDescriptionArray +
                " field array must hold unsigned chars, one component");
  const std::span<const std::uint8_t> description(bytes->GetPointer(0),
                                                  static_cast<size_t>(bytes->GetNumberOfTuples()));
  auto* points = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  if (!points || points->GetNumberOfComponents() != 1)
    throw Error("the model's control points (the image's point scalars, float, one component) "
                "are missing");
  int dims[3];
  image->GetDimensions(dims);
  const vtkIdType count = points->GetNumberOfTuples();
  if (count != static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2])
    throw Error("the image's control points do not match its dimensions");
  std::vector<float> ctrl(points->GetPointer(0), points->GetPointer(0) + count);
  auto model = std::make_shared<const Model>(
      parseModelWithControlPoints(description, std::move(ctrl), "the MFA model description"));
  const Index3 n = model->spline().counts();
  if (n[0] != dims[0] || n[1] != dims[1] || n[2] != dims[2])
    throw Error("the image's dimensions differ from the model's control-point counts");
  return model;
}

}  // namespace mfadvr::vtkglue
