#pragma once
// Adaptive encoding to an error bound: refine the knots where the model misses the data.
//
// Start with few control points; fit; measure the error at every input sample (grid) or point
// (scattered); on each axis, find the knot spans that hold a sample whose error exceeds the
// bound and split them (non-uniform knots); refit; repeat until the max error over all input
// samples is within the bound, or a limit stops it. Splitting a span on axis a refines the whole
// slab of that span, as a tensor-product spline must.
//
// Grid spans are split between their two middle samples, so every span keeps at least one
// sample and the fit stays well posed; when a failing span holds one sample, that axis goes
// straight to interpolation (a control point per sample), so every grid can meet any bound.
// Scattered spans are split at their middle (the smoothing keeps spans without points defined).
// Each scattered round starts its solver from the previous round's model.
#include <functional>
#include <string>

#include "core/encode/FitReport.h"
#include "core/encode/ScatteredEncoder.h"
#include "core/encode/StructuredEncoder.h"

namespace mfadvr {

struct AdaptiveRound {
  int round = 0;
  Index3 controlCounts{0, 0, 0};
  double maxRelativeError = 0.0;
  double rmsRelativeError = 0.0;
  double seconds = 0.0;  // since the adaptive encoding started
};

struct AdaptiveOptions {
  double maxRelativeError = 1e-2;  // the bound E, relative to the value range; > 0
  // Per-axis cap on control points; 0 on an axis: the sample count (grids) or 256 (scattered).
  Index3 maxControlCounts{0, 0, 0};
  int maxRounds = 30;
  // Called after every round, on the calling thread.
  std::function<void(const AdaptiveRound&)> onRound;
};

// Starting counts come from fit.controlCounts (0 on an axis: degree + 2, i.e. two spans).
// Returns the model with the smallest max error seen; report->reachedTarget says whether it is
// within the bound and report->stopReason why refinement stopped. Throws mfadvr::Error for
// invalid options or data.
Model fitStructuredAdaptive(const StructuredGrid& grid, const StructuredFitOptions& fit,
                            const AdaptiveOptions& adaptive, FitReport* report = nullptr);
Model fitScatteredAdaptive(const ScatteredData& data, const ScatteredFitOptions& fit,
                           const AdaptiveOptions& adaptive, FitReport* report = nullptr);

// One set of knots refined for several grids of `dims` samples (the steps of a time series,
// TimeSeriesEncoder.h), with the grid rules above. Each round calls fitAll(knots, report,
// spanErrors), which fits every grid with these knots and gives the worst over them: the report's
// errors and value range, and per axis and span the largest error; it returns any of its fits
// with these knots. Returns the knots of the round with the smallest max error; `report` as
// fitStructuredAdaptive's.
using SharedKnotsFit =
    std::function<Model(const std::array<KnotVector, 3>& knots, FitReport& report,
                        std::array<std::vector<double>, 3>& spanErrors)>;
std::array<KnotVector, 3> adaptSharedKnots(const Index3& dims, const StructuredFitOptions& fit,
                                           const AdaptiveOptions& adaptive,
                                           const SharedKnotsFit& fitAll,
                                           FitReport* report = nullptr);

}  // namespace mfadvr
