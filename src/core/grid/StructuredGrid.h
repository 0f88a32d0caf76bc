#pragma once
// Samples of a scalar field on a regular grid: the input of the structured encoder.
#include <cstdint>
#include <string>
#include <vector>

#include "core/util/Vec.h"

namespace mfadvr {

struct StructuredGrid {
  Index3 dims{0, 0, 0};           // samples per axis
  Vec3d origin = Vec3d::Zero();   // physical position of sample (0,0,0)
  Vec3d spacing = Vec3d::Ones();  // physical distance between neighbouring samples
  // x fastest: values[i + nx * (j + ny * k)]. Held as float32, the precision of the model:
  // exact for integer samples up to 2^24 and for float32 data; float64 data is rounded.
  std::vector<float> values;

  std::string source;            // where the samples came from (path or builtin spec)
  std::string fieldName;         // scalar array name, when the format has one
  std::string fieldAssociation;  // where the file held the samples: "point data", "cell data"
  std::string sampleType;        // storage type of the source: uint8, int16, float32, ...
  std::int64_t inputBytes = 0;   // bytes of the samples in their source type
  // What the reader applied or could not represent (orientation, calibration); the command
  // line prints them as warnings.
  std::vector<std::string> notes;

  std::int64_t sampleCount() const { return dims[0] * dims[1] * dims[2]; }
  float& at(std::int64_t i, std::int64_t j, std::int64_t k) {
    return values[static_cast<size_t>(i + dims[0] * (j + dims[1] * k))];
  }
  double at(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return values[static_cast<size_t>(i + dims[0] * (j + dims[1] * k))];
  }
  Vec3d position(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return origin + Vec3d(spacing[0] * i, spacing[1] * j, spacing[2] * k);
  }
  // Physical bounding box of the samples.
  Vec3d boxMin() const { return origin; }
  Vec3d boxMax() const {
    return origin + Vec3d(spacing[0] * (dims[0] - 1), spacing[1] * (dims[1] - 1),
                          spacing[2] * (dims[2] - 1));
  }

  // Throws mfadvr::Error unless dims >= 1, spacing > 0 and finite, values sized to dims and
  // every value finite (the error names the first bad sample).
  void validate() const;
  // The same for the layout alone (dims, spacing, origin), for a grid whose samples are held
  // elsewhere (GridSamples).
  void validateLayout() const;
};

// The error for sample n (x fastest) of `grid` being `value`, NaN or Inf: names the sample by
// its indices and says why such values cannot be encoded.
std::string nonFiniteSampleMessage(const StructuredGrid& grid, std::int64_t n, float value);

}  // namespace mfadvr
