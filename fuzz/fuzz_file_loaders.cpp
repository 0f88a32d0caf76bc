// libFuzzer target: the loaders as the command line calls them, VTK's readers included,
// through our wrapper (header checks, message capture, array checks, grid validation). The
// first byte picks the kind of file; the rest is written to a scratch file of that kind and
// loaded (FileLoaderInput.h). Every input must give a valid grid or point set, or an
// mfadvr::Error: no crash, hang or partial data.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "FileLoaderInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  static const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mfadvr-fuzz-" + std::to_string(::getpid()));
  (void)mfadvr::fuzzing::loadFuzzInput(data, size, dir);
  return 0;
}
