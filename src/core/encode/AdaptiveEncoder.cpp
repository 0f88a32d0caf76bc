#include "core/encode/AdaptiveEncoder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>

#include "core/encode/KnotPlacement.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr {
namespace {

using Clock = std::chrono::steady_clock;

// Where to split span s of an axis; nullopt when it cannot be split.
using SplitRule = std::function<std::optional<double>(const KnotVector&, int span)>;

// Splits, on every axis, the spans whose worst error exceeds `bound`, worst first, up to the
// axis's cap. Returns how many knots were inserted and whether any were held back by a cap.
struct Refinement {
  int inserted = 0;
  bool capped = false;
  bool unsplittable = false;
  std::array<double, 3> worstUnsplittable{0.0, 0.0, 0.0};  // per axis; 0: none
};

Refinement refine(std::array<KnotVector, 3>& knots,
                  const std::array<std::vector<double>, 3>& spanErrors, double bound,
                  const Index3& caps, const std::array<SplitRule, 3>& split) {
  Refinement out;
  for (int a = 0; a < 3; ++a) {
    const KnotVector& kv = knots[a];
    const int p = kv.degree();
    std::vector<std::pair<double, double>> candidates;  // (error, new knot)
    for (size_t s = 0; s < spanErrors[a].size(); ++s) {
      if (!(spanErrors[a][s] > bound)) continue;
      if (const auto u = split[a](kv, static_cast<int>(s) + p))
        candidates.emplace_back(spanErrors[a][s], *u);
      else {
        out.unsplittable = true;
        out.worstUnsplittable[a] = std::max(out.worstUnsplittable[a], spanErrors[a][s]);
      }
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const auto& x, const auto& y) { return x.first > y.first; });
    const std::int64_t room = caps[a] - kv.controlCount();
    if (static_cast<std::int64_t>(candidates.size()) > room) {
      out.capped = true;
      candidates.resize(static_cast<size_t>(std::max<std::int64_t>(room, 0)));
    }
    if (candidates.empty()) continue;
    std::vector<double> u = kv.knots();
    for (const auto& c : candidates) u.push_back(c.second);
    std::sort(u.begin(), u.end());
    knots[a] = KnotVector::fromKnots(p, std::move(u));
    out.inserted += static_cast<int>(candidates.size());
  }
  return out;
}

std::string stopReasonFor(const Refinement& r, int maxRounds, bool roundsLeft) {
  if (!roundsLeft) return "round limit (" + std::to_string(maxRounds) + ") reached";
  if (r.capped) return "control-point limit reached";
  if (r.unsplittable) return "the spans that exceed the bound cannot be split further";
  return "no span can be refined";
}

void validate(const AdaptiveOptions& o) {
  if (!(o.maxRelativeError > 0.0) || !std::isfinite(o.maxRelativeError))
    throw Error("the error bound must be a number above 0 (relative to the value range)");
  if (o.maxRounds < 1) throw Error("the round limit must be at least 1");
  for (std::int64_t c : o.maxControlCounts)
    if (c < 0) throw Error("control-point limits must be positive");
}

// Optional refinement hooks of a kind of input.
struct AxisRules {
  std::array<SplitRule, 3> split;
  // Per-axis span errors to refine by before falling back to the full model's span errors.
  std::function<std::array<std::vector<double>, 3>(const std::array<KnotVector, 3>&)> curveErrors;
  // Adjusts refined knots (e.g. to interpolation knots once an axis has a control point per
  // sample).
  std::function<void(std::array<KnotVector, 3>&)> normalize;
  // Called for an axis whose failing spans cannot be split; returns whether it refined the
  // axis some other way (grids: all the way to interpolation, if the cap allows).
  std::function<bool(int axis, std::array<KnotVector, 3>&)> saturate;
  // Bytes a round with these knots holds (scattered fits: scatteredFitPeakBytes). The first
  // round must fit in the memory; a later one that would not stops the refinement, with the
  // best model so far, instead of failing for want of memory.
  std::function<std::int64_t(const std::array<KnotVector, 3>&)> peakBytes;
};

std::string countsText(const std::array<KnotVector, 3>& k) {
  return std::to_string(k[0].controlCount()) + "x" + std::to_string(k[1].controlCount()) + "x" +
         std::to_string(k[2].controlCount());
}

// The refinement loop shared by grids and points. fit(knots, previous, report, spanErrors)
// fits one round.
template <class FitFn>
Model adapt(std::array<KnotVector, 3> knots, const Index3& caps, const AdaptiveOptions& adaptive,
            const AxisRules& rules, FitFn&& fit, FitReport* report) {
  const auto start = Clock::now();
  std::optional<Model> best;
  FitReport bestReport;
  std::optional<Model> previous;
  std::string stopReason;
  bool reached = false;
  int round = 0;
  int solverIterations = 0;
  for (round = 1;; ++round) {
    if (rules.peakBytes) {
      const std::int64_t need = rules.peakBytes(knots);
      if (round == 1) {
        requireMemory(need, "the first round of the adaptive fit (" + countsText(knots) +
                                " control points; fewer to start with, --ctrl, need less)");
      } else if (const std::int64_t available = availableMemoryBytes();
                 available > 0 && need > available) {
        stopReason = "memory limit: the next round (" + countsText(knots) +
                     " control points) would need " + formatBytes(need) + ", " +
                     formatBytes(available) + " available";
        --round;
        break;
      }
    }
    FitReport r;
    std::array<std::vector<double>, 3> spanErrors;
    Model m = fit(knots, previous ? &*previous : nullptr, r, spanErrors);
    solverIterations += r.solverIterations;
    if (adaptive.onRound)
      adaptive.onRound({round, r.controlCounts, r.maxRelativeError(), r.rmsRelativeError(),
                        std::chrono::duration<double>(Clock::now() - start).count()});
    const double bound = adaptive.maxRelativeError * r.valueRange();
    if (!best || r.maxError < bestReport.maxError) {
      best = m;
      bestReport = r;
    }
    if (r.maxError <= bound) {
      reached = true;
      stopReason = "reached the error bound";
      break;
    }
    const bool roundsLeft = round < adaptive.maxRounds;
    Refinement ref;
    if (roundsLeft && rules.curveErrors)
      ref = refine(knots, rules.curveErrors(knots), bound, caps, rules.split);
    if (roundsLeft && ref.inserted == 0) {
      const Refinement full = refine(knots, spanErrors, bound, caps, rules.split);
      ref.inserted = full.inserted;
      ref.capped = ref.capped || full.capped;
      ref.unsplittable = ref.unsplittable || full.unsplittable;
      for (int a = 0; a < 3; ++a)
        ref.worstUnsplittable[a] = std::max(ref.worstUnsplittable[a], full.worstUnsplittable[a]);
    }
    // Saturate one axis per round, the one with the worst unsplittable span: the next fit may
    // meet the bound without the others.
    if (roundsLeft && ref.inserted == 0 && rules.saturate) {
      std::array<int, 3> order{0, 1, 2};
      std::sort(order.begin(), order.end(),
                [&](int x, int y) { return ref.worstUnsplittable[x] > ref.worstUnsplittable[y]; });
      for (int a : order)
        if (ref.worstUnsplittable[a] > 0.0 && rules.saturate(a, knots)) {
          ++ref.inserted;
          break;
        }
    }
    if (ref.inserted > 0 && rules.normalize) rules.normalize(knots);
    if (!roundsLeft || ref.inserted == 0) {
      stopReason = stopReasonFor(ref, adaptive.maxRounds, roundsLeft);
      break;
    }
    previous = std::move(m);
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  best->provenance().fitSeconds = seconds;
  best->provenance().encoder += "-adaptive";
  if (report) {
    *report = bestReport;
    report->seconds = seconds;
    report->rounds = round;
    report->targetRelativeError = adaptive.maxRelativeError;
    report->reachedTarget = reached;
    report->stopReason = stopReason;
    report->solverIterations = solverIterations;
    report->encoder = best->provenance().encoder;
    report->modelBytes = modelFileSize(*best);
  }
  return std::move(*best);
}

}  // namespace

namespace {

// The rules of grids of `dims` samples: spans split between their two middle samples, an axis
// taken to interpolation when a failing span holds one sample. Returns the starting knots and
// fills caps and rules (all but curveErrors, which needs the samples).
std::array<KnotVector, 3> gridRules(const Index3& dims, const StructuredFitOptions& fit,
                                    const AdaptiveOptions& adaptive, Index3& caps,
                                    AxisRules& rules) {
  StructuredGrid layout;
  layout.dims = dims;
  StructuredFitOptions start = fit;
  for (int a = 0; a < 3; ++a)
    if (start.controlCounts[a] == 0)
      start.controlCounts[a] = std::min<std::int64_t>(dims[a], fit.degree[a] + 2);
  const Index3 n = resolveControlCounts(layout, start);
  std::array<KnotVector, 3> knots;
  auto& split = rules.split;
  for (int a = 0; a < 3; ++a) {
    caps[a] = adaptive.maxControlCounts[a] == 0 ? dims[a]
                                                : std::min(adaptive.maxControlCounts[a], dims[a]);
    caps[a] = std::max(caps[a], n[a]);
    knots[a] = knotsForSamples(fit.degree[a], static_cast<int>(n[a]), dims[a]);
    const double last = static_cast<double>(dims[a] - 1);
    const std::int64_t samples = dims[a];
    split[a] = [last, samples](const KnotVector& kv, int s) -> std::optional<double> {
      const double lo = kv.knots()[static_cast<size_t>(s)],
                   hi = kv.knots()[static_cast<size_t>(s + 1)];
      const bool lastSpan = s == kv.controlCount() - 1;
      // The samples t_i = i / (N-1) in [u_s, u_{s+1}) (the last span also holds t = 1), as
      // KnotVector::findSpan assigns them.
      std::int64_t first = -1, count = 0;
      for (std::int64_t i = 0; i < samples; ++i) {
        const double t = static_cast<double>(i) / last;
        if (t >= lo && (t < hi || lastSpan)) {
          if (first < 0) first = i;
          ++count;
        }
      }
      if (count < 2) return std::nullopt;
      const std::int64_t m = first + count / 2 - 1;
      return (static_cast<double>(m) + 0.5) / last;
    };
  }
  // With a control point per sample, the averaged knots make the fit an exact interpolation.
  rules.normalize = [dims](std::array<KnotVector, 3>& k) {
    for (int a = 0; a < 3; ++a)
      if (k[a].controlCount() >= dims[a])
        k[a] = knotsForSamples(k[a].degree(), static_cast<int>(dims[a]), dims[a]);
  };
  // A failing span with a single sample: only interpolation along that axis can do better.
  rules.saturate = [dims, caps](int a, std::array<KnotVector, 3>& k) {
    if (k[a].controlCount() >= dims[a] || caps[a] < dims[a]) return false;
    k[a] = knotsForSamples(k[a].degree(), static_cast<int>(dims[a]), dims[a]);
    return true;
  };
  return knots;
}

}  // namespace

Model fitStructuredAdaptive(const StructuredGrid& grid, const StructuredFitOptions& fit,
                            const AdaptiveOptions& adaptive, FitReport* report) {
  validate(adaptive);
  grid.validate();
  Index3 caps{};
  AxisRules rules;
  std::array<KnotVector, 3> knots = gridRules(grid.dims, fit, adaptive, caps, rules);
  // Refine an axis where 1-D fits of the grid lines along it miss the bound (so that a feature
  // along x does not refine y and z); only when none do, by the full model's errors.
  rules.curveErrors = [&](const std::array<KnotVector, 3>& k) { return curveSpanErrors(grid, k); };
  StructuredFitOptions round = fit;
  round.progress = nullptr;
  return adapt(
      std::move(knots), caps, adaptive, rules,
      [&](const std::array<KnotVector, 3>& k, const Model*, FitReport& r,
          std::array<std::vector<double>, 3>& spanErrors) {
        return fitStructuredWithKnots(grid, k, round, &r, &spanErrors);
      },
      report);
}

std::array<KnotVector, 3> adaptSharedKnots(const Index3& dims, const StructuredFitOptions& fit,
                                           const AdaptiveOptions& adaptive,
                                           const SharedKnotsFit& fitAll, FitReport* report) {
  validate(adaptive);
  Index3 caps{};
  AxisRules rules;
  std::array<KnotVector, 3> knots = gridRules(dims, fit, adaptive, caps, rules);
  const Model best = adapt(
      std::move(knots), caps, adaptive, rules,
      [&](const std::array<KnotVector, 3>& k, const Model*, FitReport& r,
          std::array<std::vector<double>, 3>& spanErrors) { return fitAll(k, r, spanErrors); },
      report);
  return best.spline().allKnots();
}

constexpr double kAdaptiveSolverTolerance = 1e-6;

Model fitScatteredAdaptive(const ScatteredData& data, const ScatteredFitOptions& fit,
                           const AdaptiveOptions& adaptive, FitReport* report) {
  validate(adaptive);
  data.validate();
  ScatteredFitOptions start = fit;
  for (int a = 0; a < 3; ++a)
    if (start.controlCounts[a] == 0) start.controlCounts[a] = fit.degree[a] + 2;
  const Index3 n = resolveScatteredControlCounts(data, start);
  Index3 caps{};
  std::array<KnotVector, 3> knots;
  // The first round's knots follow the points' density as a fixed fit's do.
  const std::array<std::vector<double>, 3> sorted = sortedAxisParameters(data);
  AxisRules rules;
  auto& split = rules.split;
  for (int a = 0; a < 3; ++a) {
    caps[a] =
        std::max(adaptive.maxControlCounts[a] == 0 ? 256 : adaptive.maxControlCounts[a], n[a]);
    knots[a] =
        knotsFollowingDensity(fit.degree[a], static_cast<int>(n[a]), sorted[a], fit.knotDensity);
    split[a] = [](const KnotVector& kv, int s) -> std::optional<double> {
      const double lo = kv.knots()[static_cast<size_t>(s)],
                   hi = kv.knots()[static_cast<size_t>(s + 1)];
      if (!(hi - lo > 1e-6)) return std::nullopt;
      return 0.5 * (lo + hi);
    };
  }
  rules.peakBytes = [&](const std::array<KnotVector, 3>& k) {
    return scatteredFitPeakBytes(static_cast<std::int64_t>(data.points.size()),
                                 {k[0].controlCount(), k[1].controlCount(), k[2].controlCount()},
                                 fit.degree);
  };
  ScatteredFitOptions round = fit;
  round.progress = nullptr;
  // Rounds solve tighter than a fixed fit: a loose solve's own error is refined away with more
  // knots. Measured on the blunt fin (docs/encoding.md): at 1e-4, --max-error 0.02 took 22 s
  // instead of 229 s for the same model, but 0.01 took 14 rounds and 404 s instead of 11 and
  // 287 s.
  round.tolerance = std::min(fit.tolerance, kAdaptiveSolverTolerance);
  return adapt(
      std::move(knots), caps, adaptive, rules,
      [&](const std::array<KnotVector, 3>& k, const Model* previous, FitReport& r,
          std::array<std::vector<double>, 3>& spanErrors) {
        return fitScatteredWithKnots(data, k, round, previous, &r, &spanErrors);
      },
      report);
}

}  // namespace mfadvr
