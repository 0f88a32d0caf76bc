// The per-transfer-function cost of empty-space skipping on a 256^3 model (253^3 knot-span
// cells at p = 3): the flags' build (every cell's control-point range computed and classified,
// then the pyramid), and the per-frame depth bounds over them.
//
//   build/release/bench/mfadvr_bench --benchmark_filter=EmptySpace --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

#include "core/model/Model.h"
#include "core/render/Camera.h"
#include "core/render/DepthBounds.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/TransferFunctionTable.h"

namespace mfadvr {
namespace {

// A smooth field whose upper values form blobs: a step at 0.6 hides most cells, as a transfer
// function hiding the air of a scan does.
const TensorBSpline& blobs() {
  static const std::unique_ptr<TensorBSpline> s = [] {
    constexpr int n = 256;
    std::vector<float> ctrl(static_cast<size_t>(n) * n * n);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          ctrl[i + n * (j + std::size_t(n) * k)] =
              0.5f + 0.25f * std::sin(i * 0.11f) * std::sin(j * 0.07f) * std::sin(k * 0.05f) +
              0.25f * std::sin((i + j + k) * 0.013f);
    const KnotVector knots = KnotVector::clampedUniform(3, n);
    return std::make_unique<TensorBSpline>(std::array<KnotVector, 3>{knots, knots, knots},
                                           std::move(ctrl));
  }();
  return *s;
}

const TransferFunctionTable& stepTable() {
  static const TransferFunctionTable t = [] {
    TransferFunction tf;
    tf.space = TfSpace::Data;
    tf.opacity = {{0.0, 0.0f}, {0.6, 0.0f}, {0.6001, 0.5f}, {1.0, 0.5f}};
    tf.color = {{0.0, Vec3f(1, 1, 1)}, {1.0, Vec3f(1, 0, 0)}};
    return TransferFunctionTable(tf, OpacityCorrection(1.0));
  }();
  return t;
}

void BM_EmptySpaceFlagsBuild(benchmark::State& state) {
  const SpanRanges& ranges = *blobs().spanRanges();
  std::int64_t empty = 0;
  for (auto _ : state) {
    const EmptySpaceFlags f = buildEmptySpaceFlags(blobs().view(), ranges, stepTable());
    empty = f.emptyCells;
    benchmark::DoNotOptimize(f.cells.data());
  }
  state.counters["empty_fraction"] = double(empty) / double(ranges.cellCount());
  state.counters["cells/s"] =
      benchmark::Counter(double(ranges.cellCount()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_EmptySpaceFlagsBuild)->Unit(benchmark::kMillisecond)->UseRealTime();

// The per-frame depth bounds (DepthBounds.h) of the same model at 1000x1000, the camera framing
// the box (zoom 1) or close to it (zoom 4: the blocks' projections cover many tiles).
void BM_EmptySpaceDepthBounds(benchmark::State& state) {
  static const EmptySpaceFlags flags =
      buildEmptySpaceFlags(blobs().view(), *blobs().spanRanges(), stepTable());
  ModelView view{};
  view.spline = blobs().view();
  for (int a = 0; a < 3; ++a) {
    view.boxMin[a] = 0.0;
    view.inverseExtent[a] = 1.0;
  }
  flags.attachTo(view);
  Camera camera;
  camera.resetToBounds(Vec3d::Zero(), Vec3d::Ones());
  camera.azimuth(30.0);
  camera.elevation(20.0);
  camera.zoom(static_cast<double>(state.range(0)));
  const CameraRays rays = RayGenerator(camera, 1000, 1000).rays();
  int level = 0;
  std::int64_t blocks = 0;
  for (auto _ : state) {
    const DepthBounds bounds(rays, view);
    level = bounds.level();
    blocks = bounds.occupiedBlocks();
    benchmark::DoNotOptimize(bounds.view().nearest);
  }
  state.counters["level"] = level;
  state.counters["occupied_blocks"] = double(blocks);
}
BENCHMARK(BM_EmptySpaceDepthBounds)->Arg(1)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace mfadvr
