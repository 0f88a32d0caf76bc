/**
 * @class   vtkMFAModelAlgorithm
 * @brief   superclass for algorithms whose output is a vtkMFAModelData
 *
 * Creates the output data object (VTK's executives only know built-in types), and dispatches
 * the pipeline requests to RequestInformation and RequestData like vtkDataObjectAlgorithm.
 * Subclasses set their inputs (none for a reader) and implement RequestData.
 */
#ifndef vtkMFAModelAlgorithm_h
#define vtkMFAModelAlgorithm_h

#include "vtkAlgorithm.h"
#include "vtkMFAModule.h"  // for export macro

class vtkMFAModelData;

class VTKMFA_EXPORT vtkMFAModelAlgorithm : public vtkAlgorithm {
 public:
  vtkTypeMacro(vtkMFAModelAlgorithm, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The output model.
   */
  vtkMFAModelData* GetOutput();

  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inInfo,
                             vtkInformationVector* outInfo) override;

 protected:
  vtkMFAModelAlgorithm();
  ~vtkMFAModelAlgorithm() override;

  virtual int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  virtual int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) = 0;

  int FillOutputPortInformation(int port, vtkInformation* info) override;

 private:
  vtkMFAModelAlgorithm(const vtkMFAModelAlgorithm&) = delete;
  void operator=(const vtkMFAModelAlgorithm&) = delete;
};

#endif
