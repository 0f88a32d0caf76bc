#include "core/encode/Dequantizer.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/encode/StructuredEncoder.h"
#include "core/util/Error.h"

namespace mfadvr {

namespace {

// max over i of f(i), over all cores.
template <class F>
double parallelMax(std::size_t n, const F& f) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double m) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) m = std::max(m, f(i));
        return m;
      },
      [](double a, double b) { return std::max(a, b); });
}

}  // namespace

DequantizeResult dequantizeTargets(const StructuredGrid& grid,
                                   const std::array<KnotVector, 3>& knots,
                                   const DequantizeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const double step = options.step;
  if (!(step > 0.0) || !std::isfinite(step))
    throw Error("--dequantize: the step must be positive and finite, got " + std::to_string(step));
  if (!(options.slack >= 0.0 && options.slack < 1.0))
    throw Error("--dequantize: the slack must lie in [0, 1)");
  const std::size_t n = grid.values.size();
  // Samples off the step's lattice were not quantized with it.
  const double offLattice = parallelMax(n, [&](std::size_t i) {
    const double q = grid.values[i] / step;
    return std::abs(q - std::nearbyint(q));
  });
  if (offLattice > 1e-3)
    throw Error("--dequantize " + std::to_string(step) +
                ": the samples are not multiples of the step (one is " +
                std::to_string(offLattice) +
                " of a step away); give the step the data were quantized with");

  const double h = 0.5 * step * (1.0 - options.slack);
  const GridSmoother smoother(knots, grid.dims, options.smoothing);
  std::vector<double> z(grid.values.begin(), grid.values.end()), u(n, 0.0), v(n);
  const double a = options.relaxation;
  const double tolerance = options.tolerance * step;
  DequantizeResult result;
  for (int k = 0; k < options.maxIterations; ++k) {
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) { v[i] = z[i] - u[i]; });
    smoother.apply(v);
    // The z and u updates, with both residuals.
    struct Residuals {
      double primal = 0.0, dual = 0.0;
    };
    const Residuals r = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n), Residuals{},
        [&](const tbb::blocked_range<std::size_t>& range, Residuals m) {
          for (std::size_t i = range.begin(); i < range.end(); ++i) {
            const double s = grid.values[i];
            const double relaxed = a * v[i] + (1.0 - a) * z[i];
            const double zNew = std::clamp(relaxed + u[i], s - h, s + h);
            u[i] += relaxed - zNew;
            m.primal = std::max(m.primal, std::abs(v[i] - zNew));
            m.dual = std::max(m.dual, std::abs(zNew - z[i]));
            z[i] = zNew;
          }
          return m;
        },
        [](Residuals x, Residuals y) {
          return Residuals{std::max(x.primal, y.primal), std::max(x.dual, y.dual)};
        });
    result.iterations = k + 1;
    result.primalResidual = r.primal;
    if (options.progress) options.progress(double(k + 1) / options.maxIterations, "dequantize");
    if (r.primal <= tolerance && r.dual <= tolerance) {
      result.converged = true;
      break;
    }
  }
  std::size_t onEdge = 0;
  result.targets.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    result.targets[i] = static_cast<float>(z[i]);
    if (std::abs(z[i] - grid.values[i]) >= h * (1.0 - 1e-6)) ++onEdge;
  }
  result.edgeShare = n ? double(onEdge) / double(n) : 0.0;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace mfadvr
