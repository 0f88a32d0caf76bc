#include "core/encode/TimeSeriesEncoder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/encode/AxisFit.h"
#include "core/encode/KnotPlacement.h"
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

void refuseUnsupported(const EncodeOptions& o) {
  auto refuse = [](const char* what) {
    throw Error(std::string(what) +
                " is not available for time series yet (fixed control counts, --smooth LAMBDA and "
                "the codings are)");
  };
  if (o.adaptive) refuse("--max-error");
  if (o.autoSmoothing) refuse("--smooth auto");
  if (o.dequantizeStep) refuse("--dequantize");
  if (o.coding.budget.kind != BudgetKind::kNone) refuse("a size or error budget");
}

// The zfp tolerance of the 4-D control points when none is given.
double defaultTolerance(const std::string& sampleType, double range) {
  if (isIntegerSampleType(sampleType)) return kIntegerDefaultTolerance;
  return std::max(kFloatDefaultRelativeTolerance * range, 1e-30);
}

}  // namespace

std::int64_t timeSeriesPeakBytes(const Index3& dims, const Index3& counts, std::int64_t slabs) {
  const std::int64_t controls = 4 * counts[0] * counts[1] * counts[2] * slabs;
  return controls + structuredFitPeakBytes(dims, counts) + 4 * counts[0] * counts[1] * counts[2];
}

TimeVaryingModel encodeTimeSeries(const VolumeSeries& series, const EncodeOptions& options,
                                  const TimeSeriesOptions& timeOptions, FitReport* report,
                                  std::vector<std::string>* notes) {
  const auto start = std::chrono::steady_clock::now();
  refuseUnsupported(options);
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

  TimeAxis axis;
  axis.begin = times.front();
  axis.end = times.back();
  axis.steps = times;
  std::vector<double> params(times.size());
  for (size_t s = 0; s < times.size(); ++s) params[s] = axis.toParameter(times[s]);
  params.back() = 1.0;
  axis.knots = knotsForParameters(pt, nt, params);
  const double lambda = options.smoothing.value_or(0.0);
  validateSmoothing(lambda);
  const AxisFitter timeFit(sampleAxisAt(axis.knots, params), lambda);
  const AxisSampling& rows = timeFit.sampling();

  auto progress = [&](double f, const std::string& stage) {
    if (options.progress) options.progress(f, stage);
  };

  // Pass 1: each step's spatial fit adds its row of the time basis to B = N_t^T C.
  StructuredFitOptions fit;
  fit.degree = options.degree;
  fit.controlCounts = options.controlCounts;
  fit.smoothing = lambda;
  StructuredGrid first;
  std::array<KnotVector, 3> knots;
  std::vector<float> slabs;
  std::int64_t m = 0;
  Model shape;
  double vmin = 0.0, vmax = 0.0;
  std::int64_t inputBytes = 0;
  for (int s = 0; s < steps; ++s) {
    progress(0.8 * s / steps, "fitting " + series.stepName(s));
    StructuredGrid grid = series.load(s);
    if (s == 0) {
      grid.validateLayout();
      knots = knotsOfFit(grid, fit);
      Index3 counts{};
      for (int a = 0; a < 3; ++a) counts[a] = knots[a].controlCount();
      m = counts[0] * counts[1] * counts[2];
      requireMemory(timeSeriesPeakBytes(grid.dims, counts, nt),
                    "a " + dimsText(counts) + " x " + std::to_string(nt) +
                        " model of a series of " + dimsText(grid.dims) +
                        " volumes (fewer control points, --ctrl or --time-ctrl, need less)");
      slabs.assign(static_cast<size_t>(m * nt), 0.0f);
      first = grid;
      first.values.clear();
      first.values.shrink_to_fit();
      // What the reader said of the input (a time unit, a placement), once for the series.
      if (notes) notes->insert(notes->end(), grid.notes.begin(), grid.notes.end());
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
    const Model step = fitStructuredWithKnots(grid, knots, fit);
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

  // The coding of the 4-D array.
  ControlCoding coding;
  coding.coder = !options.coding.coder && timeOptions.zfpForIntegerSamples &&
                         isIntegerSampleType(first.sampleType)
                     ? ControlCoder::kZfp
                     : resolvedCoder(options.coding);
  std::shared_ptr<const std::string> coded;
  std::string codingNote;
  if (coding.coder == ControlCoder::kZfp) {
    coding.tolerance = options.coding.tolerance > 0.0
                           ? options.coding.tolerance
                           : defaultTolerance(first.sampleType, vmax - vmin);
    if (options.coding.tolerance <= 0.0)
      codingNote = "zfp tolerance " + std::to_string(coding.tolerance) +
                   (isIntegerSampleType(first.sampleType)
                        ? " (integer samples: a model within 0.25 of them rounds back)"
                        : " (1e-5 of the value range)");
    progress(0.85, "coding");
    ZfpRoundTrip z = zfpRoundTrip(slabs, shape.spline().counts(),
                                  {ZfpSettings::Mode::kAccuracy, coding.tolerance}, nt);
    slabs = std::move(z.decoded);
    coded = std::make_shared<const std::string>(std::move(z.stream));
  }

  Provenance prov = shape.provenance();
  prov.source = series.source();
  prov.inputBytes = inputBytes;
  prov.encoder = lambda > 0.0 ? "time-series-smoothing" : "time-series-least-squares";
  TimeVaryingModel model(Model(shape.spline(), shape.domain(), vmin, vmax, prov), axis,
                         std::move(slabs));
  if (coding.coder != ControlCoder::kFloat32) {
    if (!coded) {
      const std::span<const float> all = model.controlPoints();
      coded = std::make_shared<const std::string>(
          encodeControlPoints(all, shape.spline().counts(), coding, nt));
    }
    model.setControlCoding(coding, coded);
  }

  // Pass 2: the stored model against every sample of every step.
  double maxErr = 0.0, sumSq = 0.0;
  std::int64_t samples = 0;
  for (int s = 0; s < steps; ++s) {
    progress(0.85 + 0.15 * s / steps, "measuring " + series.stepName(s));
    const StructuredGrid grid = series.load(s);
    const SampleErrors e = errorsOnGrid(model.at(times[static_cast<size_t>(s)]).spline(), grid);
    maxErr = std::max(maxErr, e.max);
    sumSq += e.rms * e.rms * static_cast<double>(grid.sampleCount());
    samples += grid.sampleCount();
  }
  progress(1.0, "done");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Provenance& p = model.provenance();
  p.maxError = maxErr;
  p.rmsError = std::sqrt(sumSq / static_cast<double>(samples));
  p.fitSeconds = seconds;
  p.smoothing = lambda;

  if (report) {
    FitReport& r = *report;
    r = FitReport();
    r.source = prov.source;
    r.samples = first.dims;
    r.degree = shape.spline().degrees();
    r.controlCounts = shape.spline().counts();
    r.seconds = seconds;
    r.valueMin = vmin;
    r.valueMax = vmax;
    r.maxError = p.maxError;
    r.rmsError = p.rmsError;
    r.inputBytes = inputBytes;
    r.modelBytes = modelFileSize(model);
    r.encoder = prov.encoder;
    r.field = first.fieldName;
    r.smoothing = lambda;
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
