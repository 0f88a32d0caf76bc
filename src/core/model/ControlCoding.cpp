#include "core/model/ControlCoding.h"

#include <zfp.h>
#include <zstd.h>

#include <cmath>
#include <cstring>

#include "core/model/Model.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// zstd level: 9 is about 3x slower than the default 3 and 2-4% smaller on control grids; coding
// is a small part of an encode.
constexpr int kZstdLevel = 9;

std::int64_t countOf(const Index3& dims) {
  return dims[0] * dims[1] * dims[2];
}

void checkTolerance(const ControlCoding& c) {
  if (c.coder == ControlCoder::kZfp && !(std::isfinite(c.tolerance) && c.tolerance > 0.0))
    throw Error("the zfp coding tolerance must be a positive number");
}

// RAII for ZFP's C objects: a stream set to fixed accuracy over a 3-D float field.
class ZfpCodec {
 public:
  ZfpCodec(float* data, const Index3& dims, double tolerance)
      : field_(zfp_field_3d(data, zfp_type_float, static_cast<size_t>(dims[0]),
                            static_cast<size_t>(dims[1]), static_cast<size_t>(dims[2]))),
        stream_(zfp_stream_open(nullptr)) {
    if (!field_ || !stream_) {
      release();
      throw Error("cannot set up the zfp coder");
    }
    zfp_stream_set_accuracy(stream_, tolerance);
  }
  ~ZfpCodec() { release(); }
  ZfpCodec(const ZfpCodec&) = delete;
  ZfpCodec& operator=(const ZfpCodec&) = delete;

  // Bytes of the largest stream ZFP writes for the field in this mode (its own bound: every
  // block, whatever its bits, is decoded from at most this many bits per block).
  size_t maximumBytes() const { return zfp_stream_maximum_size(stream_, field_); }

  // Runs ZFP over `words` (64-bit words: ZFP reads and writes whole words) of `bytes` bytes.
  size_t compress(void* words, size_t bytes) {
    attach(words, bytes);
    return zfp_compress(stream_, field_);
  }
  size_t decompress(void* words, size_t bytes) {
    attach(words, bytes);
    return zfp_decompress(stream_, field_);
  }

 private:
  void attach(void* words, size_t bytes) {
    if (bits_) stream_close(bits_);
    bits_ = stream_open(words, bytes);
    if (!bits_) throw Error("cannot set up the zfp coder");
    zfp_stream_set_bit_stream(stream_, bits_);
    zfp_stream_rewind(stream_);
  }
  void release() {
    if (bits_) stream_close(bits_);
    if (stream_) zfp_stream_close(stream_);
    if (field_) zfp_field_free(field_);
    bits_ = nullptr;
    stream_ = nullptr;
    field_ = nullptr;
  }
  zfp_field* field_ = nullptr;
  zfp_stream* stream_ = nullptr;
  bitstream* bits_ = nullptr;
};

size_t wordsFor(size_t bytes) {
  return (bytes + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);
}

std::string shuffledZstd(std::span<const float> ctrl) {
  const size_t n = ctrl.size();
  const auto* raw = reinterpret_cast<const std::uint8_t*>(ctrl.data());
  std::string planes(4 * n, '\0');
  for (size_t i = 0; i < n; ++i)
    for (size_t b = 0; b < 4; ++b) planes[b * n + i] = static_cast<char>(raw[4 * i + b]);
  std::string out(ZSTD_compressBound(planes.size()), '\0');
  const size_t size =
      ZSTD_compress(out.data(), out.size(), planes.data(), planes.size(), kZstdLevel);
  if (ZSTD_isError(size))
    throw Error(std::string("cannot compress the control points: ") + ZSTD_getErrorName(size));
  out.resize(size);
  return out;
}

std::vector<float> unshuffledZstd(std::span<const std::uint8_t> bytes, std::int64_t count) {
  const size_t n = static_cast<size_t>(count);
  std::vector<std::uint8_t> planes(4 * n);
  const size_t size = ZSTD_decompress(planes.data(), planes.size(), bytes.data(), bytes.size());
  if (ZSTD_isError(size) || size != planes.size())
    throw Error("the coded control points are corrupt (" +
                (ZSTD_isError(size) ? std::string(ZSTD_getErrorName(size))
                                    : "they hold " + std::to_string(size) + " bytes, not " +
                                          std::to_string(planes.size())) +
                ")");
  std::vector<float> ctrl(n);
  auto* raw = reinterpret_cast<std::uint8_t*>(ctrl.data());
  for (size_t i = 0; i < n; ++i)
    for (size_t b = 0; b < 4; ++b) raw[4 * i + b] = planes[b * n + i];
  return ctrl;
}

}  // namespace

const char* controlCoderName(ControlCoder c) {
  switch (c) {
    case ControlCoder::kFloat32: return "float32";
    case ControlCoder::kLossless: return "lossless";
    case ControlCoder::kZfp: return "zfp";
  }
  return "float32";
}

ControlCoder parseControlCoder(const std::string& name) {
  for (ControlCoder c : {ControlCoder::kFloat32, ControlCoder::kLossless, ControlCoder::kZfp})
    if (name == controlCoderName(c)) return c;
  throw Error("unknown control-point coding '" + name + "' (float32, lossless or zfp)");
}

std::int64_t maxCodedControlBytes(const Index3& dims, const ControlCoding& coding) {
  const std::int64_t count = countOf(dims);
  switch (coding.coder) {
    case ControlCoder::kFloat32: return 4 * count;
    case ControlCoder::kLossless:
      return static_cast<std::int64_t>(ZSTD_compressBound(static_cast<size_t>(4 * count)));
    case ControlCoder::kZfp: {
      checkTolerance(coding);
      ZfpCodec codec(nullptr, dims, coding.tolerance);
      return static_cast<std::int64_t>(codec.maximumBytes());
    }
  }
  return 0;
}

std::string encodeControlPoints(std::span<const float> ctrl, const Index3& dims,
                                const ControlCoding& coding) {
  if (static_cast<std::int64_t>(ctrl.size()) != countOf(dims))
    throw Error("control point count does not match the control grid");
  switch (coding.coder) {
    case ControlCoder::kFloat32:
      return std::string(reinterpret_cast<const char*>(ctrl.data()), ctrl.size() * sizeof(float));
    case ControlCoder::kLossless: return shuffledZstd(ctrl);
    case ControlCoder::kZfp: {
      checkTolerance(coding);
      // ZFP takes a non-const pointer for both directions; compression only reads it.
      ZfpCodec codec(const_cast<float*>(ctrl.data()), dims, coding.tolerance);
      const size_t capacity = codec.maximumBytes();
      std::vector<std::uint64_t> words(wordsFor(capacity));
      const size_t size = codec.compress(words.data(), words.size() * sizeof(std::uint64_t));
      if (size == 0) throw Error("zfp could not code the control points");
      return std::string(reinterpret_cast<const char*>(words.data()), size);
    }
  }
  return {};
}

std::vector<float> decodeControlPoints(std::span<const std::uint8_t> bytes, const Index3& dims,
                                       const ControlCoding& coding) {
  const std::int64_t count = countOf(dims);
  if (static_cast<std::int64_t>(bytes.size()) > maxCodedControlBytes(dims, coding))
    throw Error("the coded control points are longer than their coding can produce");
  switch (coding.coder) {
    case ControlCoder::kFloat32: {
      if (static_cast<std::int64_t>(bytes.size()) != 4 * count)
        throw Error("the control points hold " + std::to_string(bytes.size()) + " bytes, not " +
                    std::to_string(4 * count));
      std::vector<float> ctrl(static_cast<size_t>(count));
      std::memcpy(ctrl.data(), bytes.data(), bytes.size());
      return ctrl;
    }
    case ControlCoder::kLossless: return unshuffledZstd(bytes, count);
    case ControlCoder::kZfp: {
      std::vector<float> ctrl(static_cast<size_t>(count));
      ZfpCodec codec(ctrl.data(), dims, coding.tolerance);
      // ZFP's decoder does not know where the payload ends; from any bits it reads at most the
      // largest stream of the mode, so a zero-padded buffer of that size keeps a damaged
      // payload from reading past the end.
      std::vector<std::uint64_t> words(wordsFor(codec.maximumBytes()) + 1, 0);
      std::memcpy(words.data(), bytes.data(), bytes.size());
      const size_t used = codec.decompress(words.data(), words.size() * sizeof(std::uint64_t));
      if (used == 0 || used > wordsFor(bytes.size()) * sizeof(std::uint64_t))
        throw Error("the coded control points are corrupt (the zfp stream " +
                    std::string(used == 0 ? "does not decode" : "runs past its section") + ")");
      return ctrl;
    }
  }
  return {};
}

Model codeControlPoints(const Model& model, const ControlCoding& coding) {
  const TensorBSpline& s = model.spline();
  const Index3 dims = s.counts();
  auto payload =
      std::make_shared<const std::string>(encodeControlPoints(s.controlPoints(), dims, coding));
  std::vector<float> decoded = decodeControlPoints(
      std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(payload->data()),
                                    payload->size()),
      dims, coding);
  Model coded(TensorBSpline({s.knots(0), s.knots(1), s.knots(2)}, std::move(decoded)),
              model.domain(), model.valueMin(), model.valueMax(), model.provenance());
  coded.setMask(model.mask());
  coded.setControlCoding(coding, std::move(payload));
  return coded;
}

}  // namespace mfadvr
