#pragma once
// What the ray caster samples: a scalar field over a physical box, with its gradient.
//
// Every reconstruction method (the MFA model, the grid filters, the analytic ground truth) is a
// Field, so that renderVolume (RayCaster.h) renders them all through the same per-ray
// integration, with the same rays, samples, transfer functions, shading and compositing, and a
// comparison measures only the reconstruction. Dispatch is static: the ray loop is instantiated
// for each field's sampler and inlines it (the MFA model through its own SplineRaySampler).
//
// A Field is cheap to copy-reference and immutable; each render thread asks it for a Sampler,
// which may keep per-thread state (e.g. the last cell's coefficients).
#include <concepts>

#include "core/spline/TensorBSpline.h"  // ValueGradient
#include "core/util/Vec.h"

namespace mfadvr {

template <class S>
concept FieldSampler = requires(S s, const Vec3d& x) {
  { s.value(x) } -> std::convertible_to<float>;
  { s.valueGradient(x) } -> std::same_as<ValueGradient>;
};

template <class F>
concept Field = requires(const F f) {
  { f.boxMin() } -> std::convertible_to<Vec3d>;
  { f.boxMax() } -> std::convertible_to<Vec3d>;
  { f.sampler() } -> FieldSampler;
};

}  // namespace mfadvr
