// libFuzzer target: the time-series collections (ParaView's .pvd XML and .series JSON,
// io/VolumeSeriesReader.h) must turn any text into a list of steps or an Error.
#include <cstdint>
#include <string>

#include "core/util/Error.h"
#include "io/VolumeSeriesReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool json : {false, true}) {
    try {
      const mfadvr::CollectionSteps s = mfadvr::parseCollection(text, "/fuzz/run.pvd", json);
      if (s.files.size() != s.times.size() || s.files.empty()) __builtin_trap();
    } catch (const mfadvr::Error&) {
    }
  }
  return 0;
}
