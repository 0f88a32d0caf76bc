#pragma once
// The .mfa model file (format version 3; version 4 for time-varying models;
// docs/model-format.md describes every byte).
//
//   magic "MFADVR\r\n\x1a\n" (10 bytes) | u32 version | u32 header length H | H bytes JSON header
//   | knots: float64 per axis, x then y then z | control points, x fastest, coded as the header's
//   "control_points" says (ControlCoding.h; versions 1 and 2: float32, no such entry)
//   | [mask nodes: bit-packed, x fastest, least significant bit first; when the header has "mask"]
//   | u32 CRC-32
//
// All integers and floats little-endian; the CRC-32 (zlib) covers every byte before it. Loading
// checks everything before trusting it, so that any damaged file gives an Error, never a crash.
// Writing produces version 3 for 3-D models and version 4 (a "time" header key, the time knots
// after the spatial ones, nt slabs of control points) for time-varying ones; reading accepts
// version 1 (no mask section), 2 (float32 control points only), 3 and 4.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "core/model/ControlCoding.h"
#include "core/model/Model.h"
#include "core/model/TimeVaryingModel.h"

namespace mfadvr {

inline constexpr std::uint32_t kModelFormatVersion = 3;        // written for 3-D models
inline constexpr std::uint32_t kTimeModelFormatVersion = 4;    // written with a time axis
inline constexpr std::uint32_t kOldestModelFormatVersion = 1;  // oldest read

std::string serializeModel(const Model& model);
// The same bytes written to `allocate(size)` (called once), e.g. an array of a pipeline, with no
// copy in between: a large model's file is not held twice.
void serializeModel(const Model& model, const std::function<std::uint8_t*(size_t)>& allocate);
// `name` appears in error messages (usually the path). formatVersion (optional) receives the
// version the bytes were written in. owner (optional): what keeps `bytes` alive and unchanged;
// given it, float32 control points are used where they lie in `bytes` (when aligned: files of
// this build pad their header for it), and the model holds the owner instead of a copy.
Model parseModel(std::span<const std::uint8_t> bytes, const std::string& name = "model",
                 std::uint32_t* formatVersion = nullptr,
                 std::shared_ptr<const void> owner = nullptr);

// Writes atomically: a temporary file beside the target, flushed, then renamed over it.
void saveModel(const Model& model, const std::filesystem::path& path);
// Of a time-varying file, the model at its first step (3-D consumers: compare, the VTK mapper's
// carried model); loadTimeVaryingModel gives every instant.
Model loadModel(const std::filesystem::path& path, std::uint32_t* formatVersion = nullptr);

// Models that may have a time axis: 3-D ones are written and read exactly as above.
std::string serializeModel(const TimeVaryingModel& model);
void saveModel(const TimeVaryingModel& model, const std::filesystem::path& path);
TimeVaryingModel parseTimeVaryingModel(std::span<const std::uint8_t> bytes,
                                       const std::string& name = "model",
                                       std::uint32_t* formatVersion = nullptr,
                                       std::shared_ptr<const void> owner = nullptr);
TimeVaryingModel loadTimeVaryingModel(const std::filesystem::path& path,
                                      std::uint32_t* formatVersion = nullptr);
std::int64_t modelFileSize(const TimeVaryingModel& model);

// What a model file's header says about the model's size, read without its control points: for
// memory estimates before a model (or each block of a multi-block file) is loaded.
struct ModelFileSummary {
  Degree3 degree{};
  Index3 controlCounts{};  // spatial
  std::int64_t slabs = 1;  // time control points (1: no time axis)
  ControlCoder coder = ControlCoder::kFloat32;
  std::uint64_t fileBytes = 0;
  // Loading keeps the file's bytes as the model's float32 control points (aligned in the file):
  // no second copy while it is read.
  bool readInPlace = false;
};
// What the model holds once loaded: its control points as float32 and, for a lossy coding, the
// coded bytes it keeps for writing the model again.
std::int64_t loadedModelBytes(const ModelFileSummary& model);
// `head`: the first bytes of a model of `fileBytes` bytes, at least its prefix and header (or the
// whole model). Checks what it reads (magic, version, header length, degrees, control counts) as
// parseModel does; throws mfadvr::Error naming `name`.
ModelFileSummary summarizeModelHead(std::span<const std::uint8_t> head, std::uint64_t fileBytes,
                                    const std::string& name);
// The model whose bytes lie at [offset, offset + bytes) of `path` (a whole .mfa file: 0 and its
// size); reads only the prefix and the header.
ModelFileSummary summarizeModelFile(const std::filesystem::path& path, std::uint64_t offset,
                                    std::uint64_t bytes);
// A whole .mfa file.
ModelFileSummary summarizeModelFile(const std::filesystem::path& path);

std::int64_t modelFileSize(const Model& model);
// Bytes of the model's control-point section: its kept coding, 4 per point when uncoded, else
// coded now to count them.
std::int64_t codedControlBytes(const Model& model);

}  // namespace mfadvr
