/**
 * @class   vtkMFAReader
 * @brief   reads an MFA model file (.mfa, written by `mfadvr encode`), one model or multi-block
 *
 * The output is a vtkMFAModelData, or with OutputImageData on a vtkImageData carrying the
 * model (vtkMFAModelAlgorithm). A multi-block file (`mfadvr encode --blocks`) needs
 * OutputImageData. In a parallel pipeline with P pieces and B blocks (a single model is one
 * block over its box), piece p reads the blocks p B / P to (p + 1) B / P - 1 (x fastest) when
 * P <= B; when P > B, the pieces share the blocks (P / B or so per block), each reading its
 * block and rendering a slab of the block's region, cut along the region's longest axis. The
 * carriers are sub-extents of one whole image (WHOLE_EXTENT, ORIGIN and SPACING are set at
 * RequestInformation): the data's grid over the whole box, as ParaView expects of the pieces
 * of an image (its view bounds and compositing order come from them). A missing, truncated or
 * damaged file is reported with vtkErrorMacro (the message says what is wrong) and leaves the
 * output empty.
 *
 * A time-varying model (`mfadvr encode` of a series; docs/time-varying.md) advertises its steps
 * as TIME_STEPS and its range as TIME_RANGE, and gives the model at UPDATE_TIME_STEP, any time
 * in the range (clamped onto it), with DATA_TIME_STEP set: ParaView's animation plays it
 * (Snap To TimeSteps, or Sequence for instants between the steps). Without a requested time it
 * gives the first step.
 */
#ifndef vtkMFAReader_h
#define vtkMFAReader_h

#include "vtkMFAModelAlgorithm.h"
#include "vtkMFAModule.h"  // for export macro

#include <memory>  // for the cached layout

namespace mfadvr {
class Model;
class TimeVaryingModel;
}  // namespace mfadvr

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

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;

 private:
  struct Layout;
  // The blocks' regions, the whole box and the data spacing of FileName, read once per file
  // (and again when the file changes).
  const Layout& ReadLayout();
  std::shared_ptr<Layout> Cached;
  // The instant last given of a time-varying model (rendering one time again does not
  // contract the time axis again).
  std::shared_ptr<const mfadvr::Model> Instant;
  std::shared_ptr<const mfadvr::TimeVaryingModel> InstantOf;
  double InstantTime = 0.0;

 private:
  vtkMFAReader(const vtkMFAReader&) = delete;
  void operator=(const vtkMFAReader&) = delete;
};

#endif
