#include "core/model/ControlCoding.h"

#include <zstd.h>

#include <cmath>
#include <cstring>

#include "core/model/Model.h"
#include "core/model/ZfpArray.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// zstd level: 9 is about 3x slower than the default 3 and 2-4% smaller on control grids; coding
// is a small part of an encode.
constexpr int kZstdLevel = 9;

std::int64_t countOf(const Index3& dims) {
  return dims[0] * dims[1] * dims[2];
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
    case ControlCoder::kFloat32:
      return "float32";
    case ControlCoder::kLossless:
      return "lossless";
    case ControlCoder::kZfp:
      return "zfp";
  }
  return "float32";
}

ControlCoder parseControlCoder(const std::string& name) {
  for (ControlCoder c : {ControlCoder::kFloat32, ControlCoder::kLossless, ControlCoder::kZfp})
    if (name == controlCoderName(c)) return c;
  throw Error("unknown control-point coding '" + name + "' (float32, lossless or zfp)");
}

std::int64_t maxCodedControlBytes(const Index3& dims, const ControlCoding& coding,
                                  std::int64_t steps) {
  const std::int64_t count = countOf(dims) * steps;
  switch (coding.coder) {
    case ControlCoder::kFloat32:
      return 4 * count;
    case ControlCoder::kLossless:
      return static_cast<std::int64_t>(ZSTD_compressBound(static_cast<size_t>(4 * count)));
    case ControlCoder::kZfp:
      return zfpMaxBytes(dims, {ZfpSettings::Mode::kAccuracy, coding.tolerance}, steps);
  }
  return 0;
}

std::string encodeControlPoints(std::span<const float> ctrl, const Index3& dims,
                                const ControlCoding& coding, std::int64_t steps) {
  if (steps < 1 || static_cast<std::int64_t>(ctrl.size()) != countOf(dims) * steps)
    throw Error("control point count does not match the control grid");
  switch (coding.coder) {
    case ControlCoder::kFloat32:
      return std::string(reinterpret_cast<const char*>(ctrl.data()), ctrl.size() * sizeof(float));
    case ControlCoder::kLossless:
      return shuffledZstd(ctrl);
    case ControlCoder::kZfp:
      return zfpCompress(ctrl, dims, {ZfpSettings::Mode::kAccuracy, coding.tolerance}, steps);
  }
  return {};
}

std::vector<float> decodeControlPoints(std::span<const std::uint8_t> bytes, const Index3& dims,
                                       const ControlCoding& coding, std::int64_t steps) {
  const std::int64_t count = countOf(dims) * steps;
  if (steps < 1 ||
      static_cast<std::int64_t>(bytes.size()) > maxCodedControlBytes(dims, coding, steps))
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
    case ControlCoder::kLossless:
      return unshuffledZstd(bytes, count);
    case ControlCoder::kZfp:
      return zfpDecompress(bytes, dims, {ZfpSettings::Mode::kAccuracy, coding.tolerance}, steps);
  }
  return {};
}

Model codeControlPoints(const Model& model, const ControlCoding& coding) {
  const TensorBSpline& s = model.spline();
  const Index3 dims = s.counts();
  std::shared_ptr<const std::string> payload;
  std::vector<float> decoded;
  if (coding.coder == ControlCoder::kZfp) {
    // One round trip: the stream is decoded from the buffer it was written to.
    ZfpRoundTrip z =
        zfpRoundTrip(s.controlPoints(), dims, {ZfpSettings::Mode::kAccuracy, coding.tolerance});
    payload = std::make_shared<const std::string>(std::move(z.stream));
    decoded = std::move(z.decoded);
  } else {
    payload =
        std::make_shared<const std::string>(encodeControlPoints(s.controlPoints(), dims, coding));
    decoded = decodeControlPoints(
        std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(payload->data()),
                                      payload->size()),
        dims, coding);
  }
  Model coded(TensorBSpline({s.knots(0), s.knots(1), s.knots(2)}, std::move(decoded)),
              model.domain(), model.valueMin(), model.valueMax(), model.provenance());
  coded.setMask(model.mask());
  coded.setControlCoding(coding, std::move(payload));
  return coded;
}

}  // namespace mfadvr
