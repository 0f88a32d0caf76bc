#include "vtkMFAModelData.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"

#include "core/model/Model.h"
#include "core/model/ModelFile.h"

vtkStandardNewMacro(vtkMFAModelData);

vtkMFAModelData::vtkMFAModelData() = default;
vtkMFAModelData::~vtkMFAModelData() = default;

void vtkMFAModelData::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  if (!this->Model) {
    os << indent << "Model: (none)\n";
    return;
  }
  int degree[3], counts[3];
  double bounds[6], range[2];
  this->GetDegree(degree);
  this->GetNumberOfControlPoints(counts);
  this->GetBounds(bounds);
  this->GetScalarRange(range);
  os << indent << "Degree: " << degree[0] << " " << degree[1] << " " << degree[2] << "\n";
  os << indent << "Control points: " << counts[0] << " x " << counts[1] << " x " << counts[2]
     << "\n";
  os << indent << "Bounds: " << bounds[0] << " " << bounds[1] << " " << bounds[2] << " "
     << bounds[3] << " " << bounds[4] << " " << bounds[5] << "\n";
  os << indent << "Scalar range: " << range[0] << " " << range[1] << "\n";
  os << indent << "Field: " << this->Model->provenance().field << "\n";
  os << indent << "Domain mask: " << (this->HasDomainMask() ? "yes" : "no") << "\n";
}

void vtkMFAModelData::Initialize() {
  this->Superclass::Initialize();
  this->Model.reset();
}

void vtkMFAModelData::ShallowCopy(vtkDataObject* src) {
  if (auto* other = vtkMFAModelData::SafeDownCast(src)) {
    this->Model = other->Model;
    this->Modified();
  }
  this->Superclass::ShallowCopy(src);
}

void vtkMFAModelData::DeepCopy(vtkDataObject* src) {
  // Models are immutable once made, so sharing one is a deep copy in every observable way.
  if (auto* other = vtkMFAModelData::SafeDownCast(src)) {
    this->Model = other->Model;
    this->Modified();
  }
  this->Superclass::DeepCopy(src);
}

unsigned long vtkMFAModelData::GetActualMemorySize() {
  unsigned long kib = this->Superclass::GetActualMemorySize();
  if (this->Model) {
    const auto c = this->Model->spline().counts();
    kib += static_cast<unsigned long>(c[0] * c[1] * c[2] * sizeof(float) / 1024);
  }
  return kib;
}

bool vtkMFAModelData::HasModel() const {
  return static_cast<bool>(this->Model);
}

void vtkMFAModelData::GetBounds(double bounds[6]) {
  for (int i = 0; i < 6; ++i) {
    bounds[i] = 0.0;
  }
  if (!this->Model) {
    return;
  }
  const auto& box = this->Model->domain();
  for (int a = 0; a < 3; ++a) {
    bounds[2 * a] = box.min[a];
    bounds[2 * a + 1] = box.max[a];
  }
}

double* vtkMFAModelData::GetBounds() {
  this->GetBounds(this->Bounds);
  return this->Bounds;
}

double* vtkMFAModelData::GetScalarRange() {
  this->GetScalarRange(this->ScalarRange);
  return this->ScalarRange;
}

void vtkMFAModelData::GetScalarRange(double range[2]) {
  range[0] = this->Model ? this->Model->valueMin() : 0.0;
  range[1] = this->Model ? this->Model->valueMax() : 0.0;
}

void vtkMFAModelData::GetDegree(int degree[3]) {
  const auto d = this->Model ? this->Model->spline().degrees() : mfadvr::Degree3{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    degree[a] = d[a];
  }
}

void vtkMFAModelData::GetNumberOfControlPoints(int counts[3]) {
  const auto c = this->Model ? this->Model->spline().counts() : mfadvr::Index3{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    counts[a] = static_cast<int>(c[a]);
  }
}

bool vtkMFAModelData::HasDomainMask() const {
  return this->Model && !this->Model->mask().empty();
}

const char* vtkMFAModelData::GetFieldName() {
  return this->Model ? this->Model->provenance().field.c_str() : "";
}

double vtkMFAModelData::EvaluateValue(double x, double y, double z) {
  if (!this->Model) {
    vtkErrorMacro("EvaluateValue: no model");
    return 0.0;
  }
  return this->Model->value(mfadvr::Vec3d(x, y, z));
}

void vtkMFAModelData::EvaluateGradient(double x, double y, double z, double gradient[3]) {
  gradient[0] = gradient[1] = gradient[2] = 0.0;
  if (!this->Model) {
    vtkErrorMacro("EvaluateGradient: no model");
    return;
  }
  const auto vg = this->Model->valueGradient(mfadvr::Vec3d(x, y, z));
  for (int a = 0; a < 3; ++a) {
    gradient[a] = vg.gradient[a];
  }
}

bool vtkMFAModelData::IsInside(double x, double y, double z) {
  if (!this->Model) {
    return false;
  }
  const mfadvr::Vec3d p(x, y, z);
  return this->Model->domain().contains(p) && this->Model->inside(p);
}

vtkMFAModelData* vtkMFAModelData::GetData(vtkInformation* info) {
  return info ? vtkMFAModelData::SafeDownCast(info->Get(DATA_OBJECT())) : nullptr;
}

vtkMFAModelData* vtkMFAModelData::GetData(vtkInformationVector* v, int i) {
  return vtkMFAModelData::GetData(v->GetInformationObject(i));
}

void vtkMFAModelData::SetModel(std::shared_ptr<const mfadvr::Model> model) {
  this->Model = std::move(model);
  this->Modified();
}
