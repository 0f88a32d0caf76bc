#include "core/encode/TimeSeriesEncoder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "core/encode/AxisFit.h"
#include "core/encode/Dequantizer.h"
#include "core/encode/KnotPlacement.h"
#include "core/encode/SmoothingChoice.h"
#include "core/encode/ToleranceSearch.h"
#include "core/model/ModelFile.h"
#include "core/model/ZfpArray.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr {
namespace {

std::string dimsText(const Index3& d) {
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

bool sameLayout(const StructuredGrid& a, const StructuredGrid& b) {
  if (a.dims != b.dims) return false;
  // The same box up to rounding of a header's decimal numbers.
  for (int i = 0; i < 3; ++i) {
    const double scale = std::max(std::abs(a.spacing[i]) * static_cast<double>(a.dims[i]), 1e-300);
    if (std::abs(a.origin[i] - b.origin[i]) > 1e-6 * scale ||
        std::abs(a.spacing[i] - b.spacing[i]) > 1e-6 * std::abs(a.spacing[i]))
      return false;
  }
  return true;
}

// Options that do not combine, known before any step is read.
void refuseUnsupported(const EncodeOptions& o, int steps, int timeControls) {
  refuseWithDequantize(o);
  if (o.adaptive) {
    if (o.coding.budget.kind != BudgetKind::kNone)
      throw Error("a size or quality budget does not combine with an error bound (--max-error)");
    if (timeControls != steps)
      throw Error(
          "--max-error bounds the error at every sample of every step only with a model that "
          "interpolates in time: leave --time-ctrl at the number of steps (" +
          std::to_string(steps) + ")");
  }
  if (o.autoSmoothing && o.smoothing)
    throw Error("give either a smoothing weight or automatic smoothing, not both");
  if (o.dequantizeStep) {
    if (timeControls != steps)
      throw Error(
          "--dequantize keeps every sample of every step within half a quantization step only "
          "with a model that interpolates in time: leave --time-ctrl at the number of steps (" +
          std::to_string(steps) + ")");
  }
  const ModelBudget& budget = o.coding.budget;
  if (budget.kind != BudgetKind::kNone) {
    if (!(std::isfinite(budget.value) && budget.value > 0.0))
      throw Error("the budget must be a positive number");
    if (resolvedCoder(o.coding) != ControlCoder::kZfp)
      throw Error(
          "a budget of a time series chooses the zfp tolerance of its 4-D model: it needs "
          "--coding zfp (the default with a budget)");
    if (o.coding.tolerance > 0.0)
      throw Error("a budget chooses the zfp tolerance: give one or the other");
  }
}

// The zfp tolerance of the 4-D control points when none is given.
double defaultTolerance(const std::string& sampleType, double range) {
  if (isIntegerSampleType(sampleType)) return kIntegerDefaultTolerance;
  return std::max(kFloatDefaultRelativeTolerance * range, 1e-30);
}

}  // namespace

std::int64_t timeSeriesPeakBytes(const Index3& dims, const Index3& counts, std::int64_t slabs,
                                 const TimeSeriesWork& work) {
  const std::int64_t spatial = counts[0] * counts[1] * counts[2];
  const std::int64_t samples = dims[0] * dims[1] * dims[2];
  std::int64_t bytes = 4 * spatial * slabs + structuredFitPeakBytes(dims, counts) + 4 * spatial;
  // A decoded candidate beside the control points.
  if (work.budget) bytes += 4 * spatial * slabs;
  // The dequantizer's three double vectors and the targets, beside the step's samples.
  if (work.dequantize) bytes += 28 * samples;
  return bytes;
}

namespace {

// The max and RMS error of `model` over every sample of every step (one pass over the series).
SampleErrors measureOnSeries(const TimeVaryingModel& model, const VolumeSeries& series,
                             const std::vector<double>& times,
                             const std::function<void(int)>& onStep) {
  double maxErr = 0.0, sumSq = 0.0;
  std::int64_t samples = 0;
  for (int s = 0; s < series.size(); ++s) {
    if (onStep) onStep(s);
    const StructuredGrid grid = series.load(s);
    const SampleErrors e = errorsOnGrid(model.at(times[static_cast<size_t>(s)]).spline(), grid);
    maxErr = std::max(maxErr, e.max);
    sumSq += e.rms * e.rms * static_cast<double>(grid.sampleCount());
    samples += grid.sampleCount();
  }
  return {maxErr, std::sqrt(sumSq / static_cast<double>(std::max<std::int64_t>(samples, 1)))};
}

// What the dequantized steps (`--dequantize`) gave, over the series.
struct DequantizeTally {
  double step = 0.0;
  double lambda = 0.0;
  int iterations = 0;  // the most any step needed
  bool converged = true;
  double edgeSamples = 0.0;
  std::int64_t samples = 0;
  double seconds = 0.0;
  double maxDeviation = 0.0;  // the largest |step's fit - sample|
};

}  // namespace

TimeVaryingModel encodeTimeSeries(const VolumeSeries& series, const EncodeOptions& options,
                                  const TimeSeriesOptions& timeOptions, FitReport* report,
                                  std::vector<std::string>* notes) {
  const auto start = std::chrono::steady_clock::now();
  const int steps = series.size();
  if (steps < 2)
    throw Error("a time series needs at least two steps; " + series.source() + " has " +
                std::to_string(steps));
  std::vector<double> times(static_cast<size_t>(steps));
  for (int s = 0; s < steps; ++s) {
    times[static_cast<size_t>(s)] = series.time(s);
    if (!std::isfinite(times[static_cast<size_t>(s)]))
      throw Error("the time of " + series.stepName(s) + " is not a finite number");
    if (s > 0 && !(times[static_cast<size_t>(s)] > times[static_cast<size_t>(s - 1)])) {
      std::ostringstream m;
      m.precision(17);
      m << "the times of a series must increase: " << series.stepName(s)
        << " (t = " << times[static_cast<size_t>(s)] << ") is not after " << series.stepName(s - 1)
        << " (t = " << times[static_cast<size_t>(s - 1)] << ")";
      throw Error(m.str());
    }
  }
  if (timeOptions.degree < 1 || timeOptions.degree > kMaxDegree)
    throw Error("--time-degree must lie in 1.." + std::to_string(kMaxDegree));
  int pt = timeOptions.degree;
  if (pt > steps - 1) {
    pt = steps - 1;
    if (notes)
      notes->push_back("time degree lowered from " + std::to_string(timeOptions.degree) + " to " +
                       std::to_string(pt) + ": the series has " + std::to_string(steps) + " steps");
  }
  const int nt = timeOptions.controlCount > 0 ? timeOptions.controlCount : steps;
  if (nt < pt + 1 || nt > steps)
    throw Error("--time-ctrl " + std::to_string(nt) + " must lie between the time degree + 1 (" +
                std::to_string(pt + 1) + ") and the number of steps (" + std::to_string(steps) +
                ")");
  refuseUnsupported(options, steps, nt);
  const bool dequantize = options.dequantizeStep.has_value();
  const bool adaptive = options.adaptive.has_value();
  const ModelBudget& budget = options.coding.budget;

  auto progress = [&](double f, const std::string& stage) {
    if (options.progress) options.progress(f, stage);
  };

  // --smooth auto: lambda chosen on the middle step (the steps share the knots and the lambda).
  double lambda = options.smoothing.value_or(0.0);
  validateSmoothing(lambda);
  SmoothingChoice choice;
  if (options.autoSmoothing) {
    const int middle = steps / 2;
    progress(0.0, "choosing lambda on " + series.stepName(middle));
    StructuredGrid grid = series.load(middle);
    grid.validateLayout();
    StructuredFitOptions f;
    f.degree = options.degree;
    f.controlCounts = adaptive ? Index3{0, 0, 0} : options.controlCounts;
    SmoothingSearch search;
    search.quantizationStep = options.quantizationStep.value_or(0.0);
    choice = chooseSmoothing(grid, f, search);
    lambda = choice.lambda;
    choice.note += " (judged on " + series.stepName(middle) +
                   ", the middle step; the same lambda fits every step and the time axis)";
  }

  TimeAxis axis;
  axis.begin = times.front();
  axis.end = times.back();
  axis.steps = times;
  std::vector<double> params(times.size());
  for (size_t s = 0; s < times.size(); ++s) params[s] = axis.toParameter(times[s]);
  params.back() = 1.0;
  axis.knots = knotsForParameters(pt, nt, params);
  // Dequantized steps, and the steps of an error bound, are interpolated in time, so that every
  // step keeps the bound its own fit met.
  const double spaceLambda = dequantize ? 0.0 : lambda;
  const double timeLambda = dequantize || adaptive ? 0.0 : lambda;
  const AxisFitter timeFit(sampleAxisAt(axis.knots, params), timeLambda);
  const AxisSampling& rows = timeFit.sampling();

  // Pass 1: each step's spatial fit adds its row of the time basis to B = N_t^T C.
  StructuredFitOptions fit;
  fit.degree = options.degree;
  fit.controlCounts = options.controlCounts;
  fit.smoothing = spaceLambda;
  // The coder of the 4-D array: `mfadvr encode` gives integer samples zfp, as for one grid.
  auto coderFor = [&](const std::string& sampleType) {
    return !options.coding.coder && timeOptions.zfpForIntegerSamples &&
                   isIntegerSampleType(sampleType)
               ? ControlCoder::kZfp
               : resolvedCoder(options.coding);
  };

  // --max-error: the spatial knots refined for every step at once (each round fits every step
  // with one set of knots and refines where any misses the bound). With zfp to choose, the fit
  // gets half the bound and the coding the room it leaves, as for one grid.
  std::optional<std::array<KnotVector, 3>> adaptedKnots;
  FitReport adaptiveReport;
  if (adaptive) {
    const StructuredGrid probe = series.load(0);
    probe.validateLayout();
    AdaptiveOptions bound = *options.adaptive;
    if (coderFor(probe.sampleType) == ControlCoder::kZfp && options.coding.tolerance <= 0.0)
      bound.maxRelativeError *= 0.5;
    int round = 0;
    const SharedKnotsFit fitAll = [&](const std::array<KnotVector, 3>& k, FitReport& r,
                                      std::array<std::vector<double>, 3>& spanErrors) {
      ++round;
      Model any;
      double maxErr = 0.0, sumSq = 0.0, lo = 0.0, hi = 0.0;
      std::int64_t samples = 0;
      for (int s = 0; s < steps; ++s) {
        progress(0.0, "round " + std::to_string(round) + ": fitting " + series.stepName(s));
        const StructuredGrid grid = series.load(s);
        if (grid.dims != probe.dims)
          throw Error(series.stepName(s) + " has another grid than " + series.stepName(0) +
                      ": the steps of a series must share one grid");
        FitReport one;
        std::array<std::vector<double>, 3> spans;
        Model m = fitStructuredWithKnots(grid, k, fit, &one, &spans);
        for (int a = 0; a < 3; ++a) {
          if (s == 0) spanErrors[a].assign(spans[a].size(), 0.0);
          for (size_t i = 0; i < spans[a].size() && i < spanErrors[a].size(); ++i)
            spanErrors[a][i] = std::max(spanErrors[a][i], spans[a][i]);
        }
        maxErr = std::max(maxErr, one.maxError);
        sumSq += one.rmsError * one.rmsError * static_cast<double>(grid.sampleCount());
        samples += grid.sampleCount();
        lo = s == 0 ? one.valueMin : std::min(lo, one.valueMin);
        hi = s == 0 ? one.valueMax : std::max(hi, one.valueMax);
        if (s == 0) {
          r = one;
          any = std::move(m);
        }
      }
      r.maxError = maxErr;
      r.rmsError = std::sqrt(sumSq / static_cast<double>(std::max<std::int64_t>(samples, 1)));
      r.valueMin = lo;
      r.valueMax = hi;
      return any;
    };
    adaptedKnots = adaptSharedKnots(probe.dims, fit, bound, fitAll, &adaptiveReport);
  }

  StructuredGrid first;
  std::array<KnotVector, 3> knots;
  std::vector<float> slabs;
  std::int64_t m = 0;
  Model shape;
  double vmin = 0.0, vmax = 0.0;
  std::int64_t inputBytes = 0;
  DequantizeTally dq;
  if (dequantize) dq.lambda = options.smoothing.value_or(DequantizeOptions{}.smoothing);
  for (int s = 0; s < steps; ++s) {
    const double stepStart = 0.8 * s / steps, stepShare = 0.8 / steps;
    progress(stepStart, "fitting " + series.stepName(s));
    StructuredGrid grid = series.load(s);
    if (s == 0) {
      grid.validateLayout();
      knots = adaptedKnots ? *adaptedKnots : knotsOfFit(grid, fit);
      Index3 counts{};
      for (int a = 0; a < 3; ++a) counts[a] = knots[a].controlCount();
      m = counts[0] * counts[1] * counts[2];
      requireMemory(timeSeriesPeakBytes(grid.dims, counts, nt,
                                        {budget.kind != BudgetKind::kNone, dequantize}),
                    "a " + dimsText(counts) + " x " + std::to_string(nt) +
                        " model of a series of " + dimsText(grid.dims) +
                        " volumes (fewer control points, --ctrl or --time-ctrl, need less)");
      slabs.assign(static_cast<size_t>(m * nt), 0.0f);
      first = grid;
      first.values.clear();
      first.values.shrink_to_fit();
      // What the reader said of the input (a time unit, a placement), once for the series.
      if (notes) notes->insert(notes->end(), grid.notes.begin(), grid.notes.end());
      if (dequantize) {
        dq.step = *options.dequantizeStep;
        if (dq.step == 0.0) {
          if (!isIntegerSampleType(grid.sampleType))
            throw Error("--dequantize: " + series.source() + " holds " + grid.sampleType +
                        " samples; give the step they were quantized with (--dequantize STEP)");
          dq.step = 1.0;
        }
      }
    } else if (!sameLayout(first, grid)) {
      throw Error(series.stepName(s) + " has another grid than " + series.stepName(0) + " (" +
                  dimsText(grid.dims) + " samples from (" + std::to_string(grid.origin[0]) + ", " +
                  std::to_string(grid.origin[1]) + ", " + std::to_string(grid.origin[2]) + ") vs " +
                  dimsText(first.dims) + " from (" + std::to_string(first.origin[0]) + ", " +
                  std::to_string(first.origin[1]) + ", " + std::to_string(first.origin[2]) +
                  ")): the steps of a series must share one grid");
    }
    if (grid.sampleType != first.sampleType && notes && s > 0 &&
        std::find(notes->begin(), notes->end(), "steps of different sample types") == notes->end())
      notes->push_back("steps of different sample types");
    inputBytes += grid.inputBytes;
    Model step;
    if (dequantize) {
      // The step's values within its quantization intervals, then the model through them.
      DequantizeOptions d;
      d.step = dq.step;
      d.smoothing = dq.lambda;
      d.progress = [&](double f, const std::string& stage) {
        progress(stepStart + 0.9 * stepShare * f, series.stepName(s) + ": " + stage);
      };
      DequantizeResult r = dequantizeTargets(grid, knots, d);
      StructuredGrid targets = first;
      targets.values = std::move(r.targets);
      step = fitStructuredWithKnots(targets, knots, fit);
      targets = {};
      dq.maxDeviation = std::max(dq.maxDeviation, errorsOnGrid(step.spline(), grid).max);
      dq.iterations = std::max(dq.iterations, r.iterations);
      dq.converged = dq.converged && r.converged;
      dq.edgeSamples += r.edgeShare * static_cast<double>(grid.sampleCount());
      dq.samples += grid.sampleCount();
      dq.seconds += r.seconds;
    } else {
      step = fitStructuredWithKnots(grid, knots, fit);
    }
    if (s == 0) {
      shape = step;
      vmin = step.valueMin();
      vmax = step.valueMax();
    }
    vmin = std::min(vmin, step.valueMin());
    vmax = std::max(vmax, step.valueMax());
    const std::span<const float> c = step.spline().controlPoints();
    const int w = pt + 1;
    const int f = rows.first[static_cast<size_t>(s)];
    const double* weights = &rows.weights[static_cast<size_t>(s * w)];
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, m, 1 << 14), [&](const auto& range) {
      for (int r = 0; r < w; ++r) {
        if (weights[r] == 0.0) continue;
        float* out = slabs.data() + (f + r) * m;
        for (std::int64_t i = range.begin(); i < range.end(); ++i)
          out[i] += static_cast<float>(weights[r] * c[static_cast<size_t>(i)]);
      }
    });
  }

  // The time solve, one banded system per spatial control point, a block of them at a time.
  progress(0.8, "fitting time");
  constexpr std::int64_t kBlock = 1024;
  tbb::parallel_for(
      tbb::blocked_range<std::int64_t>(0, (m + kBlock - 1) / kBlock), [&](const auto& range) {
        Eigen::MatrixXd rhs;
        for (std::int64_t b = range.begin(); b < range.end(); ++b) {
          const std::int64_t i0 = b * kBlock, k = std::min(kBlock, m - i0);
          rhs.resize(nt, k);
          for (int l = 0; l < nt; ++l)
            for (std::int64_t i = 0; i < k; ++i)
              rhs(l, i) = slabs[static_cast<size_t>(l * m + i0 + i)];
          timeFit.solveNormal(rhs);
          for (int l = 0; l < nt; ++l)
            for (std::int64_t i = 0; i < k; ++i)
              slabs[static_cast<size_t>(l * m + i0 + i)] = static_cast<float>(rhs(l, i));
        }
      });

  Provenance prov = shape.provenance();
  prov.source = series.source();
  prov.inputBytes = inputBytes;
  prov.encoder = dequantize     ? "time-series-dequantize"
                 : lambda > 0.0 ? "time-series-smoothing"
                                : "time-series-least-squares";
  if (adaptive) prov.encoder += "-adaptive";
  const Model spatial(shape.spline(), shape.domain(), vmin, vmax, prov);
  const Index3 counts = shape.spline().counts();
  const double samplesAll =
      static_cast<double>(first.dims[0] * first.dims[1] * first.dims[2]) * steps;

  // The coding of the 4-D array.
  ControlCoding coding;
  coding.coder = coderFor(first.sampleType);
  std::shared_ptr<const std::string> coded;
  std::string codingNote;
  std::optional<SampleErrors> measured;  // the stored model's errors, when a search measured them
  if (coding.coder == ControlCoder::kZfp && budget.kind != BudgetKind::kNone) {
    // A budget: the zfp tolerance of the 4-D array, by bisection over its powers of two (the
    // control grid stays the given or default one).
    const auto [lo, hi] = toleranceExponentRange(vmin, vmax);
    std::map<int, std::int64_t> bytesAt;
    std::map<int, SampleErrors> errorsAt;
    auto codeAt = [&](int k) {
      ZfpRoundTrip z =
          zfpRoundTrip(slabs, counts, {ZfpSettings::Mode::kAccuracy, std::ldexp(1.0, k)}, nt);
      bytesAt[k] = static_cast<std::int64_t>(z.stream.size());
      return z;
    };
    auto bytes = [&](int k) {
      if (!bytesAt.count(k)) codeAt(k);
      return bytesAt[k];
    };
    auto bitsOf = [&](std::int64_t b) { return 8.0 * static_cast<double>(b) / samplesAll; };
    auto measure = [&](TimeVaryingModel candidate, const std::string& what) {
      return measureOnSeries(candidate, series, times, [&](int s) {
        progress(0.85, "budget: measuring " + what + " on " + series.stepName(s));
      });
    };
    auto errors = [&](int k) {
      if (!errorsAt.count(k))
        errorsAt[k] = measure(TimeVaryingModel(spatial, axis, codeAt(k).decoded),
                              "tolerance " + tolerancePhrase(k));
      return errorsAt[k];
    };
    const double range = vmax - vmin;
    int k = 0;
    std::ostringstream note;
    if (budget.kind == BudgetKind::kBitsPerSample) {
      const auto cap = static_cast<std::int64_t>(std::floor(budget.value * samplesAll / 8.0));
      k = smallestPassing(lo, hi, [&](int e) { return bytes(e) <= cap; });
      if (k > hi)
        throw Error("no zfp tolerance codes the " + dimsText(counts) + " x " + std::to_string(nt) +
                    " model of " + series.source() + " within " + numberText(budget.value) +
                    " bits/sample (at " + tolerancePhrase(hi) + ": " +
                    numberText(bitsOf(bytes(hi)), "%.3f") +
                    "); raise the budget or give fewer control points (--ctrl, --time-ctrl)");
      note << "zfp tolerance " << tolerancePhrase(k) << ": the smallest within "
           << numberText(budget.value) << " bits/sample";
    } else {
      const double target = budget.kind == BudgetKind::kPsnr
                                ? (range > 0.0 ? range / std::pow(10.0, budget.value / 20.0) : 0.0)
                                : budget.value;
      const SampleErrors fitted = measure(TimeVaryingModel(spatial, axis, slabs), "the fit");
      const std::string wanted = budget.kind == BudgetKind::kPsnr
                                     ? "--psnr " + numberText(budget.value) + " dB"
                                     : "--rms-error " + numberText(budget.value);
      if (fitted.rms > target)
        throw Error("the " + dimsText(counts) + " x " + std::to_string(nt) + " model of " +
                    series.source() + " reaches " + numberText(psnrOf(range, fitted.rms), "%.2f") +
                    " dB (RMS error " + numberText(fitted.rms) + ") before any coding, short of " +
                    wanted + ": give more control points (--ctrl, --time-ctrl) or less smoothing");
      k = largestPassing(lo, hi, [&](int e) { return errors(e).rms <= target; });
      if (k < lo)
        throw Error("zfp misses " + wanted + " at every tolerance down to " + tolerancePhrase(lo) +
                    "; --coding lossless keeps the fit's " +
                    numberText(psnrOf(range, fitted.rms), "%.2f") + " dB");
      measured = errorsAt[k];
      note << "zfp tolerance " << tolerancePhrase(k) << ": the largest that meets " << wanted
           << " (the fit alone: " << numberText(psnrOf(range, fitted.rms), "%.2f") << " dB)";
    }
    note << "; tried:";
    for (const auto& [e, b] : bytesAt) {
      note << " 2^" << e << " " << numberText(bitsOf(b), "%.3f") << " bits/sample";
      if (errorsAt.count(e))
        note << " " << numberText(psnrOf(range, errorsAt[e].rms), "%.2f") << " dB";
      note << ";";
    }
    note << " (a series' budget searches the tolerance; the control grid is the given one)";
    codingNote = note.str();
    coding.tolerance = std::ldexp(1.0, k);
  } else if (coding.coder == ControlCoder::kZfp && options.coding.tolerance <= 0.0 &&
             (dequantize || adaptive)) {
    // The room the fits leave within the bound (half a step, or --max-error), less a margin for
    // the rounding of the time solve: zfp moves a control point, hence the model, by at most the
    // tolerance.
    const double bound =
        dequantize ? 0.5 * dq.step : options.adaptive->maxRelativeError * (vmax - vmin);
    const double deviation = dequantize ? dq.maxDeviation : adaptiveReport.maxError;
    const std::string what = dequantize ? "half a step" : "the error bound";
    const double room = bound - deviation - 1e-5 * std::max(vmax - vmin, bound);
    if (room > 0.0) {
      coding.tolerance = std::ldexp(1.0, static_cast<int>(std::floor(std::log2(room))));
      codingNote = "zfp tolerance " + numberText(coding.tolerance) +
                   ": the room the fits leave within " + what + " (they keep " +
                   numberText(deviation) + ")";
    } else {
      coding.coder = ControlCoder::kLossless;
      codingNote = "lossless: the fits leave no room within " + what + " for zfp";
    }
  } else if (coding.coder == ControlCoder::kZfp) {
    coding.tolerance = options.coding.tolerance > 0.0
                           ? options.coding.tolerance
                           : defaultTolerance(first.sampleType, vmax - vmin);
    if (options.coding.tolerance <= 0.0)
      codingNote = "zfp tolerance " + std::to_string(coding.tolerance) +
                   (isIntegerSampleType(first.sampleType)
                        ? " (integer samples: a model within 0.25 of them rounds back)"
                        : " (1e-5 of the value range)");
  }
  if (coding.coder == ControlCoder::kZfp) {
    progress(0.85, "coding");
    ZfpRoundTrip z =
        zfpRoundTrip(slabs, counts, {ZfpSettings::Mode::kAccuracy, coding.tolerance}, nt);
    slabs = std::move(z.decoded);
    coded = std::make_shared<const std::string>(std::move(z.stream));
  }

  TimeVaryingModel model(spatial, axis, std::move(slabs));
  if (coding.coder != ControlCoder::kFloat32) {
    if (!coded) {
      const std::span<const float> all = model.controlPoints();
      coded = std::make_shared<const std::string>(encodeControlPoints(all, counts, coding, nt));
    }
    model.setControlCoding(coding, coded);
  }

  // Pass 2: the stored model against every sample of every step (unless a search measured it).
  if (!measured)
    measured = measureOnSeries(model, series, times, [&](int s) {
      progress(0.85 + 0.15 * s / steps, "measuring " + series.stepName(s));
    });
  progress(1.0, "done");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Provenance& p = model.provenance();
  p.maxError = measured->max;
  p.rmsError = measured->rms;
  p.fitSeconds = seconds;
  p.smoothing = dequantize ? dq.lambda : lambda;

  if (report) {
    FitReport& r = *report;
    r = FitReport();
    r.source = prov.source;
    r.samples = first.dims;
    r.degree = shape.spline().degrees();
    r.controlCounts = counts;
    r.seconds = seconds;
    r.valueMin = vmin;
    r.valueMax = vmax;
    r.maxError = p.maxError;
    r.rmsError = p.rmsError;
    r.inputBytes = inputBytes;
    r.modelBytes = modelFileSize(model);
    r.encoder = prov.encoder;
    r.field = first.fieldName;
    r.smoothing = dequantize ? 0.0 : lambda;
    if (options.autoSmoothing) {
      r.noiseEstimate = choice.noiseRms;
      r.smoothingNote = choice.note;
    }
    if (adaptive) {
      r.rounds = adaptiveReport.rounds;
      r.targetRelativeError = options.adaptive->maxRelativeError;
      r.reachedTarget = r.maxRelativeError() <= r.targetRelativeError;
      r.stopReason = adaptiveReport.stopReason;
      if (!r.reachedTarget && (r.stopReason.empty() || adaptiveReport.reachedTarget))
        r.stopReason = "the coded model misses the bound";
    }
    if (dequantize) {
      r.dequantizeStep = dq.step;
      r.dequantizeLambda = dq.lambda;
      r.dequantizeIterations = dq.iterations;
      r.dequantizeConverged = dq.converged;
      r.dequantizeEdgeShare =
          dq.edgeSamples / static_cast<double>(std::max<std::int64_t>(dq.samples, 1));
      r.dequantizeSeconds = dq.seconds;
    }
    r.coding = controlCoderName(coding.coder);
    r.codingTolerance = coding.tolerance;
    r.codingNote = codingNote;
    r.timeSteps = steps;
    r.timeDegree = pt;
    r.timeControlCount = nt;
  }
  return model;
}

}  // namespace mfadvr
