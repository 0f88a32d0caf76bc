#pragma once
// The way in through empty space, for several rays at once (host).
//
// With empty-space skipping, a ray of a sparse scene spends most of its time before its first
// visible cell: each jump over empty blocks (the sampler's emptyAlong: locate the sample, read
// the cell's flag, walk on through the empty blocks ahead) waits for the one before, and its flag
// reads miss the caches. One ray at a time, the processor has nothing
// else to do meanwhile. marchIn() walks G neighbouring rays' jumps in turn, one jump of each
// per round, so that the jumps of different rays overlap; each ray stops at its first sample
// that is not in an empty cell (or at its end), and integrateSegment (RayIntegrator.h) goes on
// from there. The jumps are the integration's own (stepSample, emptyAlong, stepAfterEmpty), so
// every ray skips, samples and counts exactly what it would alone.
#include "core/render/kernel/RayIntegrator.h"

namespace mfadvr {

// Rays marched together per group.
inline constexpr int kMarchGroup = 4;

// Samplers that can march rays apart from their own state (SplineRaySampler with skipping).
template <class Sampler>
constexpr bool marchesRaysApart() {
  return Sampler::kSkipsEmptySpace && requires {
    typename Sampler::RayMarch;
  };
}

// For each of the G rays (null: misses the box), where its integration starts: its first step
// from start[g] on (in: where its march begins, every step before it empty; RayStart{}: the
// whole ray) whose sample is not in an empty cell, and the samples skipped before it. counters:
// only the profiling build's (its time counts as the rays', as marching and as marching ahead,
// its checks and jumps as such).
// Masked: samples outside the sampler's domain mask are passed over uncounted, as
// integrateSegment does; the mask, not a mesh's boundary, which the sampler follows for one ray
// at a time (insideFollowsTheRay(): the caller does not march such rays here).
template <int G, bool Masked, class Sampler>
MFADVR_INLINE void marchIn(const RayParams& rp, Sampler& sampler, const RaySegment* const rays[G],
                           RayStart start[G], [[maybe_unused]] RayCounters& counters) {
#if MFADVR_EMPTY_SPACE_PROFILE
  const std::int64_t marchStart = cycleCount();
#endif
  const double dt = rp.sampleDistance;
  typename Sampler::RayMarch march[G];
  bool going[G];
  int active = 0;
  for (int g = 0; g < G; ++g) {
    going[g] = rays[g] && start[g].k < rays[g]->steps;
    if (going[g]) {
      sampler.beginMarch(rays[g]->o, rays[g]->d, march[g]);
      ++active;
    }
  }
  while (active > 0) {
    for (int g = 0; g < G; ++g) {
      if (!going[g]) continue;
      const RaySegment& ray = *rays[g];
      RayStart& s = start[g];
      double length, p[3], tLeave;
      typename Sampler::PointLocation loc;
      bool stop = !stepSample(ray, s.k, dt, p, length);  // no step k: the integration ends there
      if (Masked && !stop && !sampler.inside(p)) {
        ++s.k;
      } else if (!stop && sampler.emptyAlong(march[g], p, tLeave, loc)) {
        const std::int64_t next = stepAfterEmpty(s.k + 1, tLeave, ray.t0, dt, ray.steps);
        s.skipped += next - s.k;
        s.k = next;
#if MFADVR_EMPTY_SPACE_PROFILE
        ++counters.cycles.jumps;
        ++counters.cycles.checks;
#endif
      } else {
#if MFADVR_EMPTY_SPACE_PROFILE
        if (!stop) ++counters.cycles.checks;  // a cell that is not empty
#endif
        stop = true;  // the integration takes this step
      }
      if (stop || s.k >= ray.steps) {
        going[g] = false;
        --active;
      }
    }
  }
#if MFADVR_EMPTY_SPACE_PROFILE
  const std::int64_t cycles = cycleCount() - marchStart;
  counters.cycles.marching += cycles;
  counters.cycles.ahead += cycles;
  counters.cycles.ray += cycles;
#endif
}

}  // namespace mfadvr
