/**
 * @class   vtkMFAReader
 * @brief   reads an MFA model file (.mfa, written by `mfadvr encode`), one model or multi-block
 *
 * The output is a vtkMFAModelData, or with OutputImageData on a vtkImageData carrying the
 * model (vtkMFAModelAlgorithm). A multi-block file (`mfadvr encode --blocks`) needs
 * OutputImageData: in a parallel pipeline, piece p of P reads the blocks p B / P to
 * (p + 1) B / P - 1 (x fastest) and carries them with their regions; a single model is read by
 * piece 0 alone. A missing, truncated or damaged file is reported with vtkErrorMacro (the
 * message says what is wrong) and leaves the output empty.
 */
#ifndef vtkMFAReader_h
#define vtkMFAReader_h

#include "vtkMFAModelAlgorithm.h"
#include "vtkMFAModule.h"  // for export macro

class VTKMFA_EXPORT vtkMFAReader : public vtkMFAModelAlgorithm {
 public:
  static vtkMFAReader* New();
  vtkTypeMacro(vtkMFAReader, vtkMFAModelAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  //@{
  /**
   * The .mfa file to read.
   */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  //@}

  /**
   * Whether the file looks like an MFA model (checks the magic bytes only).
   */
  static bool CanReadFile(const char* fileName);

 protected:
  vtkMFAReader();
  ~vtkMFAReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;

 private:
  vtkMFAReader(const vtkMFAReader&) = delete;
  void operator=(const vtkMFAReader&) = delete;
};

#endif
