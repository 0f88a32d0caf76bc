/**
 * @class   vtkMFAModelData
 * @brief   an MFA model (tensor-product B-spline over a box) as a VTK data object
 *
 * Carries an mfadvr model through a pipeline, from vtkMFAReader or vtkMFAEncoder to
 * vtkMFAVolumeMapper. The model itself is immutable and shared: ShallowCopy and DeepCopy share
 * it, which is safe because nothing modifies a model after it is made. The query methods
 * evaluate the spline exactly (value, analytic gradient) at world points.
 */
#ifndef vtkMFAModelData_h
#define vtkMFAModelData_h

#include "vtkDataObject.h"
#include "vtkMFAModule.h"  // for export macro

#ifndef __VTK_WRAP__
#include <memory>  // for std::shared_ptr
namespace mfadvr {
class Model;
}
#endif

class vtkInformation;
class vtkInformationVector;

class VTKMFA_EXPORT vtkMFAModelData : public vtkDataObject {
 public:
  static vtkMFAModelData* New();
  vtkTypeMacro(vtkMFAModelData, vtkDataObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Initialize() override;
  void ShallowCopy(vtkDataObject* src) override;
  void DeepCopy(vtkDataObject* src) override;
  unsigned long GetActualMemorySize() override;

  /**
   * Whether a model is present.
   */
  bool HasModel() const;

  /**
   * The model's box (xmin, xmax, ymin, ymax, zmin, zmax); all zero without a model.
   */
  void GetBounds(double bounds[6]);
  double* GetBounds() VTK_SIZEHINT(6);

  /**
   * The value range of the data the model was fitted to (what normalized transfer functions
   * refer to).
   */
  void GetScalarRange(double range[2]);
  double* GetScalarRange() VTK_SIZEHINT(2);

  /**
   * Spline degree and control-point count per axis.
   */
  void GetDegree(int degree[3]);
  void GetNumberOfControlPoints(int counts[3]);

  /**
   * Whether the model has a domain mask (models of meshes and point clouds): outside it the
   * model is undefined and renders empty.
   */
  bool HasDomainMask() const;

  /**
   * Name of the scalar field the model was fitted to.
   */
  const char* GetFieldName();

  /**
   * Exact value at a world point (clamped onto the box).
   */
  double EvaluateValue(double x, double y, double z);

  /**
   * Exact gradient at a world point.
   */
  void EvaluateGradient(double x, double y, double z, double gradient[3]);

  /**
   * Whether a world point is inside the box and the domain mask.
   */
  bool IsInside(double x, double y, double z);

  //@{
  /**
   * The model in a pipeline information object.
   */
  static vtkMFAModelData* GetData(vtkInformation* info);
  static vtkMFAModelData* GetData(vtkInformationVector* v, int i = 0);
  //@}

#ifndef __VTK_WRAP__
  /**
   * The model (C++ only).
   */
  void SetModel(std::shared_ptr<const mfadvr::Model> model);
  const std::shared_ptr<const mfadvr::Model>& GetModel() const {
    return this->Model;
  }
#endif

 protected:
  vtkMFAModelData();
  ~vtkMFAModelData() override;

  double Bounds[6] = {0, 0, 0, 0, 0, 0};
  double ScalarRange[2] = {0, 0};

 private:
  vtkMFAModelData(const vtkMFAModelData&) = delete;
  void operator=(const vtkMFAModelData&) = delete;

#ifndef __VTK_WRAP__
  std::shared_ptr<const mfadvr::Model> Model;
#endif
};

#endif
