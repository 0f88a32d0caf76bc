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

// The model of a carrier's byte array. Its float32 control points stay in the array, which the
// model holds (a reference): no second copy of what the pipeline already holds.
std::shared_ptr<const Model> modelOfArray(vtkUnsignedCharArray* bytes, const std::string& name) {
  auto owner = std::make_shared<const vtkSmartPointer<vtkUnsignedCharArray>>(bytes);
  return std::make_shared<const Model>(
      parseModel(std::span<const std::uint8_t>(bytes->GetPointer(0),
                                               static_cast<size_t>(bytes->GetNumberOfTuples())),
                 name, nullptr, std::move(owner)));
}

}  // namespace

CarrierGrid wholeCarrierGrid(const DomainBox& box, const Vec3d& step) {
  CarrierGrid g;
  for (int a = 0; a < 3; ++a) {
    const double extent = box.max[a] - box.min[a];
    const double n = extent > 0.0 && step[a] > 0.0 ? std::round(extent / step[a]) + 1.0 : 2.0;
    const int dims = static_cast<int>(std::clamp(n, 2.0, 65536.0));
    g.origin[a] = box.min[a];
    g.spacing[a] = extent > 0.0 ? extent / (dims - 1) : 1.0;
    g.extent[2 * a] = 0;
    g.extent[2 * a + 1] = dims - 1;
  }
  return g;
}

CarrierGrid carrierSubGrid(const CarrierGrid& whole, const DomainBox& region) {
  CarrierGrid g = whole;
  for (int a = 0; a < 3; ++a) {
    const int lo = whole.extent[2 * a], hi = whole.extent[2 * a + 1];
    const auto index = [&](double x) {
      const double i = std::round((x - whole.origin[a]) / whole.spacing[a]);
      return static_cast<int>(std::clamp(i, static_cast<double>(lo), static_cast<double>(hi)));
    };
    int first = index(region.min[a]), last = index(region.max[a]);
    if (last <= first) {  // a region thinner than a cell still gets one
      last = std::min(first + 1, hi);
      first = last - 1;
    }
    g.extent[2 * a] = first;
    g.extent[2 * a + 1] = last;
  }
  return g;
}

vtkSmartPointer<vtkImageData> imageOfModels(std::vector<CarriedModel> models, const int* firstIndex,
                                            const CarrierValues& values, const int* reach) {
  if (models.empty()) throw Error("internal: a carrier needs at least one model");
  DomainBox all = models.front().region;
  for (const auto& m : models) {
    all.min = all.min.cwiseMin(m.region.min);
    all.max = all.max.cwiseMax(m.region.max);
  }
  // The data's grid over the regions, moved to start at firstIndex.
  CarrierGrid grid = wholeCarrierGrid(all, models.front().model->dataSpacing());
  if (firstIndex) {
    for (int a = 0; a < 3; ++a) {
      grid.origin[a] -= firstIndex[a] * grid.spacing[a];
      grid.extent[2 * a] += firstIndex[a];
      grid.extent[2 * a + 1] += firstIndex[a];
    }
  }
  if (reach && values && !std::equal(reach, reach + 6, grid.extent)) {
    CarrierGrid wide = grid;  // the origin is that of index 0: the same for the wider extent
    std::copy(reach, reach + 6, wide.extent);
    if (vtkSmartPointer<vtkDataArray> samples = values(wide)) {
      vtkSmartPointer<vtkImageData> image = imageOfModels(
          std::move(models), wide, [&samples](const CarrierGrid&) { return samples; });
      image->GenerateGhostArray(grid.extent, true);
      return image;
    }
  }
  return imageOfModels(std::move(models), grid, values);
}

vtkSmartPointer<vtkImageData> imageOfModels(std::vector<CarriedModel> models,
                                            const CarrierGrid& grid, const CarrierValues& given) {
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
    vtkNew<vtkUnsignedCharArray> array;
    array->SetName(modelArrayName(i).c_str());
    serializeModel(*models[i].model, [&array](size_t bytes) {
      array->SetNumberOfTuples(static_cast<vtkIdType>(bytes));
      return array->GetPointer(0);
    });
    image->GetFieldData()->AddArray(array);
    // From here on the model is the one in the array: the caller's copy goes now (when it gave
    // up its references), before the values on the grid are computed.
    models[i].model = modelOfArray(array, "the carried model " + modelArrayName(i));
  }
  image->GetFieldData()->AddArray(regions);
  const double bounds[6] = {all.min[0], all.max[0], all.min[1], all.max[1], all.min[2], all.max[2]};

  image->SetExtent(const_cast<int*>(grid.extent));
  image->SetOrigin(grid.origin.data());
  image->SetSpacing(grid.spacing.data());
  int dims[3];
  image->GetDimensions(dims);
  if (given) {
    if (vtkSmartPointer<vtkDataArray> samples = given(grid)) {
      if (samples->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2])
        throw Error("internal: the carrier's given values do not match its grid");
      image->GetPointData()->SetScalars(samples);
      return image;
    }
  }
  const int* first = grid.extent;
  const double spacing[3] = {grid.spacing[0], grid.spacing[1], grid.spacing[2]};
  // Position of point i (of the carrier's own numbering, from 0) along axis a: on the grid, the
  // last one on the regions' face (no rounding past it).
  const auto coordinate = [&](int a, int i) {
    if (i + 1 == dims[a]) return bounds[2 * a + 1];
    if (i == 0) return bounds[2 * a];
    return grid.origin[a] + (first[2 * a] + i) * spacing[a];
  };

  // Each point takes the value of the first model whose region holds it (neighbours share
  // their faces, where their models agree), evaluated a z plane at a time on all cores.
  vtkNew<vtkFloatArray> values;
  values->SetName(carrierArrayName(*models.front().model).c_str());
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
          const Vec3d x(coordinate(0, i), coordinate(1, j), coordinate(2, k));
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

std::string carrierArrayName(const Model& model) {
  const std::string& field = model.provenance().field;
  return field.empty() ? "MFA value" : field;
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
    c.model = modelOfArray(bytes, "the carried model " + name);
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
