#include "core/encode/StructuredEncoder.h"

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <sstream>
#include <type_traits>

#include "core/encode/AxisFit.h"
#include "core/encode/KnotPlacement.h"
#include "core/model/ModelFile.h"
#include "core/spline/BasisFunctions.h"
#include "core/spline/DerivativePenalty.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "core/util/UtcTime.h"

namespace mfadvr {
namespace {

const char* axisName(int a) {
  return a == 0 ? "x" : (a == 1 ? "y" : "z");
}

// Applies a linear map along the fastest axis of an (A, B, C) array and writes the result as a
// (B, C, outLen) array, so that three passes visit x, y, z and return to x-fastest order.
// `op(slab, lines, out)` maps `lines` contiguous input lines of length A (one (·, ·, c) slab) to
// an outLen x lines column-major matrix.
template <class SlabOp>
void passAlongFastest(const std::vector<double>& in, const Index3& dims, std::int64_t outLen,
                      std::vector<double>& out, const SlabOp& op) {
  const std::int64_t A = dims[0], B = dims[1], C = dims[2];
  out.assign(static_cast<size_t>(B * C * outLen), 0.0);
  tbb::parallel_for(std::int64_t(0), C, [&](std::int64_t c) {
    Eigen::Map<const Eigen::MatrixXd> slab(in.data() + c * A * B, A, B);
    Eigen::MatrixXd result(outLen, B);
    op(slab, result);
    for (std::int64_t o = 0; o < outLen; ++o) {
      double* dst = out.data() + B * (c + C * o);
      for (std::int64_t b = 0; b < B; ++b) dst[b] = result(o, b);
    }
  });
}

// The control points of the separable fit, float32, x fastest. x and y are fitted plane by plane
// (both lie within a z plane) into one float array of n0 x n1 x N2 coefficients; z is then
// fitted along its rows a block at a time and written back in place (a row's n2 results take the
// places of its first n2 values), so that besides the samples only that array lives: 4 bytes
// per sample instead of two double arrays (16). Every solve runs in double; the intermediate
// coefficients are rounded to float once, as the stored model is.
std::vector<float> fitControlPoints(const GridSamples& samples,
                                    const std::array<AxisSampling, 3>& sampling, double smoothing,
                                    const std::function<void(double, const char*)>& progress) {
  const std::int64_t N0 = samples.dims()[0], N1 = samples.dims()[1], N2 = samples.dims()[2];
  const std::int64_t n0 = sampling[0].controlCount, n1 = sampling[1].controlCount,
                     n2 = sampling[2].controlCount, plane = n0 * n1;
  const AxisFitter fitX(sampling[0], smoothing), fitY(sampling[1], smoothing);
  std::vector<float> ctrl(static_cast<size_t>(plane * N2));
  progress(0.0, "fit x, y");
  tbb::parallel_for(std::int64_t(0), N2, [&](std::int64_t k) {
    std::vector<float> scratch;
    const Eigen::MatrixXd planeSamples =
        Eigen::Map<const Eigen::MatrixXf>(samples.plane(k, scratch), N0, N1).cast<double>();
    Eigen::MatrixXd alongX(n0, N1);
    fitX(Eigen::Map<const Eigen::MatrixXd>(planeSamples.data(), N0, N1), alongX);
    const Eigen::MatrixXd yLines = alongX.transpose();  // N1 x n0: one y line per column
    Eigen::MatrixXd alongY(n1, n0);
    fitY(Eigen::Map<const Eigen::MatrixXd>(yLines.data(), N1, n0), alongY);
    float* dst = ctrl.data() + k * plane;
    for (std::int64_t j = 0; j < n1; ++j)
      for (std::int64_t i = 0; i < n0; ++i) dst[i + n0 * j] = static_cast<float>(alongY(j, i));
  });
  progress(0.5, "fit z");
  const AxisFitter fitZ(sampling[2], smoothing);
  constexpr std::int64_t kRows = 64;  // z lines per task: kRows consecutive floats per plane
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, plane, kRows), [&](const auto& r) {
    const std::int64_t p0 = r.begin(), rows = r.size();
    Eigen::MatrixXd lines(N2, rows);
    for (std::int64_t k = 0; k < N2; ++k)
      for (std::int64_t b = 0; b < rows; ++b) lines(k, b) = ctrl[p0 + b + plane * k];
    Eigen::MatrixXd alongZ(n2, rows);
    fitZ(Eigen::Map<const Eigen::MatrixXd>(lines.data(), N2, rows), alongZ);
    for (std::int64_t k = 0; k < n2; ++k)
      for (std::int64_t b = 0; b < rows; ++b)
        ctrl[p0 + b + plane * k] = static_cast<float>(alongZ(k, b));
  });
  if (n2 < N2) {
    ctrl.resize(static_cast<size_t>(plane * n2));
    ctrl.shrink_to_fit();
  }
  return ctrl;
}

Index3 rotate(const Index3& d, std::int64_t newLast) {
  return {d[1], d[2], newLast};
}

// The spline with control points `ctrl` (n, x fastest) at the samples of `sampling`, separably.
std::vector<double> evaluateOnSamples(const std::array<AxisSampling, 3>& sampling,
                                      std::span<const float> ctrl, Index3 dims) {
  std::vector<double> recon(ctrl.begin(), ctrl.end()), tmp;
  for (int a = 0; a < 3; ++a) {
    passAlongFastest(recon, dims, sampling[a].samples, tmp, AxisEvaluator(sampling[a]));
    recon.swap(tmp);
    dims = rotate(dims, sampling[a].samples);
  }
  return recon;
}

// The samples with z in [zBegin, zEnd) only (x fastest), from the control planes they depend
// on: first[zBegin] .. first[zEnd - 1] + p. The same sums as the whole evaluation, bit for bit.
std::vector<double> evaluateSlab(std::array<AxisSampling, 3> sampling, std::span<const float> ctrl,
                                 const Index3& n, std::int64_t zBegin, std::int64_t zEnd) {
  if (zBegin == 0 && zEnd == sampling[2].samples) return evaluateOnSamples(sampling, ctrl, n);
  AxisSampling& z = sampling[2];
  const int p = z.degree, w = p + 1;
  const int c0 = z.first[static_cast<size_t>(zBegin)];
  const int c1 = z.first[static_cast<size_t>(zEnd - 1)] + p;
  AxisSampling slab;
  slab.degree = p;
  slab.controlCount = c1 - c0 + 1;
  slab.samples = zEnd - zBegin;
  for (std::int64_t i = zBegin; i < zEnd; ++i) {
    slab.first.push_back(z.first[static_cast<size_t>(i)] - c0);
    const double* wi = &z.weights[static_cast<size_t>(i * w)];
    slab.weights.insert(slab.weights.end(), wi, wi + w);
  }
  z = std::move(slab);
  const size_t plane = static_cast<size_t>(n[0] * n[1]);
  return evaluateOnSamples(sampling,
                           ctrl.subspan(c0 * plane, static_cast<size_t>(z.controlCount) * plane),
                           {n[0], n[1], z.controlCount});
}

// z slabs of about 2^22 samples (32 MB of doubles), at least 16 planes so that the control
// planes a slab shares with its neighbours (p of them) cost little.
std::int64_t slabPlanes(const Index3& dims) {
  const std::int64_t plane = std::max<std::int64_t>(1, dims[0] * dims[1]);
  return std::clamp<std::int64_t>((std::int64_t(1) << 22) / plane, 16,
                                  std::max<std::int64_t>(1, dims[2]));
}

// Calls visit(zBegin, zEnd, values) for consecutive z slabs covering the samples of `sampling`;
// a visit that returns false ends the walk (a visit returning nothing never does).
template <class Visit>
void forEachSlab(const std::array<AxisSampling, 3>& sampling, std::span<const float> ctrl,
                 const Index3& n, const Visit& visit) {
  const Index3 dims{sampling[0].samples, sampling[1].samples, sampling[2].samples};
  const std::int64_t planes = slabPlanes(dims);
  for (std::int64_t z0 = 0; z0 < dims[2]; z0 += planes) {
    const std::int64_t z1 = std::min(dims[2], z0 + planes);
    if constexpr (std::is_same_v<decltype(visit(z0, z1, std::vector<double>())), bool>) {
      if (!visit(z0, z1, evaluateSlab(sampling, ctrl, n, z0, z1))) return;
    } else {
      visit(z0, z1, evaluateSlab(sampling, ctrl, n, z0, z1));
    }
  }
}

}  // namespace

std::vector<double> splineOnGrid(const TensorBSpline& spline, const Index3& dims) {
  return splineOnGrid(spline, dims, 0, dims[2]);
}

std::vector<double> splineOnGrid(const TensorBSpline& spline, const Index3& dims,
                                 std::int64_t zBegin, std::int64_t zEnd) {
  if (zBegin < 0 || zEnd > dims[2] || zBegin >= zEnd)
    throw Error("splineOnGrid: empty or out-of-range z slab");
  std::array<AxisSampling, 3> sampling;
  for (int a = 0; a < 3; ++a) sampling[a] = sampleAxis(spline.knots(a), dims[a]);
  return evaluateSlab(std::move(sampling), spline.controlPoints(), spline.counts(), zBegin, zEnd);
}

std::optional<SampleErrors> errorsOnGridWithin(const TensorBSpline& spline,
                                               const StructuredGrid& grid, double limit) {
  std::array<AxisSampling, 3> sampling;
  for (int a = 0; a < 3; ++a) sampling[a] = sampleAxis(spline.knots(a), grid.dims[a]);
  SampleErrors e;
  double sumSq = 0.0;
  forEachSlab(sampling, spline.controlPoints(), spline.counts(),
              [&](std::int64_t z0, std::int64_t, const std::vector<double>& recon) {
                const float* v = grid.values.data() + z0 * grid.dims[0] * grid.dims[1];
                for (size_t i = 0; i < recon.size(); ++i) {
                  const double d = std::abs(recon[i] - v[i]);
                  e.max = std::max(e.max, d);
                  sumSq += d * d;
                }
                return e.max <= limit;
              });
  if (!(e.max <= limit)) return std::nullopt;
  const auto count = static_cast<double>(grid.sampleCount());
  e.rms = count > 0 ? std::sqrt(sumSq / count) : 0.0;
  return e;
}

SampleErrors errorsOnGrid(const TensorBSpline& spline, const StructuredGrid& grid) {
  return *errorsOnGridWithin(spline, grid, std::numeric_limits<double>::infinity());
}

std::array<std::vector<double>, 3> curveSpanErrors(const StructuredGrid& grid,
                                                   const std::array<KnotVector, 3>& knots) {
  std::array<std::vector<double>, 3> result;
  std::vector<double> data(grid.values.begin(), grid.values.end()), rotated;
  Index3 dims = grid.dims;  // axis a is fastest in `data` at step a
  for (int a = 0; a < 3; ++a) {
    const AxisSampling sampling = sampleAxis(knots[a], dims[0]);
    const AxisFitter fitter(sampling);
    const AxisEvaluator evaluator(sampling);
    const std::int64_t A = dims[0], B = dims[1], C = dims[2];
    const size_t spans = static_cast<size_t>(knots[a].controlCount() - knots[a].degree());
    std::vector<std::vector<double>> perSlab(static_cast<size_t>(C));
    tbb::parallel_for(std::int64_t(0), C, [&](std::int64_t c) {
      Eigen::Map<const Eigen::MatrixXd> slab(data.data() + c * A * B, A, B);
      Eigen::MatrixXd coeffs(knots[a].controlCount(), B), recon(A, B);
      fitter(slab, coeffs);
      evaluator(Eigen::Map<const Eigen::MatrixXd>(coeffs.data(), coeffs.rows(), B), recon);
      std::vector<double>& worst = perSlab[static_cast<size_t>(c)];
      worst.assign(spans, 0.0);
      for (std::int64_t b = 0; b < B; ++b)
        for (std::int64_t i = 0; i < A; ++i) {
          double& w = worst[static_cast<size_t>(sampling.first[i])];
          w = std::max(w, std::abs(recon(i, b) - slab(i, b)));
        }
    });
    result[a].assign(spans, 0.0);
    for (const auto& w : perSlab)
      for (size_t s = 0; s < spans; ++s) result[a][s] = std::max(result[a][s], w[s]);
    if (a < 2) {
      passAlongFastest(
          data, dims, A, rotated,
          [](const Eigen::Map<const Eigen::MatrixXd>& in, Eigen::MatrixXd& out) { out = in; });
      data.swap(rotated);
      dims = rotate(dims, A);
    }
  }
  return result;
}

void validateSmoothing(double lambda) {
  if (!(lambda >= 0.0) || !(lambda <= kMaxGridSmoothing)) {
    std::ostringstream m;
    m << "the smoothing weight must be a number in 0.." << kMaxGridSmoothing << ", got " << lambda;
    if (lambda > kMaxGridSmoothing)
      m << " (above it only the polynomials of the model's degree are left)";
    throw Error(m.str());
  }
}

std::int64_t structuredFitPeakBytes(const Index3& N, const Index3& n) {
  const std::int64_t samples = N[0] * N[1] * N[2], ctrl = n[0] * n[1] * n[2];
  // fitControlPoints: one float array of n0 x n1 x N2 (and, when n2 < N2, its shrunk copy), and
  // per thread one plane's double matrices.
  const std::int64_t threads = tbb::info::default_concurrency();
  const std::int64_t fit = 4 * n[0] * n[1] * N[2] + (n[2] < N[2] ? 4 * ctrl : 0) +
                           threads * 8 * (N[0] * N[1] + 3 * n[0] * N[1]);
  // The errors: the control points and one slab of evaluations.
  const std::int64_t errors = 4 * ctrl + 16 * slabPlanes(N) * N[0] * N[1];
  return std::int64_t(sizeof(float)) * samples + std::max(fit, errors);
}

double effectiveParameters(const std::array<KnotVector, 3>& knots, const Index3& dims,
                           double smoothing) {
  validateSmoothing(smoothing);
  double trace = 1.0;
  for (int a = 0; a < 3; ++a)
    trace *= AxisFitter(sampleAxis(knots[a], dims[a]), smoothing).hatTrace();
  return trace;
}

Index3 resolveControlCounts(const StructuredGrid& grid, const StructuredFitOptions& options) {
  validateSmoothing(options.smoothing);
  Index3 n{};
  for (int a = 0; a < 3; ++a) {
    const int p = options.degree[a];
    const std::int64_t N = grid.dims[a];
    std::ostringstream m;
    if (p < 1 || p > kMaxDegree) {
      m << "degree " << p << " on axis " << axisName(a) << " is outside 1.." << kMaxDegree;
      throw Error(m.str());
    }
    if (N < 2) {
      m << "the grid has " << N << " sample on axis " << axisName(a)
        << "; a 3-D fit needs at least 2";
      throw Error(m.str());
    }
    n[a] = options.controlCounts[a] == 0 ? N : options.controlCounts[a];
    if (n[a] > N) {
      m << n[a] << " control points on axis " << axisName(a) << " exceed its " << N
        << " samples; use at most " << N;
      throw Error(m.str());
    }
    if (n[a] < p + 1) {
      m << n[a] << " control points on axis " << axisName(a) << " are too few for degree " << p
        << "; use at least " << p + 1;
      if (N < p + 1) m << " (the axis has only " << N << " samples: lower the degree)";
      throw Error(m.str());
    }
  }
  return n;
}

std::array<KnotVector, 3> knotsOfFit(const StructuredGrid& layout,
                                     const StructuredFitOptions& options) {
  const Index3 n = resolveControlCounts(layout, options);
  std::array<KnotVector, 3> knots;
  for (int a = 0; a < 3; ++a)
    knots[a] = knotsForSamples(options.degree[a], static_cast<int>(n[a]), layout.dims[a]);
  return knots;
}

struct GridSmoother::Axes {
  std::array<AxisSampling, 3> sampling;
  std::array<std::unique_ptr<AxisFitter>, 3> fitters;
};

GridSmoother::GridSmoother(const std::array<KnotVector, 3>& knots, const Index3& dims,
                           double smoothing)
    : dims_(dims), axes_(std::make_unique<Axes>()) {
  validateSmoothing(smoothing);
  for (int a = 0; a < 3; ++a) {
    if (knots[a].controlCount() > dims[a])
      throw Error("more control points than samples along " + std::string(axisName(a)));
    axes_->sampling[a] = sampleAxis(knots[a], dims[a]);
    axes_->fitters[a] = std::make_unique<AxisFitter>(axes_->sampling[a], smoothing);
  }
}

GridSmoother::~GridSmoother() = default;

void GridSmoother::apply(std::vector<double>& values) const {
  if (static_cast<std::int64_t>(values.size()) != dims_[0] * dims_[1] * dims_[2])
    throw Error("GridSmoother: the values do not fill the grid");
  Index3 dims = dims_;
  std::vector<double> tmp;
  for (int a = 0; a < 3; ++a) {
    const AxisSampling& s = axes_->sampling[a];
    const AxisFitter& fit = *axes_->fitters[a];
    const AxisEvaluator evaluate(s);
    passAlongFastest(
        values, dims, s.samples, tmp,
        [&](const Eigen::Map<const Eigen::MatrixXd>& lines, Eigen::MatrixXd& out) {
          Eigen::MatrixXd coeffs(s.controlCount, lines.cols());
          fit(lines, coeffs);
          evaluate(Eigen::Map<const Eigen::MatrixXd>(coeffs.data(), coeffs.rows(), coeffs.cols()),
                   out);
        });
    values.swap(tmp);
    dims = rotate(dims, s.samples);
  }
}

Model fitStructured(const StructuredGrid& grid, const StructuredFitOptions& options,
                    FitReport* report) {
  grid.validate();
  return fitStructuredWithKnots(grid, GridSamples(grid), knotsOfFit(grid, options), options, report,
                                nullptr, /*validated=*/true);
}

Model fitStructured(const StructuredGrid& layout, const GridSamples& samples,
                    const StructuredFitOptions& options, FitReport* report) {
  return fitStructuredWithKnots(layout, samples, knotsOfFit(layout, options), options, report);
}

Model fitStructuredWithKnots(const StructuredGrid& grid, std::array<KnotVector, 3> knots,
                             const StructuredFitOptions& options, FitReport* report,
                             std::array<std::vector<double>, 3>* spanErrors) {
  grid.validate();
  return fitStructuredWithKnots(grid, GridSamples(grid), std::move(knots), options, report,
                                spanErrors, /*validated=*/true);
}

// `grid` gives dims, box and provenance; its values are not read (they are in `samples`).
Model fitStructuredWithKnots(const StructuredGrid& grid, const GridSamples& samples,
                             std::array<KnotVector, 3> knots, const StructuredFitOptions& options,
                             FitReport* report, std::array<std::vector<double>, 3>* spanErrors,
                             bool validated) {
  const auto start = std::chrono::steady_clock::now();
  if (!validated) {
    grid.validateLayout();
    samples.validateFor(grid);
  }
  validateSmoothing(options.smoothing);
  Index3 n{};
  Degree3 degree{};
  for (int a = 0; a < 3; ++a) {
    degree[a] = knots[a].degree();
    n[a] = knots[a].controlCount();
    if (n[a] > grid.dims[a] || n[a] < degree[a] + 1) {
      std::ostringstream m;
      m << n[a] << " control points of degree " << degree[a] << " on axis " << axisName(a)
        << " do not fit its " << grid.dims[a] << " samples";
      throw Error(m.str());
    }
  }
  // The samples are held already; the rest is allocated from here on.
  requireMemory(
      structuredFitPeakBytes(grid.dims, n) - std::int64_t(sizeof(float)) * grid.sampleCount(),
      "fitting " + std::to_string(n[0]) + "x" + std::to_string(n[1]) + "x" + std::to_string(n[2]) +
          " control points to " + std::to_string(grid.dims[0]) + "x" +
          std::to_string(grid.dims[1]) + "x" + std::to_string(grid.dims[2]) +
          " samples (fewer control points, --ctrl, or --blocks need less)");
  auto progress = [&](double f, const char* stage) {
    if (options.progress) options.progress(f, stage);
  };

  std::array<AxisSampling, 3> sampling;
  for (int a = 0; a < 3; ++a) sampling[a] = sampleAxis(knots[a], grid.dims[a]);
  std::vector<float> ctrl =
      fitControlPoints(samples, sampling, options.smoothing,
                       [&](double f, const char* stage) { progress(0.75 * f, stage); });

  // Error of the stored (float32) model at every input sample, z slab by z slab.
  progress(0.75, "error");
  double maxErr = 0.0, sumSq = 0.0;
  std::vector<float> scratch;
  double vmin = *samples.values(0, 1, scratch), vmax = vmin;
  if (spanErrors)
    for (int a = 0; a < 3; ++a) (*spanErrors)[a].assign(static_cast<size_t>(n[a] - degree[a]), 0.0);
  forEachSlab(
      sampling, ctrl, n, [&](std::int64_t z0, std::int64_t z1, const std::vector<double>& recon) {
        const std::int64_t planeSize = grid.dims[0] * grid.dims[1];
        const float* slab = samples.values(z0 * planeSize, (z1 - z0) * planeSize, scratch);
        size_t r = 0;
        for (std::int64_t z = z0; z < z1; ++z)
          for (std::int64_t y = 0; y < grid.dims[1]; ++y)
            for (std::int64_t x = 0; x < grid.dims[0]; ++x, ++r) {
              const double v = slab[r];
              const double e = std::abs(recon[r] - v);
              maxErr = std::max(maxErr, e);
              sumSq += e * e;
              vmin = std::min(vmin, v);
              vmax = std::max(vmax, v);
              if (spanErrors) {
                // sampling.first is the span's first control point: span index - degree.
                const std::int64_t at[3] = {x, y, z};
                for (int a = 0; a < 3; ++a) {
                  double& worst = (*spanErrors)[a][static_cast<size_t>(sampling[a].first[at[a]])];
                  worst = std::max(worst, e);
                }
              }
            }
      });
  const double rms = std::sqrt(sumSq / static_cast<double>(grid.sampleCount()));
  progress(1.0, "done");

  Provenance prov;
  prov.source = grid.source;
  prov.field = grid.fieldName;
  prov.fieldAssociation = grid.fieldAssociation;
  prov.sampleType = grid.sampleType;
  prov.sampleDims = grid.dims;
  prov.inputBytes = grid.inputBytes;
  prov.encoder = options.smoothing > 0.0 ? "structured-smoothing" : "structured-least-squares";
  prov.smoothing = options.smoothing;
  prov.created = utcNow();
  prov.toolVersion = MFADVR_VERSION;
  prov.maxError = maxErr;
  prov.rmsError = rms;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  prov.fitSeconds = seconds;

  Model model(TensorBSpline(std::move(knots), std::move(ctrl)),
              DomainBox{grid.boxMin(), grid.boxMax()}, vmin, vmax, std::move(prov));
  if (report) *report = fitReportOf(model);
  return model;
}

}  // namespace mfadvr
