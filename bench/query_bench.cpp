// Query throughput of the tensor-product B-spline model: value and value+gradient, degrees 1..4,
// 64^3 and 256^3 control points, random and ray-ordered points, one thread and all threads.
//
//   build/release/bench/mfadvr_bench --benchmark_filter=Query --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
#include <benchmark/benchmark.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <map>
#include <memory>
#include <random>

#include "core/model/Model.h"

namespace mfadvr {
namespace {

constexpr size_t kPoints = 1 << 20;

const Model& modelFor(int degree, int n) {
  static std::map<std::pair<int, int>, std::unique_ptr<Model>> cache;
  auto& slot = cache[{degree, n}];
  if (!slot) {
    std::mt19937 rng(degree * 1000 + n);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    std::vector<float> ctrl(static_cast<size_t>(n) * n * n);
    for (float& c : ctrl) c = uni(rng);
    const KnotVector k = KnotVector::clampedUniform(degree, n);
    slot =
        std::make_unique<Model>(TensorBSpline({k, k, k}, std::move(ctrl)), DomainBox{}, 0.0, 1.0);
  }
  return *slot;
}

// Uniform random points in the unit cube: every query a cache miss on large models.
const std::vector<Vec3d>& randomPoints() {
  static const std::vector<Vec3d> pts = [] {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::vector<Vec3d> p(kPoints);
    for (auto& x : p) x = Vec3d(uni(rng), uni(rng), uni(rng));
    return p;
  }();
  return pts;
}

// Points in the order a ray caster visits them: 1024 rays of 1024 samples through the cube.
const std::vector<Vec3d>& rayPoints() {
  static const std::vector<Vec3d> pts = [] {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    std::vector<Vec3d> p;
    p.reserve(kPoints);
    while (p.size() < kPoints) {
      const Vec3d a(uni(rng), uni(rng), 0.0), b(uni(rng), uni(rng), 1.0);
      for (int s = 0; s < 1024; ++s) p.push_back(a + (b - a) * (s / 1023.0));
    }
    return p;
  }();
  return pts;
}

enum class Order { kRandom, kRay };
enum class Kind { kValue, kValueGradient };

void query(benchmark::State& state, Kind kind, Order order) {
  const int degree = static_cast<int>(state.range(0));
  const int n = static_cast<int>(state.range(1));
  const int threads =
      state.range(2) == 0 ? tbb::info::default_concurrency() : static_cast<int>(state.range(2));
  const Model& m = modelFor(degree, n);
  const auto& pts = order == Order::kRandom ? randomPoints() : rayPoints();
  std::vector<float> values(pts.size());
  std::vector<Vec3f> gradients(kind == Kind::kValueGradient ? pts.size() : 0);
  tbb::task_arena arena(threads);
  for (auto _ : state) {
    arena.execute([&] { m.evaluate(pts, values, gradients); });
    benchmark::DoNotOptimize(values.data());
    benchmark::DoNotOptimize(gradients.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * pts.size()));
  state.counters["threads"] = threads;
  state.counters["ns_per_point_per_thread"] = benchmark::Counter(
      static_cast<double>(pts.size()) / threads,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void queryArgs(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 0})
    for (int n : {64, 256})
      for (int p = 1; p <= 4; ++p) b->Args({p, n, threads});
  b->ArgNames({"p", "ctrl", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK_CAPTURE(query, Query_value_random, Kind::kValue, Order::kRandom)->Apply(queryArgs);
BENCHMARK_CAPTURE(query, Query_value_gradient_random, Kind::kValueGradient, Order::kRandom)
    ->Apply(queryArgs);
BENCHMARK_CAPTURE(query, Query_value_ray, Kind::kValue, Order::kRay)->Apply(queryArgs);
BENCHMARK_CAPTURE(query, Query_value_gradient_ray, Kind::kValueGradient, Order::kRay)
    ->Apply(queryArgs);

}  // namespace
}  // namespace mfadvr
