#pragma once
// Least-squares fit of a tensor-product B-spline to samples on a regular grid, optionally
// penalized (smoothing: the roughness penalty of core/spline/DerivativePenalty.h, of order p + 1
// on every axis, so that polynomials of the model's degree are not biased).
//
// The fit is separable: the tensor least-squares solution equals one 1-D least-squares solve
// per axis applied to every grid line along it (the pseudo-inverse of a Kronecker product is the
// Kronecker product of the pseudo-inverses). Each axis factors its banded normal matrix once and
// solves all lines with it, in parallel. Control counts equal to the sample counts interpolate
// (without smoothing). With smoothing each axis solves (N^T N + m mu D^T D) c = N^T f instead,
// still one banded factorization per axis: the tensor product of 1-D smoothers.
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/encode/FitReport.h"
#include "core/grid/GridSamples.h"
#include "core/grid/StructuredGrid.h"
#include "core/model/Model.h"

namespace mfadvr {

struct StructuredFitOptions {
  Degree3 degree{3, 3, 3};
  Index3 controlCounts{0, 0, 0};  // 0 on an axis: as many control points as samples
  // lambda >= 0 of the roughness penalty (DerivativePenalty.h); 0: plain least squares.
  double smoothing = 0.0;
  // Called on the calling thread between stages with the fraction done and the stage name.
  std::function<void(double fraction, const std::string& stage)> progress;
};

// Throws mfadvr::Error for degrees outside 1..7, counts below degree + 1 or above the sample
// count, grids with fewer than two samples on an axis, non-finite samples and a smoothing weight
// that is negative or not finite.
Model fitStructured(const StructuredGrid& grid, const StructuredFitOptions& options,
                    FitReport* report = nullptr);
// The same fit of samples held elsewhere (`layout` gives dims, box and provenance; its values
// are not read): the samples are read one z plane (and one error slab) at a time, so an input
// in another type costs no float32 copy of the whole grid. Gives the model of the fit above
// with the samples converted to float32.
Model fitStructured(const StructuredGrid& layout, const GridSamples& samples,
                    const StructuredFitOptions& options, FitReport* report = nullptr);

// The same fit with the given knot vectors (any clamped vectors, e.g. refined by the adaptive
// encoder; n <= samples on every axis). With spanErrors, (*spanErrors)[a][s - p] receives the
// largest absolute error of the samples whose axis-a parameter lies in knot span s.
Model fitStructuredWithKnots(const StructuredGrid& grid, std::array<KnotVector, 3> knots,
                             const StructuredFitOptions& options, FitReport* report = nullptr,
                             std::array<std::vector<double>, 3>* spanErrors = nullptr);
// The same with the samples held elsewhere; `validated`: layout and samples were checked.
Model fitStructuredWithKnots(const StructuredGrid& layout, const GridSamples& samples,
                             std::array<KnotVector, 3> knots, const StructuredFitOptions& options,
                             FitReport* report = nullptr,
                             std::array<std::vector<double>, 3>* spanErrors = nullptr,
                             bool validated = false);

// For each axis a, the largest absolute error, per knot span of knots[a], of 1-D least-squares
// fits of every grid line along a with knots[a] alone: where axis a needs knots, whatever the
// other axes do (the adaptive encoder's refinement test).
std::array<std::vector<double>, 3> curveSpanErrors(const StructuredGrid& grid,
                                                   const std::array<KnotVector, 3>& knots);

// The spline's values at every sample of a grid of `dims` samples spanning its parameter box
// (x fastest), evaluated separably (as fast as a fit).
std::vector<double> splineOnGrid(const TensorBSpline& spline, const Index3& dims);
// The samples of that grid with z in [zBegin, zEnd) only (x fastest), from the control planes
// they depend on: a slab's work and memory, for decoding large grids slab by slab.
std::vector<double> splineOnGrid(const TensorBSpline& spline, const Index3& dims,
                                 std::int64_t zBegin, std::int64_t zEnd);

struct SampleErrors {
  double max = 0.0, rms = 0.0;  // absolute
};
// The spline against every sample of `grid`.
SampleErrors errorsOnGrid(const TensorBSpline& spline, const StructuredGrid& grid);
// The same, or nullopt as soon as one z slab holds an error above `limit` (NaN included): a
// candidate that fails a bound is rejected after a part of the work.
std::optional<SampleErrors> errorsOnGridWithin(const TensorBSpline& spline,
                                               const StructuredGrid& grid, double limit);

// The most memory a fit of a `dims` grid with `counts` control points holds at once, the input's
// samples (float, 4 bytes each) included: the float coefficient array the passes share, per
// thread one plane's work, or the control points and the slab of evaluations that measures the
// errors (about 8 bytes per sample when the counts equal the sample counts). The fit checks it
// against the available memory before it starts.
std::int64_t structuredFitPeakBytes(const Index3& dims, const Index3& counts);

// Resolves 0 entries of options.controlCounts and validates everything against the grid.
Index3 resolveControlCounts(const StructuredGrid& grid, const StructuredFitOptions& options);
// The knot vectors of a fit with options.degree and options.controlCounts (uniform, clamped).
std::array<KnotVector, 3> knotsOfFit(const StructuredGrid& layout,
                                     const StructuredFitOptions& options);

// The separable smoother in value space, for iterative fits on one grid (encode --dequantize):
// apply() replaces the values of a `dims` grid (x fastest) by those of its fit with `knots` and
// smoothing weight lambda (the fit of fitStructuredWithKnots, in double, not rounded to float),
// evaluated back at the samples. Each axis's factorization is made once, at construction.
class GridSmoother {
 public:
  GridSmoother(const std::array<KnotVector, 3>& knots, const Index3& dims, double smoothing);
  ~GridSmoother();
  void apply(std::vector<double>& values) const;

 private:
  struct Axes;
  Index3 dims_;
  std::unique_ptr<Axes> axes_;
};

// The effective number of parameters of the fit with these knots and smoothing weight: the
// trace of its hat matrix (the product over the axes of the 1-D traces; the control count when
// lambda is 0). Generalized cross-validation divides by P minus it.
double effectiveParameters(const std::array<KnotVector, 3>& knots, const Index3& dims,
                           double smoothing);

// The largest smoothing weight of a grid fit: its cut-off wavelength is 60 knot spans, and the
// penalty then outweighs the data term by 1e8 (a larger ratio would leave the solve singular).
inline constexpr double kMaxGridSmoothing = 1e4;
// Throws mfadvr::Error unless 0 <= lambda <= kMaxGridSmoothing.
void validateSmoothing(double lambda);

}  // namespace mfadvr
