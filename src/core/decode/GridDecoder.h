#pragma once
// The way back out of a model: its values on a regular grid, slab by slab (`mfadvr decode`, and
// for programs that need samples rather than a model).
#include <cstdint>
#include <functional>
#include <span>

#include "core/model/Model.h"

namespace mfadvr {

struct DecodeGrid {
  Index3 dims{0, 0, 0};
  Vec3d origin = Vec3d::Zero();   // first sample: the model box's minimum corner
  Vec3d spacing = Vec3d::Ones();  // the box divided into dims - 1 intervals
};

// The grid the model stands for: the input's sample grid when the model records one, else the
// model's data spacing over its box.
DecodeGrid defaultDecodeGrid(const Model& model);
// `dims` samples over the model's box (at least 2 per axis; throws mfadvr::Error otherwise).
DecodeGrid decodeGridWithSamples(const Model& model, const Index3& dims);

// Evaluates the model at every sample of `grid`, z slab by z slab of at most about slabSamples
// samples, and hands each slab (its z range and its values, x fastest) to `sink` in order.
// Samples outside the model's domain mask are NaN. Memory: a slab and the control planes it
// depends on; every slab is evaluated over all cores.
void decodeBySlabs(const Model& model, const DecodeGrid& grid, std::int64_t slabSamples,
                   const std::function<void(std::int64_t zBegin, std::int64_t zEnd,
                                            std::span<const double> values)>& sink);

}  // namespace mfadvr
