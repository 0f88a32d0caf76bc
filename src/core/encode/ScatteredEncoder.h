#pragma once
// Least-squares fit of a tensor-product B-spline to values at scattered points.
//
// The control points c minimize
//   (1/P) sum_k (s(x_k) - v_k)^2  +  lambda * sum_a  h_a^4 integral over [0,1]^3 of (d^2 s /
//   du_a^2)^2
// over the P input points, where h_a = 1 / (n_a - p_a) is the mean knot span of axis a. The
// integral is approximated through the second-derivative coefficients of the spline (mass
// lumping, core/spline/DerivativePenalty.h). lambda is dimensionless: both terms scale with the
// square of the values, and h^4 makes the penalty measure curvature per knot span, so that one
// lambda damps the same part of what the control grid can resolve at any control count (frequencies
// above about 1 / (h lambda^(1/4)) radians per unit parameter). The penalty makes the system
// definite, so spans without points get the smoothest continuation of their surroundings instead of
// arbitrary values, and multilinear functions carry no penalty at all.
//
// The normal equations are solved by conjugate gradients (Eigen) with a Jacobi preconditioner,
// matrix-free in the data term: the sparse basis matrix N (P rows of (p+1)^3 entries, about 12
// bytes each) is assembled in parallel and applied as N^T (N x), never multiplied out; the
// penalty D^T D is multiplied out once (at most 13 entries per row).
// Empty regions converge slowly on one grid (their modes have eigenvalues of order lambda), so
// the fit runs coarse to fine: each level starts from the previous level's spline sampled at its
// own Greville abscissae.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "core/encode/FitReport.h"
#include "core/mesh/ScatteredData.h"
#include "core/model/Model.h"

namespace mfadvr {

inline constexpr double kDefaultSmoothing = 1e-2;
// The knot density weight of meshes by default (point clouds: 0, uniform knots).
inline constexpr double kDefaultMeshKnotDensity = 0.75;
// Second derivatives (core/spline/DerivativePenalty.h): regions without points get the
// smoothest, nearly linear continuation of their surroundings. Grids penalize order p + 1.
inline constexpr int kScatteredPenaltyOrder = 2;

struct ScatteredFitOptions {
  Degree3 degree{3, 3, 3};
  Index3 controlCounts{0, 0, 0};         // 0 on an axis: defaultScatteredControlCount
  double smoothing = kDefaultSmoothing;  // lambda, >= 0 (0 only when every span has points)
  // How far the knots follow the points' density along each axis (knotsFollowingDensity):
  // 0 uniform, up to < 1. encodeScattered gives meshes kDefaultMeshKnotDensity (measured on the
  // blunt-fin mesh, docs/encoding.md: the image closest to VTK's tetrahedral ray caster, at 3.7x
  // the fit time of uniform knots).
  double knotDensity = 0.0;
  // Relative residual |b - Ax| / |b| of each solve. 1e-4 measured against 1e-6 on the blunt-fin
  // and spx meshes (docs/encoding.md): the same value PSNR and image (to 0.03 dB) at a quarter of
  // the fit time; the reported errors are measured on the model either way. Adaptive rounds
  // solve to 1e-6 (fitScatteredAdaptive).
  double tolerance = 1e-4;
  int maxIterations = 4000;  // conjugate-gradient iterations per level
  // Called on the calling thread with the fraction done and the stage name.
  std::function<void(double fraction, const std::string& stage)> progress;
};

// The default control counts: as many control points per axis as the points' mean spacing
// h = (V / P)^(1/3) fits into the box's extent on that axis (extent / h + 1), where V is the
// volume the P points fill: a mesh's total tetrahedron volume, a point cloud's box. So a flat or
// long domain gets its control points where it is long, and a mesh that fills a fraction of its
// box gets the spacing of its points, not of the box. At least degree + 1 and at most 256 per
// axis, and at most 64^3 in all (scaled down alike on every axis beyond that).
Index3 defaultScatteredControlCounts(const ScatteredData& data, const Degree3& degree);

// Bytes one fit of `points` points with `counts` control points holds at most, the points
// themselves not counted: their parameters, the sparse basis matrix and its transpose (12 bytes
// per entry, (p+1)^3 entries per point), the second differences and the penalty (13 entries per
// control point), and the solver's vectors. The control counts weigh most: 256^3 control points
// need about 6 GB whatever the number of points.
std::int64_t scatteredFitPeakBytes(std::int64_t points, const Index3& counts,
                                   const Degree3& degree);

// The points' parameters in their box along each axis, sorted (for knotsFollowingDensity).
std::array<std::vector<double>, 3> sortedAxisParameters(const ScatteredData& data);

// Resolves 0 entries of options.controlCounts and validates degrees, counts and smoothing.
Index3 resolveScatteredControlCounts(const ScatteredData& data, const ScatteredFitOptions& options);

// Throws mfadvr::Error for invalid data (ScatteredData::validate) or options, and before it
// starts when the fit needs more memory than there is (scatteredFitPeakBytes). The model's box
// is the points' bounding box; it has no mask (the caller adds one, see encodeScattered).
Model fitScattered(const ScatteredData& data, const ScatteredFitOptions& options,
                   FitReport* report = nullptr);

// One solve with the given knot vectors, starting from `initial` (sampled at the Greville
// abscissae; null: the mean value). spanErrors as in fitStructuredWithKnots.
Model fitScatteredWithKnots(const ScatteredData& data, std::array<KnotVector, 3> knots,
                            const ScatteredFitOptions& options, const Model* initial,
                            FitReport* report = nullptr,
                            std::array<std::vector<double>, 3>* spanErrors = nullptr);

}  // namespace mfadvr
