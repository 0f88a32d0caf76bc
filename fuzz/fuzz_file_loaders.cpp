// libFuzzer target: the loaders as the command line calls them, VTK's readers included,
// through our wrapper (header checks, message capture, array checks, grid validation). The
// first byte picks the kind of file; the rest is written to a scratch file of that kind and
// loaded. Every input must give a valid grid or point set, or an mfadvr::Error: no crash,
// hang or partial data.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/util/Error.h"
#include "io/ScatteredLoader.h"
#include "io/VolumeLoader.h"

namespace {

struct Kind {
  const char* name;  // file name in the scratch folder ("" for a DICOM series folder)
  bool volume;
};

constexpr Kind kKinds[] = {
    {"f.nrrd", true},  {"f.mha", true}, {"f.vtk", true},  {"f.vti", true},
    {"f.nii", true},   {"f.nii.gz", true}, {"", true},     {"v_4x3x2_uint8.raw", true},
    {"m.vtu", false},  {"m.vtk", false}, {"p.csv", false},
};

std::filesystem::path scratch() {
  static const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mfadvr-fuzz-" + std::to_string(::getpid()));
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const Kind& kind = kKinds[data[0] % (sizeof kKinds / sizeof kKinds[0])];
  const auto dir = scratch();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::filesystem::path input = dir / kind.name;
  std::filesystem::path file = input;
  if (std::string(kind.name).empty()) {  // a DICOM series of one slice
    input = dir / "series";
    std::filesystem::create_directories(input);
    file = input / "s.dcm";
  }
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(data) + 1, static_cast<std::streamsize>(size - 1));
  try {
    if (kind.volume) {
      const mfadvr::StructuredGrid g = mfadvr::loadStructuredVolume(input.string());
      if (static_cast<std::int64_t>(g.values.size()) != g.sampleCount()) __builtin_trap();
    } else {
      const mfadvr::ScatteredData d = mfadvr::loadScatteredData(input.string());
      if (d.points.size() != d.values.size()) __builtin_trap();
    }
  } catch (const mfadvr::Error&) {
  }
  return 0;
}
