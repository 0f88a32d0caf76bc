#include "core/model/ZfpLibrary.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/Error.h"

#ifndef MFADVR_ZFP_LIBRARY
#define MFADVR_ZFP_LIBRARY "libzfp.so.1"
#endif

namespace mfadvr {
namespace {

constexpr const char* kSoname = "libzfp.so.1";
// Overrides the candidates (a ZFP built elsewhere; the tests' way to a ZFP that fails).
constexpr const char* kOverride = "MFADVR_ZFP_LIBRARY";

template <typename F>
void resolve(void* handle, const char* name, F& slot, std::string& missing) {
  slot = reinterpret_cast<F>(dlsym(handle, name));
  if (!slot) missing += std::string(missing.empty() ? "" : ", ") + name;
}

// ZFP's answer on one 4 x 4 x 4 block of a smooth ramp, compressed to 1e-3 and back: the stream
// must be non-empty, decode to its own length, and every value must be within the tolerance.
std::string roundTripFailure(const ZfpLibrary& z) {
  constexpr int kSide = 4;
  constexpr double kTolerance = 1e-3;
  std::vector<float> values(kSide * kSide * kSide), decoded(values.size(), -1.0f);
  for (size_t i = 0; i < values.size(); ++i)
    values[i] = 0.25f * static_cast<float>(i % 7) + 0.01f * i;
  zfp_field* in = z.field_3d(values.data(), zfp_type_float, kSide, kSide, kSide);
  zfp_field* out = z.field_3d(decoded.data(), zfp_type_float, kSide, kSide, kSide);
  zfp_stream* stream = z.stream_open(nullptr);
  std::string why;
  if (!in || !out || !stream) why = "it cannot set up a field and a stream";
  bitstream* bits = nullptr;
  std::vector<std::uint64_t> words;
  if (why.empty()) {
    z.set_accuracy(stream, kTolerance);
    words.assign(z.maximum_size(stream, in) / sizeof(std::uint64_t) + 2, 0);
    bits = z.bitstream_open(words.data(), words.size() * sizeof(std::uint64_t));
    if (!bits) why = "it cannot open a bit stream";
  }
  if (why.empty()) {
    z.set_bit_stream(stream, bits);
    z.rewind(stream);
    const size_t written = z.compress(stream, in);
    z.rewind(stream);
    const size_t read = written ? z.decompress(stream, out) : 0;
    if (written == 0 || read != written) {
      why = "a round trip through compression wrote " + std::to_string(written) +
            " bytes and read " + std::to_string(read);
    } else {
      for (size_t i = 0; i < values.size() && why.empty(); ++i)
        if (!(std::abs(decoded[i] - values[i]) <= kTolerance))
          why = "a round trip through compression returned wrong values";
    }
  }
  if (bits) z.bitstream_close(bits);
  if (stream) z.stream_close(stream);
  if (in) z.field_free(in);
  if (out) z.field_free(out);
  return why;
}

struct Loaded {
  ZfpLibrary library{};
  std::string error;  // empty when the library is usable
};

// One attempt at a file: "" and a filled library, or why it is not usable.
std::string loadFrom(const char* file, ZfpLibrary& z) {
  // A namespace of its own: ZFP's references bind to ZFP (and its libc), never to a same-named
  // function of another library of this process.
  void* handle = dlmopen(LM_ID_NEWLM, file, RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    return why ? why : "dlmopen failed";
  }
  std::string missing;
  resolve(handle, "zfp_field_3d", z.field_3d, missing);
  resolve(handle, "zfp_field_4d", z.field_4d, missing);
  resolve(handle, "zfp_field_free", z.field_free, missing);
  resolve(handle, "zfp_stream_open", z.stream_open, missing);
  resolve(handle, "zfp_stream_close", z.stream_close, missing);
  resolve(handle, "zfp_stream_set_rate", z.set_rate, missing);
  resolve(handle, "zfp_stream_set_accuracy", z.set_accuracy, missing);
  resolve(handle, "zfp_stream_maximum_size", z.maximum_size, missing);
  resolve(handle, "zfp_stream_set_bit_stream", z.set_bit_stream, missing);
  resolve(handle, "zfp_stream_rewind", z.rewind, missing);
  resolve(handle, "zfp_compress", z.compress, missing);
  resolve(handle, "zfp_decompress", z.decompress, missing);
  resolve(handle, "stream_open", z.bitstream_open, missing);
  resolve(handle, "stream_close", z.bitstream_close, missing);
  std::string why =
      missing.empty() ? roundTripFailure(z) : "it lacks the function(s) " + missing + " of zfp 1.0";
  // The namespace stays loaded for the life of the process (ZFP is loaded once); a library that
  // failed is closed.
  if (!why.empty()) dlclose(handle);
  z.path = file;
  return why;
}

Loaded load() {
  Loaded out;
  std::vector<std::string> tried;
  const char* override = std::getenv(kOverride);
  const bool overridden = override && *override;
  std::vector<const char*> files;
  if (overridden) {
    files.push_back(override);
  } else {
    // The library mfadvr was built against (its full path), then its soname through the dynamic
    // linker's search (LD_LIBRARY_PATH, the cache).
    files.push_back(MFADVR_ZFP_LIBRARY);
    if (std::string_view(MFADVR_ZFP_LIBRARY) != kSoname) files.push_back(kSoname);
  }
  for (const char* file : files) {
    const std::string why = loadFrom(file, out.library);
    if (why.empty()) return out;
    tried.push_back(std::string(file) + ": " + why);
  }
  out.error = "ZFP (the coder of zfp-coded control points, zfp 1.0's libzfp.so.1) is not usable";
  if (overridden) out.error += std::string(" (") + kOverride + " names " + override + ")";
  for (const std::string& t : tried) out.error += "; " + t;
  out.error += ". Install libzfp1 (Debian: apt-get install libzfp1) or point " +
               std::string(kOverride) +
               " at a libzfp.so.1; models coded float32 or lossless need no ZFP";
  return out;
}

}  // namespace

const ZfpLibrary& zfpLibrary() {
  static const Loaded loaded = load();
  if (!loaded.error.empty()) throw Error(loaded.error);
  return loaded.library;
}

}  // namespace mfadvr
