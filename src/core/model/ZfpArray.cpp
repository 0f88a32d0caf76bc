#include "core/model/ZfpArray.h"

#include <cmath>
#include <cstring>
#include <memory>

#include "core/model/ZfpLibrary.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// RAII for ZFP's C objects: a stream in the given mode over a 3-D float field, or a 4-D one of
// `steps` such fields when steps > 1.
class ZfpCodec {
 public:
  ZfpCodec(float* data, const Index3& dims, const ZfpSettings& settings, std::int64_t steps = 1)
      : zfp_(zfpLibrary()),
        field_(steps > 1
                   ? zfp_.field_4d(data, zfp_type_float, static_cast<size_t>(dims[0]),
                                   static_cast<size_t>(dims[1]), static_cast<size_t>(dims[2]),
                                   static_cast<size_t>(steps))
                   : zfp_.field_3d(data, zfp_type_float, static_cast<size_t>(dims[0]),
                                   static_cast<size_t>(dims[1]), static_cast<size_t>(dims[2]))),
        stream_(zfp_.stream_open(nullptr)) {
    if (!field_ || !stream_) {
      release();
      throw Error("cannot set up the zfp coder");
    }
    if (!(std::isfinite(settings.parameter) && settings.parameter > 0.0)) {
      release();
      throw Error(std::string("the zfp ") +
                  (settings.mode == ZfpSettings::Mode::kRate ? "rate" : "tolerance") +
                  " must be a positive number");
    }
    if (settings.mode == ZfpSettings::Mode::kRate)
      zfp_.set_rate(stream_, settings.parameter, zfp_type_float, steps > 1 ? 4 : 3, zfp_false);
    else
      zfp_.set_accuracy(stream_, settings.parameter);
  }
  ~ZfpCodec() { release(); }
  ZfpCodec(const ZfpCodec&) = delete;
  ZfpCodec& operator=(const ZfpCodec&) = delete;

  // Bytes of the longest stream ZFP writes for the field in this mode. Its decoder, whatever the
  // bits, reads no more per block than this bound allows.
  size_t maximumBytes() const { return zfp_.maximum_size(stream_, field_); }

  // Runs ZFP over `words` (64-bit words: ZFP reads and writes whole words) of `bytes` bytes.
  size_t compress(void* words, size_t bytes) {
    attach(words, bytes);
    return zfp_.compress(stream_, field_);
  }
  size_t decompress(void* words, size_t bytes) {
    attach(words, bytes);
    return zfp_.decompress(stream_, field_);
  }

 private:
  void attach(void* words, size_t bytes) {
    if (bits_) zfp_.bitstream_close(bits_);
    bits_ = zfp_.bitstream_open(words, bytes);
    if (!bits_) throw Error("cannot set up the zfp coder");
    zfp_.set_bit_stream(stream_, bits_);
    zfp_.rewind(stream_);
  }
  void release() {
    if (bits_) zfp_.bitstream_close(bits_);
    if (stream_) zfp_.stream_close(stream_);
    if (field_) zfp_.field_free(field_);
    bits_ = nullptr;
    stream_ = nullptr;
    field_ = nullptr;
  }
  const ZfpLibrary& zfp_;
  zfp_field* field_ = nullptr;
  zfp_stream* stream_ = nullptr;
  bitstream* bits_ = nullptr;
};

size_t wordsFor(size_t bytes) {
  return (bytes + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);
}

void checkCount(size_t count, const Index3& dims, std::int64_t steps) {
  if (steps < 1 || static_cast<std::int64_t>(count) != dims[0] * dims[1] * dims[2] * steps)
    throw Error("the zfp array does not hold dims[0] x dims[1] x dims[2] x steps values");
}

}  // namespace

std::int64_t zfpMaxBytes(const Index3& dims, const ZfpSettings& settings, std::int64_t steps) {
  ZfpCodec codec(nullptr, dims, settings, steps);
  return static_cast<std::int64_t>(codec.maximumBytes());
}

namespace {

// A buffer for ZFP's longest stream, left uninitialized: a stream uses only its first bytes, and
// pages never written are never resident, so a large array does not cost a second copy of its
// size in memory.
struct StreamBuffer {
  explicit StreamBuffer(size_t bytes)
      : count(wordsFor(bytes) + kMargin),
        words(std::make_unique_for_overwrite<std::uint64_t[]>(count)) {}
  // ZFP reads a stream a 64-bit word ahead: after a stream of `used` bytes, the next words are
  // zeroed so that decoding it back reads nothing unset.
  void zeroAfter(size_t used) {
    const size_t from = wordsFor(used);
    std::memset(words.get() + from, 0,
                (std::min(count, from + kMargin) - from) * sizeof(std::uint64_t));
  }
  static constexpr size_t kMargin = 4;
  size_t count;
  std::unique_ptr<std::uint64_t[]> words;
};

}  // namespace

std::string zfpCompress(std::span<const float> values, const Index3& dims,
                        const ZfpSettings& settings, std::int64_t steps) {
  checkCount(values.size(), dims, steps);
  // ZFP takes a non-const pointer for both directions; compression only reads it.
  ZfpCodec codec(const_cast<float*>(values.data()), dims, settings, steps);
  StreamBuffer buffer(codec.maximumBytes());
  const size_t size = codec.compress(buffer.words.get(), buffer.count * sizeof(std::uint64_t));
  if (size == 0) throw Error("zfp could not compress the array");
  return std::string(reinterpret_cast<const char*>(buffer.words.get()), size);
}

ZfpRoundTrip zfpRoundTrip(std::span<const float> values, const Index3& dims,
                          const ZfpSettings& settings, std::int64_t steps) {
  checkCount(values.size(), dims, steps);
  ZfpCodec encoder(const_cast<float*>(values.data()), dims, settings, steps);
  StreamBuffer buffer(encoder.maximumBytes());
  const size_t size = encoder.compress(buffer.words.get(), buffer.count * sizeof(std::uint64_t));
  if (size == 0) throw Error("zfp could not compress the array");
  buffer.zeroAfter(size);
  ZfpRoundTrip out;
  out.stream.assign(reinterpret_cast<const char*>(buffer.words.get()), size);
  // Our own stream, decoded where it was written: no padded copy of the longest stream.
  out.decoded.resize(values.size());
  ZfpCodec decoder(out.decoded.data(), dims, settings, steps);
  if (decoder.decompress(buffer.words.get(), buffer.count * sizeof(std::uint64_t)) == 0)
    throw Error("zfp could not decode the stream it wrote");
  return out;
}

std::vector<float> zfpDecompress(std::span<const std::uint8_t> bytes, const Index3& dims,
                                 const ZfpSettings& settings, std::int64_t steps) {
  if (steps < 1) throw Error("the zfp array needs at least one step");
  std::vector<float> values(static_cast<size_t>(dims[0] * dims[1] * dims[2] * steps));
  ZfpCodec codec(values.data(), dims, settings, steps);
  const size_t maximum = codec.maximumBytes();
  if (bytes.size() > maximum) throw Error("the zfp stream is longer than its mode can produce");
  // ZFP's decoder does not know where the stream ends: decode from a zero-padded copy of the
  // largest size, so that damaged bits cannot make it read past the buffer.
  std::vector<std::uint64_t> words(wordsFor(maximum) + 1, 0);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  const size_t used = codec.decompress(words.data(), words.size() * sizeof(std::uint64_t));
  if (used == 0 || used > wordsFor(bytes.size()) * sizeof(std::uint64_t))
    throw Error(std::string("the zfp stream is corrupt (it ") +
                (used == 0 ? "does not decode" : "runs past its end") + ")");
  return values;
}

}  // namespace mfadvr
