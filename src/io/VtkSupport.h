#pragma once
// Small pieces shared by the VTK-based readers (volumes and scattered data). Internal to
// mfadvr_io: VTK types are only forward-declared, so this header needs no VTK include paths.
#include <memory>
#include <string>

class vtkDataArray;
class vtkDataReader;
class vtkFieldData;

namespace mfadvr {

// VTK readers report failure by printing, not by throwing. While one of these lives, VTK's
// error messages (and std::cerr, which MetaIO writes to directly) are collected instead of
// printed, with VTK's source-location lines and object addresses removed; warnings are
// dropped, except those that say data could not be read (a truncated legacy file), which
// count as errors, as does MetaIO's "data not read completely". VTK's output window and logger are
// process-wide, so captures (and the reads inside them) are serialised.
class VtkMessageCapture {
 public:
  VtkMessageCapture();
  ~VtkMessageCapture();
  VtkMessageCapture(const VtkMessageCapture&) = delete;
  VtkMessageCapture& operator=(const VtkMessageCapture&) = delete;

  bool hasErrors() const;
  // All collected error text on one line, in the order it came; "" when there is none.
  std::string errorText() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// "float32", "int16", "uint8", ...; "" for types that are not plain numbers.
std::string vtkSampleTypeName(vtkDataArray* array);
// The VTK data type (VTK_UNSIGNED_CHAR, ...) that holds samples of a raw sample type name
// (RawVolumeReader.h's: uint8, int8, uint16, int16, uint32, int32, float32, float64). Throws
// mfadvr::Error for any other name.
int vtkTypeOfSampleType(const std::string& name);

// Makes a legacy reader read every SCALARS/VECTORS/COLOR_SCALARS/FIELD block (by default it
// reads only the first SCALARS block, and the field asked for may be another).
void readAllLegacyArrays(vtkDataReader* reader);

// "'Density', 'Momentum' (3 components)", or "none".
std::string describeVtkArrays(vtkFieldData* data);

}  // namespace mfadvr
