#pragma once
// Where the knots go when a spline is fitted to equally spaced samples.
//
// Uniform knots look natural but are a poor choice near interpolation: with n close to N the
// samples drift against the knots, some basis functions are sampled only at the tails of their
// support, and the normal equations become numerically singular (cubic, N = 118: smallest
// singular value of the collocation matrix 4e-9). The placements of The NURBS Book keep every
// span populated and the system well conditioned:
//   n = N (interpolation): averaging, u_{p+j} = (1/p) sum_{i=j}^{j+p-1} t_i      (eq. 9.8)
//   n < N (approximation): u_{p+j} = (1 - a) t_{i-1} + a t_i, i = floor(j d), a = j d - i,
//                          d = N / (n - p)                                       (eq. 9.69)
// with t_i = i / (N - 1). For equally spaced samples both leave the interior knots equally
// spaced (only the end spans differ), so span lookup stays O(1).
#include <cstdint>
#include <span>

#include "core/spline/KnotVector.h"

namespace mfadvr {

KnotVector knotsForSamples(int degree, int controlCount, std::int64_t sampleCount);
// The same placements for samples at any non-decreasing parameters t_i in [0, 1] (the times of a
// series' steps), at least controlCount of them. Throws mfadvr::Error when the knots they give
// are not a valid vector (samples too close together for the degree).
KnotVector knotsForParameters(int degree, int controlCount, std::span<const double> parameters);

// Knots of scattered points: each interior knot j of the controlCount - degree spans is
// (1 - weight) j / spans + weight q_j, where q_j is the j / spans quantile of the points'
// parameters along the axis (`sorted`: non-decreasing, in [0, 1]). Weight 0 gives uniform knots;
// towards 1 the spans hold equal shares of the points, so that control points gather where a mesh
// is refined (where its simulation needed resolution). The uniform share keeps every span at
// least (1 - weight) / spans wide; a region without points may get one wide span (meshes hide it
// with their domain; point clouds default to uniform knots). Throws mfadvr::Error for a weight
// outside [0, 1) or no points.
KnotVector knotsFollowingDensity(int degree, int controlCount, std::span<const double> sorted,
                                 double weight);

}  // namespace mfadvr
