#pragma once
// Where a frame's time goes in empty space, measured in CPU cycles (the time-stamp counter) by a
// profiling build (CMake option MFADVR_PROFILE_EMPTY_SPACE, preset `profile`; off by default:
// the counters cost cycles of their own). Per ray that takes one sample at a time (renders with
// skipping or a mask): all of its integration; the marching between evaluations (the steps,
// the empty-space checks of every sample and the jumps over empty blocks; with skipping on,
// mostly time in empty space); and the evaluation of samples that the transfer function makes
// transparent (their share of each batch's evaluation). Read once per batch of samples, not per
// sample. `mfadvr render` prints the shares. Host only: the GPU kernels never count.
#include <cstdint>

#if defined(MFADVR_PROFILE_EMPTY_SPACE) && !defined(__CUDA_ARCH__)
#include <x86intrin.h>

#include <atomic>
#define MFADVR_EMPTY_SPACE_PROFILE 1
#else
#define MFADVR_EMPTY_SPACE_PROFILE 0
#endif

namespace mfadvr {

struct EmptySpaceCycles {
  std::int64_t ray = 0;          // the whole integration of rays that crossed the box
  std::int64_t marching = 0;     // steps, empty-space checks and jumps between evaluations
  std::int64_t ahead = 0;        // the part of `marching` in the march ahead (InterleavedMarch.h)
  std::int64_t transparent = 0;  // evaluating samples whose opacity is 0
  std::int64_t jumps = 0;        // empty-space checks that found the sample's cell empty
  std::int64_t checks = 0;       // empty-space checks in all

  EmptySpaceCycles& operator+=(const EmptySpaceCycles& o) {
    ray += o.ray;
    marching += o.marching;
    ahead += o.ahead;
    transparent += o.transparent;
    jumps += o.jumps;
    checks += o.checks;
    return *this;
  }
};

#if MFADVR_EMPTY_SPACE_PROFILE
inline std::int64_t cycleCount() {
  return static_cast<std::int64_t>(__rdtsc());
}

// The sum over every frame since the last take (all threads).
struct EmptySpaceProfile {
  static inline std::atomic<std::int64_t> ray{0}, marching{0}, ahead{0}, transparent{0}, jumps{0},
      checks{0};
  static void add(const EmptySpaceCycles& c) {
    ray += c.ray;
    marching += c.marching;
    ahead += c.ahead;
    transparent += c.transparent;
    jumps += c.jumps;
    checks += c.checks;
  }
  static EmptySpaceCycles take() {
    return {ray.exchange(0),         marching.exchange(0), ahead.exchange(0),
            transparent.exchange(0), jumps.exchange(0),    checks.exchange(0)};
  }
};
#endif

}  // namespace mfadvr
