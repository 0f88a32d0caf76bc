#include "VtkModelImage.h"

#include "vtkDoubleArray.h"
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

#include "core/model/Model.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"

namespace mfadvr::vtkglue {
namespace {

constexpr const char* kRegionsArray = "MFARegions";

std::string modelArrayName(size_t i) {
  return "MFAModel" + std::to_string(i);
}

}  // namespace

vtkSmartPointer<vtkImageData> imageOfModels(const std::vector<CarriedModel>& models) {
  if (models.empty()) throw Error("internal: a carrier needs at least one model");
  double bounds[6] = {INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY};
  double lo = INFINITY, hi = -INFINITY;
  vtkNew<vtkDoubleArray> regions;
  regions->SetName(kRegionsArray);
  regions->SetNumberOfComponents(6);
  auto image = vtkSmartPointer<vtkImageData>::New();
  for (size_t i = 0; i < models.size(); ++i) {
    const Model& m = *models[i].model;
    regions->InsertNextTuple(models[i].region);
    for (int a = 0; a < 3; ++a) {
      bounds[2 * a] = std::min(bounds[2 * a], models[i].region[2 * a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], models[i].region[2 * a + 1]);
    }
    lo = std::min(lo, m.valueMin());
    hi = std::max(hi, m.valueMax());
    const std::string bytes = serializeModel(m);
    vtkNew<vtkUnsignedCharArray> array;
    array->SetName(modelArrayName(i).c_str());
    array->SetNumberOfTuples(static_cast<vtkIdType>(bytes.size()));
    std::memcpy(array->GetPointer(0), bytes.data(), bytes.size());
    image->GetFieldData()->AddArray(array);
  }
  image->GetFieldData()->AddArray(regions);
  image->SetDimensions(2, 2, 2);
  image->SetOrigin(bounds[0], bounds[2], bounds[4]);
  image->SetSpacing(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]);
  const std::string& field = models.front().model->provenance().field;
  vtkNew<vtkFloatArray> range;
  range->SetName(field.empty() ? "MFA value" : field.c_str());
  range->SetNumberOfTuples(8);
  for (vtkIdType i = 0; i < 8; ++i) range->SetValue(i, static_cast<float>(i % 2 ? hi : lo));
  image->GetPointData()->SetScalars(range);
  return image;
}

bool carriesModels(vtkDataObject* data) {
  auto* image = vtkImageData::SafeDownCast(data);
  return image && image->GetFieldData() &&
         image->GetFieldData()->GetAbstractArray(kRegionsArray) != nullptr;
}

std::vector<CarriedModel> modelsOfImage(vtkImageData* image) {
  if (!carriesModels(image)) throw Error("the image data does not carry MFA models");
  auto* regions =
      vtkDoubleArray::SafeDownCast(image->GetFieldData()->GetAbstractArray(kRegionsArray));
  if (!regions || regions->GetNumberOfComponents() != 6)
    throw Error(std::string("the carrier's ") + kRegionsArray +
                " array must hold doubles, 6 components");
  std::vector<CarriedModel> out;
  for (vtkIdType i = 0; i < regions->GetNumberOfTuples(); ++i) {
    const std::string name = modelArrayName(static_cast<size_t>(i));
    auto* bytes =
        vtkUnsignedCharArray::SafeDownCast(image->GetFieldData()->GetAbstractArray(name.c_str()));
    if (!bytes || bytes->GetNumberOfComponents() != 1)
      throw Error("the carrier lacks its model array " + name);
    CarriedModel c;
    c.model = std::make_shared<const Model>(parseModel(
        std::span<const std::uint8_t>(bytes->GetPointer(0),
                                      static_cast<size_t>(bytes->GetNumberOfTuples())),
        "the carried model " + name));
    regions->GetTypedTuple(i, c.region);
    for (int a = 0; a < 3; ++a)
      if (!(c.region[2 * a] <= c.region[2 * a + 1]))
        throw Error("the region of " + name + " is empty or not a number");
    out.push_back(std::move(c));
  }
  if (out.empty()) throw Error("the carrier holds no model");
  return out;
}

}  // namespace mfadvr::vtkglue
