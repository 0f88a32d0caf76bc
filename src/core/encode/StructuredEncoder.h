#pragma once
// Least-squares fit of a tensor-product B-spline to samples on a regular grid.
//
// The fit is separable: the tensor least-squares solution equals one 1-D least-squares solve
// per axis applied to every grid line along it (the pseudo-inverse of a Kronecker product is the
// Kronecker product of the pseudo-inverses). Each axis factors its banded normal matrix once and
// solves all lines with it, in parallel. Control counts equal to the sample counts interpolate.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "core/encode/FitReport.h"
#include "core/grid/StructuredGrid.h"
#include "core/model/Model.h"

namespace mfadvr {

struct StructuredFitOptions {
  Degree3 degree{3, 3, 3};
  Index3 controlCounts{0, 0, 0};  // 0 on an axis: as many control points as samples
  // Called on the calling thread between stages with the fraction done and the stage name.
  std::function<void(double fraction, const std::string& stage)> progress;
};

// Throws mfadvr::Error for degrees outside 1..7, counts below degree + 1 or above the sample
// count, grids with fewer than two samples on an axis, and non-finite samples.
Model fitStructured(const StructuredGrid& grid, const StructuredFitOptions& options,
                    FitReport* report = nullptr);

// The same fit with the given knot vectors (any clamped vectors, e.g. refined by the adaptive
// encoder; n <= samples on every axis). With spanErrors, (*spanErrors)[a][s - p] receives the
// largest absolute error of the samples whose axis-a parameter lies in knot span s.
Model fitStructuredWithKnots(const StructuredGrid& grid, std::array<KnotVector, 3> knots,
                             const StructuredFitOptions& options, FitReport* report = nullptr,
                             std::array<std::vector<double>, 3>* spanErrors = nullptr);

// For each axis a, the largest absolute error, per knot span of knots[a], of 1-D least-squares
// fits of every grid line along a with knots[a] alone: where axis a needs knots, whatever the
// other axes do (the adaptive encoder's refinement test).
std::array<std::vector<double>, 3> curveSpanErrors(const StructuredGrid& grid,
                                                   const std::array<KnotVector, 3>& knots);

// Resolves 0 entries of options.controlCounts and validates everything against the grid.
Index3 resolveControlCounts(const StructuredGrid& grid, const StructuredFitOptions& options);

}  // namespace mfadvr
