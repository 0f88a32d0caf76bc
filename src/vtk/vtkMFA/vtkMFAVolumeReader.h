/**
 * @class   vtkMFAVolumeReader
 * @brief   reads a volume file as `mfadvr encode` does, one requested extent at a time
 *
 * Reads every volume input of the command line (docs/input-formats.md): raw files named
 * NAME_XxYxZ_TYPE.raw, NRRD, MetaImage, NIfTI, legacy VTK structured points, VTK XML image
 * data, DICOM directories and built-in functions (builtin:NAME:N), into vtkImageData with the
 * grid and the array name the command line fits. A header is checked against its data before
 * any VTK reader sees it, so a damaged file is an error message, not a crash.
 *
 * Files whose samples lie uncompressed in one file (raw; NRRD, MetaImage, NIfTI and legacy
 * structured points with one binary component), and gzip NRRD and NIfTI data (inflated once to
 * a temporary file), are read box by box: the output holds exactly the requested extent, read
 * from disk, in the file's own sample type (float32 for calibrated NIfTI). So each rank of a
 * parallel pipeline reads only its piece (CAN_PRODUCE_SUB_EXTENT), which VTK 9.1's NRRD reader
 * cannot do. Other inputs (text data, several components, rotated axes, a chosen array,
 * compressed MetaImage, XML, DICOM, built-ins) are read whole as float32 and the extent is
 * copied out of them: every rank then holds the whole volume while it reads.
 *
 * The array has the name VTK's reader of the format gives it (`ImageFile` for raw files, whose
 * format names no field). Errors are reported with vtkErrorMacro and leave the output empty.
 *
 * Gzip data is inflated at the first RequestData (RequestInformation reads the header only),
 * up to the last z plane of the requested extent, and only the requested planes are kept (a
 * piece's planes, in a parallel pipeline; a later request for other planes inflates again).
 * That takes seconds per gigabyte: the reader reports it as progress (ProgressEvent, progress
 * text "inflating FILE"), and an observer that sets AbortExecute stops it, which is then an
 * error like a bad file's.
 */
#ifndef vtkMFAVolumeReader_h
#define vtkMFAVolumeReader_h

#include "vtkImageAlgorithm.h"
#include "vtkMFAModule.h"  // for export macro

#include <cstdint>  // for plane numbers
#include <memory>   // for the open file

class VTKMFA_EXPORT vtkMFAVolumeReader : public vtkImageAlgorithm {
 public:
  static vtkMFAVolumeReader* New();
  vtkTypeMacro(vtkMFAVolumeReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  //@{
  /**
   * The volume file (or DICOM directory, or builtin:NAME:N) to read.
   */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  //@}

  /**
   * Whether this reader reads the file as a volume, from its name and, for a legacy .vtk
   * file, its header (a structured-points data set); it does not validate the data.
   */
  static bool CanReadFile(const char* fileName);

 protected:
  vtkMFAVolumeReader();
  ~vtkMFAVolumeReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  char* FileName = nullptr;

 private:
  struct Opened;
  // FileName opened (its header read and checked), kept while the file
  // and its modification time stay the same.
  Opened& Open();
  // Makes `opened` hold the z planes z0 .. z1 of its gzip samples (with those it held),
  // inflated into a temporary file, reporting progress.
  void Inflate(Opened& opened, std::int64_t z0, std::int64_t z1);
  std::shared_ptr<Opened> Cached;

  vtkMFAVolumeReader(const vtkMFAVolumeReader&) = delete;
  void operator=(const vtkMFAVolumeReader&) = delete;
};

#endif
