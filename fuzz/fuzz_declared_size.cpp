// libFuzzer target: the header checks that run before VTK's readers (io/DeclaredSizeCheck.h).
// The first byte picks the format; the rest is the header (and, for DICOM, the whole file).
// Every input must end in a return or an mfadvr::Error, never a crash or a hang.
#include <cstdint>
#include <sstream>
#include <string>

#include "core/util/Error.h"
#include "io/DeclaredSizeCheck.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  const auto fileBytes = static_cast<std::int64_t>(bytes.size());
  // A detached data file of a size taken from the input, so that both fits and misfits occur.
  const mfadvr::DataFileSize dataFile = [&](const std::string& name) -> std::int64_t {
    return name.empty() ? -1 : static_cast<std::int64_t>(name.size()) * 4096;
  };
  try {
    switch (data[0] % 6) {
      case 0:
        (void)mfadvr::checkNrrdHeaderText(bytes, "f.nrrd", fileBytes, dataFile);
        break;
      case 1:
        mfadvr::checkMetaImageHeaderText(bytes, "f.mha", fileBytes, dataFile);
        break;
      case 2:
        mfadvr::checkLegacyVtkHeaderText(bytes, "f.vtk", fileBytes);
        break;
      case 3:
        mfadvr::checkXmlVtkText(bytes, bytes.substr(bytes.size() > 256 ? bytes.size() - 256 : 0),
                                "f.vti", fileBytes);
        break;
      case 4:
        (void)mfadvr::checkNiftiHeaderBytes(bytes, "f.nii", fileBytes, (data[0] & 8) != 0);
        break;
      case 5: {
        std::istringstream in(bytes);
        mfadvr::checkDicomFile(in, fileBytes, "f.dcm");
        break;
      }
    }
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
