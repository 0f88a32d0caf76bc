#pragma once
// A read-only view of a grid's samples where they already are, in their own type (x fastest):
// a VTK pipeline's uint8 array, or a StructuredGrid's floats. The structured fit reads its input
// one z plane at a time through it, so that an input held elsewhere is fitted without a float32
// copy of the whole grid (4 bytes per sample). Each value reaches the fit as float32, as the
// copy would have held it, so the two ways give the same model.
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/grid/StructuredGrid.h"
#include "core/util/Vec.h"

namespace mfadvr {

class GridSamples {
 public:
  GridSamples() = default;
  // The grid's own values (which must outlive the view and not be resized).
  explicit GridSamples(const StructuredGrid& grid);
  // `data` holds dims[0] * dims[1] * dims[2] values of an arithmetic type; it must outlive the
  // view.
  template <typename T>
  static GridSamples of(const T* data, const Index3& dims) {
    static_assert(std::is_arithmetic_v<T>, "samples are numbers");
    GridSamples s;
    s.data_ = data;
    s.dims_ = dims;
    s.integral_ = std::is_integral_v<T>;
    s.floats_ = std::is_same_v<T, float> ? static_cast<const float*>(static_cast<const void*>(data))
                                         : nullptr;
    s.convert_ = [](const void* from, std::int64_t first, std::int64_t count, float* out) {
      const T* v = static_cast<const T*>(from) + first;
      for (std::int64_t i = 0; i < count; ++i) out[i] = static_cast<float>(v[i]);
    };
    return s;
  }

  const Index3& dims() const { return dims_; }
  std::int64_t sampleCount() const { return dims_[0] * dims_[1] * dims_[2]; }
  bool empty() const { return data_ == nullptr; }

  // The `count` samples from index `first` (x fastest) as float32: the data itself when it is
  // float32, else converted into `scratch` (resized as needed).
  const float* values(std::int64_t first, std::int64_t count, std::vector<float>& scratch) const;
  // z plane k.
  const float* plane(std::int64_t k, std::vector<float>& scratch) const {
    return values(k * dims_[0] * dims_[1], dims_[0] * dims_[1], scratch);
  }
  // All samples as float32 (for the fits that need the whole grid in memory).
  std::vector<float> toFloats() const;

  // Throws mfadvr::Error, as StructuredGrid::validate does, when the view is not of `layout`'s
  // dims or a sample is NaN or infinite as float32 (naming it by `layout`'s source and indices).
  // One pass over floating-point samples; integer samples are always finite and are not read.
  void validateFor(const StructuredGrid& layout) const;
  // Smallest and largest sample as float32 (0, 0 for an empty view).
  std::pair<float, float> range() const;

 private:
  using Convert = void (*)(const void* data, std::int64_t first, std::int64_t count, float* out);
  const void* data_ = nullptr;
  const float* floats_ = nullptr;  // data_ when the samples are float32
  Convert convert_ = nullptr;
  bool integral_ = false;
  Index3 dims_{0, 0, 0};
};

}  // namespace mfadvr
