#include "core/encode/ScatteredSmoothingChoice.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "core/encode/KnotPlacement.h"
#include "core/model/DomainBox.h"
#include "core/util/Error.h"

namespace mfadvr {

namespace {

// Splitmix64: a fixed, well-mixed order of the points that does not follow their numbering
// (meshes number points along lines, so every eighth index would be a regular sub-grid).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

ScatteredSmoothingChoice chooseScatteredSmoothing(const ScatteredData& data,
                                                  const ScatteredFitOptions& options) {
  data.validate();
  constexpr std::int64_t kMinPoints = 64;
  if (data.pointCount() < kMinPoints)
    throw Error("--smooth auto needs at least " + std::to_string(kMinPoints) + " points; " +
                data.source + " has " + std::to_string(data.pointCount()) +
                " (give a weight, --smooth L)");
  const Index3 n = resolveScatteredControlCounts(data, options);

  // The points that span the box stay in the training set.
  std::vector<char> extreme(data.points.size(), 0);
  for (int a = 0; a < 3; ++a) {
    auto [lo, hi] =
        std::minmax_element(data.points.begin(), data.points.end(),
                            [a](const Vec3d& p, const Vec3d& q) { return p[a] < q[a]; });
    extreme[static_cast<size_t>(lo - data.points.begin())] = 1;
    extreme[static_cast<size_t>(hi - data.points.begin())] = 1;
  }
  ScatteredData train;
  train.source = data.source;
  train.kind = data.kind;
  std::vector<Vec3d> heldParams;
  std::vector<double> heldValues;
  const DomainBox box{data.boxMin(), data.boxMax()};
  for (size_t i = 0; i < data.points.size(); ++i) {
    if (!extreme[i] && mix(i) % 8 == 0) {
      heldParams.push_back(box.toParameter(data.points[i]));
      heldValues.push_back(data.values[i]);
    } else {
      train.points.push_back(data.points[i]);
      train.values.push_back(data.values[i]);
    }
  }

  // The final fit's knots, from all the points.
  const std::array<std::vector<double>, 3> sorted = sortedAxisParameters(data);
  std::array<KnotVector, 3> knots;
  for (int a = 0; a < 3; ++a)
    knots[a] = knotsFollowingDensity(options.degree[a], static_cast<int>(n[a]), sorted[a],
                                     options.knotDensity);

  ScatteredSmoothingChoice choice;
  choice.heldOutPoints = static_cast<std::int64_t>(heldParams.size());
  std::map<double, double> errorAt;  // log10 lambda -> held-out RMS
  std::optional<Model> previous;
  const int kMaxFits = 9;  // 7 decades and 2 refinements at most
  auto tryLog = [&](double lg) {
    if (auto it = errorAt.find(lg); it != errorAt.end()) return it->second;
    ScatteredFitOptions o = options;
    o.controlCounts = n;
    o.smoothing = std::pow(10.0, lg);
    const int done = static_cast<int>(choice.curve.size());
    char stage[96];
    std::snprintf(stage, sizeof stage, "choosing the smoothing (lambda %.3g, fit %d)", o.smoothing,
                  done + 1);
    o.progress = [&](double f, const std::string&) {
      if (options.progress) options.progress((done + f) / kMaxFits, stage);
    };
    Model m = previous ? fitScatteredWithKnots(train, knots, o, &*previous)
                       : fitScattered(train, o);  // coarse to fine the first time
    const TensorBSpline& s = m.spline();
    const double sumSq = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, heldParams.size(), 4096), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double acc) {
          for (size_t i = r.begin(); i < r.end(); ++i) {
            const double e = static_cast<double>(s.value(heldParams[i])) - heldValues[i];
            acc += e * e;
          }
          return acc;
        },
        [](double x, double y) { return x + y; });
    const double rms = std::sqrt(sumSq / static_cast<double>(heldParams.size()));
    errorAt[lg] = rms;
    choice.curve.push_back({o.smoothing, rms});
    previous = std::move(m);
    return rms;
  };

  // Decades from 1 down to 1e-6, stopping two decades past the best.
  double bestLog = 0.0, best = tryLog(0.0);
  for (double lg = -1.0; lg >= -6.0; lg -= 1.0) {
    const double e = tryLog(lg);
    if (e < best) {
      best = e;
      bestLog = lg;
    } else if (lg <= bestLog - 2.0) {
      break;
    }
  }
  // Half a decade on both sides (the warm start is the last fit, close to both).
  for (double lg : {bestLog - 0.5, bestLog + 0.5}) {
    if (lg > 0.0 || lg < -6.0) continue;
    const double e = tryLog(lg);
    if (e < best) {
      best = e;
      bestLog = lg;
    }
  }
  choice.lambda = std::pow(10.0, bestLog);
  choice.heldOutRms = best;
  char line[256];
  std::snprintf(line, sizeof line,
                "lambda %.3g by hold-out cross-validation (%lld of %lld points held out, %zu "
                "fits); held-out RMS error %.3g",
                choice.lambda, static_cast<long long>(choice.heldOutPoints),
                static_cast<long long>(data.pointCount()), choice.curve.size(), best);
  choice.note = line;
  return choice;
}

}  // namespace mfadvr
