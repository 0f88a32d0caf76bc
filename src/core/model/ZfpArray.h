#pragma once
// ZFP (Debian libzfp, zfp 1.0) on a 3-D float array, x fastest (or a 4-D one: `steps` > 1 such
// arrays, one after the other, coded as one 4-D field, for time-varying models): the coder of the
// control points (ControlCoding.h) and, on the samples themselves, the baseline of the compression
// study
// (`mfadvr eval compression`). Streams carry no ZFP header: the caller stores dims and mode.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/util/Vec.h"

namespace mfadvr {

struct ZfpSettings {
  enum class Mode { kAccuracy, kRate };
  Mode mode = Mode::kAccuracy;
  // kAccuracy: the absolute error tolerance (> 0); kRate: bits per value (> 0, random access).
  double parameter = 0.0;
};

// Throws mfadvr::Error for a parameter that is not finite and positive.
std::string zfpCompress(std::span<const float> values, const Index3& dims,
                        const ZfpSettings& settings, std::int64_t steps = 1);
// zfpCompress and the stream decoded again, as zfpDecompress would decode it, without its padded
// copy of the longest stream (the stream is trusted: it was just written).
struct ZfpRoundTrip {
  std::string stream;
  std::vector<float> decoded;
};
ZfpRoundTrip zfpRoundTrip(std::span<const float> values, const Index3& dims,
                          const ZfpSettings& settings, std::int64_t steps = 1);
// The longest stream ZFP can write for `dims` values in this mode.
std::int64_t zfpMaxBytes(const Index3& dims, const ZfpSettings& settings, std::int64_t steps = 1);
// Decodes a stream of zfpCompress. Any bytes decode without reading outside `bytes` (a damaged
// stream is decoded from a zero-padded copy of ZFP's maximum size); a stream that ZFP rejects,
// runs past its bytes or is longer than the maximum throws mfadvr::Error.
std::vector<float> zfpDecompress(std::span<const std::uint8_t> bytes, const Index3& dims,
                                 const ZfpSettings& settings, std::int64_t steps = 1);

}  // namespace mfadvr
