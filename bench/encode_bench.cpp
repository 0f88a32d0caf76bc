// Structured encode time: Marschner-Lobb 128^3 -> 64^3 control points at degree 3, and
// 256^3 -> 256^3 at degree 2 (sampling the function is outside the timed region).
//
//   build/release/bench/mfadvr_bench --benchmark_filter=Encode --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"

namespace mfadvr {
namespace {

void encode(benchmark::State& state) {
  const std::int64_t samples = state.range(0), ctrl = state.range(1);
  const int degree = static_cast<int>(state.range(2));
  const StructuredGrid g =
      sampleBuiltin(*makeBuiltin("marschner-lobb"), {samples, samples, samples});
  StructuredFitOptions o;
  o.degree = {degree, degree, degree};
  o.controlCounts = {ctrl, ctrl, ctrl};
  FitReport r;
  for (auto _ : state) benchmark::DoNotOptimize(fitStructured(g, o, &r));
  state.counters["max_rel_error"] = r.maxRelativeError();
  state.counters["samples_per_s"] = benchmark::Counter(
      static_cast<double>(g.sampleCount()), benchmark::Counter::kIsIterationInvariantRate);
}

BENCHMARK(encode)
    ->Name("Encode_marschner_lobb")
    ->Args({128, 64, 3})
    ->Args({256, 256, 2})
    ->ArgNames({"samples", "ctrl", "p"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace
}  // namespace mfadvr
