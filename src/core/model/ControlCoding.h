#pragma once
// How the control points of a model are stored in its .mfa file (format version 3).
//
//   float32   4 bytes per control point, as in memory (versions 1 and 2 store only this)
//   lossless  the float32 bytes shuffled into four byte planes (sign/exponent bytes together,
//             which compress well), then zstd: decodes bit for bit
//   zfp       ZFP's fixed-accuracy mode over the 3-D control grid (it is a smooth array, which is
//             what ZFP's block transform is made for): every decoded control point lies within
//             `tolerance` of the fitted one. The model is a convex combination of control points
//             (B-splines are a partition of unity), so the model moves by at most `tolerance`
//             anywhere.
//
// Loading decodes once into the in-memory float32 model: queries and renderers never see the
// coding. A model whose control points were coded lossily holds the decoded values, and the
// errors it states are measured on them (codeControlPoints).
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/util/Vec.h"

namespace mfadvr {

class Model;

enum class ControlCoder { kFloat32, kLossless, kZfp };

struct ControlCoding {
  ControlCoder coder = ControlCoder::kFloat32;
  double tolerance = 0.0;  // zfp: the largest change of a control point (absolute, > 0)
};

// "float32", "lossless", "zfp": the names of the file header and of `encode --coding`.
const char* controlCoderName(ControlCoder c);
// Throws mfadvr::Error listing the names for anything else.
ControlCoder parseControlCoder(const std::string& name);

// Codes `ctrl` (dims[0] x dims[1] x dims[2], x fastest; `steps` such grids one after the other
// for a time-varying model, zfp coding them as one 4-D array). Throws mfadvr::Error for a zfp
// tolerance that is not finite and positive.
std::string encodeControlPoints(std::span<const float> ctrl, const Index3& dims,
                                const ControlCoding& coding, std::int64_t steps = 1);

// The largest payload a coding can produce for `dims` control points: a reader refuses larger
// sections before allocating anything.
std::int64_t maxCodedControlBytes(const Index3& dims, const ControlCoding& coding,
                                  std::int64_t steps = 1);

// Decodes a payload written by encodeControlPoints. Damaged payloads throw mfadvr::Error (never
// read outside `bytes`); the values may still be non-finite, which the model reader checks.
std::vector<float> decodeControlPoints(std::span<const std::uint8_t> bytes, const Index3& dims,
                                       const ControlCoding& coding, std::int64_t steps = 1);

// `model` with its control points coded: the coded bytes are kept with the model (the file
// writer stores them as they are) and the control points replaced by their decoded values, so
// that the model in memory is the model a reader loads. Errors stated in the provenance are not
// changed: the encoder measures them again on the result.
Model codeControlPoints(const Model& model, const ControlCoding& coding);

}  // namespace mfadvr
