/**
 * @class   vtkMFAModelAlgorithm
 * @brief   superclass for algorithms whose output is a vtkMFAModelData
 *
 * Creates the output data object (VTK's executives only know built-in types), and dispatches
 * the pipeline requests to RequestInformation, RequestUpdateExtent and RequestData like
 * vtkDataObjectAlgorithm. Subclasses set their inputs (none for a reader) and implement
 * RequestData, handing the model to SetOutputModel.
 *
 * With OutputImageData on, the output is a vtkImageData that carries the model (and, for a
 * reader of a multi-block file, several): the models as .mfa bytes in field arrays
 * "MFAModel0", ..., the region each renders in "MFARegions", a grid over the regions at the
 * data's spacing holding the model's values (VtkModelImage.h). It is the form ParaView moves
 * between processes, and vtkMFAVolumeMapper renders it like the models themselves. GetOutput() is
 * then null; use GetOutputDataObject(0).
 */
#ifndef vtkMFAModelAlgorithm_h
#define vtkMFAModelAlgorithm_h

#include "vtkAlgorithm.h"
#include "vtkMFAModule.h"  // for export macro

#ifndef __VTK_WRAP__
#include <functional>         // for std::function
#include <memory>             // for std::shared_ptr
#include "vtkSmartPointer.h"  // for the carrier's values
class vtkDataArray;
namespace mfadvr {
class Model;
namespace vtkglue {
struct CarrierGrid;
}
}  // namespace mfadvr
#endif

class vtkMFAModelData;

class VTKMFA_EXPORT vtkMFAModelAlgorithm : public vtkAlgorithm {
 public:
  vtkTypeMacro(vtkMFAModelAlgorithm, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The output model.
   */
  vtkMFAModelData* GetOutput();

  //@{
  /**
   * Output the model as a vtkImageData that carries it (default off: a vtkMFAModelData).
   */
  vtkSetMacro(OutputImageData, bool);
  vtkGetMacro(OutputImageData, bool);
  vtkBooleanMacro(OutputImageData, bool);
  //@}

  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inInfo,
                             vtkInformationVector* outInfo) override;

 protected:
  vtkMFAModelAlgorithm();
  ~vtkMFAModelAlgorithm() override;

  virtual int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  virtual int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  virtual int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) = 0;

#ifndef __VTK_WRAP__
  /**
   * Puts `model` into the output of port 0 (`outInfo`), as the model or as image data that
   * carries it; renderBounds (image data only): the region to render, null for the model's box;
   * firstIndex (image data only): the index of the carrier's first point in the input image's
   * index space, null for 0; values (image data only, optional): the carrier's point scalars
   * instead of the model evaluated on its grid; reach (image data only, with values, optional):
   * the carrier's extent past renderBounds, its cells outside them marked as ghost cells
   * (VtkModelImage.h).
   */
  void SetOutputModel(
      vtkInformationVector* outInfo, std::shared_ptr<const mfadvr::Model> model,
      const double* renderBounds = nullptr, const int* firstIndex = nullptr,
      const std::function<vtkSmartPointer<vtkDataArray>(const mfadvr::vtkglue::CarrierGrid&)>&
          values = {},
      const int* reach = nullptr);
#endif

  bool OutputImageData = false;

  int FillOutputPortInformation(int port, vtkInformation* info) override;

 private:
  vtkMFAModelAlgorithm(const vtkMFAModelAlgorithm&) = delete;
  void operator=(const vtkMFAModelAlgorithm&) = delete;
};

#endif
