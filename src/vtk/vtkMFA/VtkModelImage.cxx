#include "VtkModelImage.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
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

vtkSmartPointer<vtkImageData> imageOfModels(const std::vector<CarriedModel>& models,
                                            const int* firstIndex) {
  if (models.empty()) throw Error("internal: a carrier needs at least one model");
  DomainBox all = models.front().region;
  vtkNew<vtkDoubleArray> regions;
  regions->SetName(kRegionsArray);
  regions->SetNumberOfComponents(6);
  auto image = vtkSmartPointer<vtkImageData>::New();
  for (size_t i = 0; i < models.size(); ++i) {
    const DomainBox& r = models[i].region;
    const double tuple[6] = {r.min[0], r.max[0], r.min[1], r.max[1], r.min[2], r.max[2]};
    regions->InsertNextTuple(tuple);
    all.min = all.min.cwiseMin(r.min);
    all.max = all.max.cwiseMax(r.max);
    const std::string bytes = serializeModel(*models[i].model);
    vtkNew<vtkUnsignedCharArray> array;
    array->SetName(modelArrayName(i).c_str());
    array->SetNumberOfTuples(static_cast<vtkIdType>(bytes.size()));
    std::memcpy(array->GetPointer(0), bytes.data(), bytes.size());
    image->GetFieldData()->AddArray(array);
  }
  image->GetFieldData()->AddArray(regions);
  const double bounds[6] = {all.min[0], all.max[0], all.min[1], all.max[1], all.min[2], all.max[2]};

  // The data's grid over the regions (at least 2 points per axis).
  const Vec3d step = models.front().model->dataSpacing();
  int dims[3];
  double spacing[3];
  for (int a = 0; a < 3; ++a) {
    const double extent = bounds[2 * a + 1] - bounds[2 * a];
    const double n = extent > 0.0 && step[a] > 0.0 ? std::round(extent / step[a]) + 1.0 : 2.0;
    dims[a] = static_cast<int>(std::clamp(n, 2.0, 65536.0));
    spacing[a] = extent / (dims[a] - 1);
  }
  int first[3] = {0, 0, 0};
  if (firstIndex) std::copy(firstIndex, firstIndex + 3, first);
  image->SetExtent(first[0], first[0] + dims[0] - 1, first[1], first[1] + dims[1] - 1, first[2],
                   first[2] + dims[2] - 1);
  image->SetOrigin(bounds[0] - first[0] * spacing[0], bounds[2] - first[1] * spacing[1],
                   bounds[4] - first[2] * spacing[2]);
  image->SetSpacing(spacing);

  // Each point takes the value of the first model whose region holds it (neighbours share
  // their faces, where their models agree), evaluated a z plane at a time on all cores.
  const std::string& field = models.front().model->provenance().field;
  vtkNew<vtkFloatArray> values;
  values->SetName(field.empty() ? "MFA value" : field.c_str());
  values->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
  float* out = values->GetPointer(0);
  std::fill(out, out + values->GetNumberOfTuples(), std::numeric_limits<float>::quiet_NaN());
  const size_t plane = static_cast<size_t>(dims[0]) * dims[1];
  std::vector<Vec3d> points;
  std::vector<size_t> index;
  std::vector<float> result;
  std::vector<char> done(plane);
  for (int k = 0; k < dims[2]; ++k) {
    std::fill(done.begin(), done.end(), 0);
    for (const CarriedModel& c : models) {
      points.clear();
      index.clear();
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i) {
          const size_t at = static_cast<size_t>(i) + static_cast<size_t>(dims[0]) * j;
          if (done[at]) continue;
          // The last point of an axis is the bound itself (no rounding past a region's face).
          const Vec3d x(i + 1 == dims[0] ? bounds[1] : bounds[0] + i * spacing[0],
                        j + 1 == dims[1] ? bounds[3] : bounds[2] + j * spacing[1],
                        k + 1 == dims[2] ? bounds[5] : bounds[4] + k * spacing[2]);
          bool inRegion = true;
          for (int a = 0; a < 3; ++a) {
            const double tolerance = 1e-9 * (bounds[2 * a + 1] - bounds[2 * a]);
            inRegion = inRegion && x[a] >= c.region.min[a] - tolerance &&
                       x[a] <= c.region.max[a] + tolerance;
          }
          if (!inRegion) continue;
          done[at] = 1;
          if (!c.model->inside(x)) continue;  // outside the domain mask: NaN
          points.push_back(x);
          index.push_back(at);
        }
      result.resize(points.size());
      c.model->evaluate(points, result);
      for (size_t p = 0; p < points.size(); ++p) out[plane * k + index[p]] = result[p];
    }
  }
  image->GetPointData()->SetScalars(values);
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
    c.model = std::make_shared<const Model>(
        parseModel(std::span<const std::uint8_t>(bytes->GetPointer(0),
                                                 static_cast<size_t>(bytes->GetNumberOfTuples())),
                   "the carried model " + name));
    double tuple[6];
    regions->GetTypedTuple(i, tuple);
    for (int a = 0; a < 3; ++a) {
      if (!(tuple[2 * a] <= tuple[2 * a + 1]))
        throw Error("the region of " + name + " is empty or not a number");
      c.region.min[a] = tuple[2 * a];
      c.region.max[a] = tuple[2 * a + 1];
    }
    out.push_back(std::move(c));
  }
  if (out.empty()) throw Error("the carrier holds no model");
  return out;
}

}  // namespace mfadvr::vtkglue
