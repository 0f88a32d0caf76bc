#pragma once
// How fuzz_file_loaders turns a fuzz input into a file: the first byte picks the kind, the rest
// is the file. Shared with the regression test that replays the inputs the fuzzer found
// (tests/io/FuzzRegressionTest.cpp), so both load them the same way.
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/grid/SampleRange.h"
#include "core/util/Error.h"
#include "io/ScatteredLoader.h"
#include "io/StreamedVolumeReader.h"
#include "io/VolumeLoader.h"
#include "io/VolumeSeriesReader.h"

namespace mfadvr::fuzzing {

struct FileKind {
  const char* name;  // file name in the scratch folder ("": a DICOM series folder)
  bool volume;
};

inline constexpr FileKind kFileKinds[] = {
    {"f.nrrd", true}, {"f.mha", true},    {"f.vtk", true},  {"f.vti", true},
    {"f.nii", true},  {"f.nii.gz", true}, {"", true},       {"v_4x3x2_uint8.raw", true},
    {"m.vtu", false}, {"m.vtk", false},   {"p.csv", false}, {"f.nc", true},
};

// Writes the input as a file of its kind under `dir` (emptied first) and loads it as the
// command line would. Returns false when the loader refused it with an mfadvr::Error; traps
// when a loaded grid or point set is inconsistent.
inline bool loadFuzzInput(const std::uint8_t* data, size_t size, const std::filesystem::path& dir) {
  if (size < 1) return false;
  const FileKind& kind = kFileKinds[data[0] % (sizeof kFileKinds / sizeof kFileKinds[0])];
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
    // A file of several time steps (4-D NRRD or NIfTI, NetCDF with a time dimension): every
    // step, as `encode` reads a series.
    if (kind.volume && isVolumeSeriesInput(input.string())) {
      const auto series = openVolumeSeries(input.string());
      for (int s = 0; s < series->size(); ++s) {
        const StructuredGrid step = series->load(s);
        if (static_cast<std::int64_t>(step.values.size()) != step.sampleCount()) __builtin_trap();
      }
    } else if (kind.volume) {
      const StructuredGrid g = loadStructuredVolume(input.string());
      if (static_cast<std::int64_t>(g.values.size()) != g.sampleCount()) __builtin_trap();
      // A streamed file read a box at a time (the out-of-core encoder's reads) must give the
      // same samples as the whole read.
      if (auto source =
              openStreamedVolume(input.string(), {}, GzipPayloads::kInflateToTemporaryFile)) {
        if (source->layout().dims != g.dims) __builtin_trap();
        SampleRange box;
        for (int a = 0; a < 3; ++a) {
          box.lo[a] = g.dims[a] / 4;
          box.hi[a] = std::max(box.lo[a], g.dims[a] - 1 - g.dims[a] / 3);
        }
        if (source->read(box).values != subGrid(g, box).values) __builtin_trap();
      }
    } else {
      const ScatteredData d = loadScatteredData(input.string());
      if (d.points.size() != d.values.size()) __builtin_trap();
    }
    return true;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace mfadvr::fuzzing
