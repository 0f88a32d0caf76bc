#include "core/encode/SmoothingChoice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/encode/KnotPlacement.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// One part of the data the choice is judged on, with its control counts.
struct Part {
  StructuredGrid grid;
  Index3 counts{};
};

StructuredGrid brickOf(const StructuredGrid& g, const Index3& begin, const Index3& size) {
  StructuredGrid b;
  b.dims = size;
  b.spacing = g.spacing;
  b.origin = g.position(begin[0], begin[1], begin[2]);
  b.values.resize(static_cast<size_t>(size[0] * size[1] * size[2]));
  size_t i = 0;
  for (std::int64_t z = 0; z < size[2]; ++z)
    for (std::int64_t y = 0; y < size[1]; ++y)
      for (std::int64_t x = 0; x < size[0]; ++x)
        b.values[i++] = g.at(begin[0] + x, begin[1] + y, begin[2] + z);
  return b;
}

std::vector<Part> partsOf(const StructuredGrid& grid, const Index3& counts, const Degree3& p,
                          const SmoothingSearch& search) {
  std::vector<Part> parts;
  if (grid.sampleCount() <= search.wholeGridSamples) {
    parts.push_back({grid, counts});
    return parts;
  }
  const std::int64_t kBrick = search.brickSamples;
  Index3 size{}, n{};
  for (int a = 0; a < 3; ++a) {
    size[a] = std::min<std::int64_t>(kBrick, grid.dims[a]);
    // Spans per sample as in the whole fit: (n - p) / (N - 1).
    const double spansPerSample =
        static_cast<double>(counts[a] - p[a]) / static_cast<double>(grid.dims[a] - 1);
    n[a] = std::clamp<std::int64_t>(
        p[a] + std::llround(spansPerSample * static_cast<double>(size[a] - 1)), p[a] + 1, size[a]);
  }
  for (int o = 0; o < 8; ++o) {
    Index3 begin{};
    for (int a = 0; a < 3; ++a) {
      const std::int64_t centre = ((o >> a) & 1) ? 3 * grid.dims[a] / 4 : grid.dims[a] / 4;
      begin[a] = std::clamp<std::int64_t>(centre - size[a] / 2, 0, grid.dims[a] - size[a]);
    }
    parts.push_back({brickOf(grid, begin, size), n});
  }
  return parts;
}

}  // namespace

SmoothingChoice chooseSmoothing(const StructuredGrid& grid, const StructuredFitOptions& options,
                                const SmoothingSearch& search) {
  grid.validate();
  const Index3 counts = resolveControlCounts(
      grid, StructuredFitOptions{options.degree, options.controlCounts, 0.0, nullptr});
  if (!(search.quantizationStep >= 0.0) || !std::isfinite(search.quantizationStep))
    throw Error("the quantization step must be a finite number >= 0");
  const std::vector<Part> parts = partsOf(grid, counts, options.degree, search);
  SmoothingChoice choice;
  choice.bricks = parts.size() > 1 ? static_cast<int>(parts.size()) : 0;
  for (const Part& part : parts) choice.samplesJudged += part.grid.sampleCount();
  const double P = static_cast<double>(choice.samplesJudged);

  auto evaluate = [&](double logLambda) {
    const double lambda = std::pow(10.0, logLambda);
    double rss = 0.0, trace = 0.0;
    for (const Part& part : parts) {
      StructuredFitOptions fit;
      fit.degree = options.degree;
      fit.controlCounts = part.counts;
      fit.smoothing = lambda;
      const Model m = fitStructured(part.grid, fit);
      const double rms = m.provenance().rmsError;
      rss += rms * rms * static_cast<double>(part.grid.sampleCount());
      trace += effectiveParameters(m.spline().allKnots(), part.grid.dims, lambda);
    }
    const double free = 1.0 - trace / P;
    const double gcv =
        free > 0.0 ? (rss / P) / (free * free) : std::numeric_limits<double>::infinity();
    choice.curve.push_back({lambda, gcv, rss, trace});
    return gcv;
  };

  constexpr double kLow = -6.0, kHigh = 3.0;
  const int coarseSteps = static_cast<int>(kHigh - kLow);
  double bestLog = kLow, bestGcv = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= coarseSteps; ++i) {
    if (options.progress) options.progress(0.6 * i / coarseSteps, "choosing the smoothing");
    const double l = kLow + i;
    const double g = evaluate(l);
    if (g < bestGcv) bestGcv = g, bestLog = l;
  }
  int refinement = 0;
  for (double step = 0.5; step >= 0.125; step *= 0.5, ++refinement) {
    if (options.progress) options.progress(0.6 + 0.13 * refinement, "choosing the smoothing");
    const double centre = bestLog;
    for (double l : {centre - step, centre + step}) {
      if (l < kLow || l > kHigh) continue;
      const double g = evaluate(l);
      if (g < bestGcv) bestGcv = g, bestLog = l;
    }
  }
  auto noiseAt = [&](const SmoothingChoice::Point& pt) {
    return P > pt.trace ? std::sqrt(pt.rss / (P - pt.trace)) : 0.0;
  };
  auto pointAt = [&](double logLambda) -> const SmoothingChoice::Point& {
    const double lambda = std::pow(10.0, logLambda);
    for (const auto& pt : choice.curve)
      if (pt.lambda == lambda) return pt;
    evaluate(logLambda);
    return choice.curve.back();
  };
  const double floor = search.quantizationStep / std::sqrt(12.0);
  if (floor > 0.0 && noiseAt(pointAt(bestLog)) < floor) {
    // The implied noise grows with lambda: bisect log lambda between the GCV choice and the
    // first coarse lambda above the floor (or the largest) to a factor of 10^(1/16).
    double lo = bestLog, hi = kHigh;
    for (const auto& pt : choice.curve) {
      const double l = std::log10(pt.lambda);
      if (l > lo && l < hi && noiseAt(pt) >= floor) hi = l;
    }
    if (noiseAt(pointAt(hi)) >= floor) {
      while (hi - lo > 1.0 / 16.0) {
        const double mid = 0.5 * (lo + hi);
        (noiseAt(pointAt(mid)) < floor ? lo : hi) = mid;
      }
    }
    bestLog = hi;
    choice.raisedToQuantization = true;
  }
  choice.lambda = std::pow(10.0, bestLog);
  const SmoothingChoice::Point& chosen = pointAt(bestLog);
  choice.effectiveParameters = chosen.trace;
  choice.noiseRms = noiseAt(chosen);
  char line[320];
  const std::string over = choice.bricks
                               ? "8 bricks of " + std::to_string(search.brickSamples) + "^3 samples"
                               : std::string("every sample");
  std::snprintf(
      line, sizeof line,
      "lambda %.3g by generalized cross-validation over %s (%zu fits)%s; estimated "
      "noise %.3g RMS; %.3g effective parameters per sample",
      choice.lambda, over.c_str(), choice.curve.size(),
      choice.raisedToQuantization ? ", raised to the quantization floor (step/sqrt(12))" : "",
      choice.noiseRms, choice.effectiveParameters / P);
  choice.note = line;
  if (options.progress) options.progress(1.0, "choosing the smoothing");
  return choice;
}

}  // namespace mfadvr
