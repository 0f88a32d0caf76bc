#pragma once
// Tighter bounds of a tensor B-spline over each knot-span cell: the range of the cell's
// Bernstein (Bezier) coefficients.
//
// Inside one cell the spline is a tensor-product polynomial of degree (p0, p1, p2). Written in
// the cell's Bernstein basis, its (p+1)^3 coefficients are B = (M0 x M1 x M2) P, where P is the
// cell's block of control points and Ma, per axis and span, expresses the span's p+1 B-spline
// basis functions in the Bernstein basis of that span. The Bernstein basis is non-negative and
// sums to one, so the polynomial lies between min B and max B (the Bezier convex hull). Each
// row of Ma is non-negative and sums to one as well, so each Bezier coefficient is a weighted
// average of control points, and this range is never wider than the control points' range
// (SpanRanges.h) and usually much narrower: on a noisy scan fitted with as many control points
// as samples the control points oscillate around the data, and the averages do not
// (docs/benchmarks.md, "Bezier bounds").
//
// The coefficients are computed in float; relativeRounding() bounds their error relative to
// the cell's largest |control point|. The caller widens by it and by the evaluation kernel's
// own rounding bound (EmptySpaceGrid.h) before asking a transfer function, so that skipping
// stays exact.
#include <cstdint>
#include <vector>

#include "core/spline/SplineView.h"

namespace mfadvr {

// Above this magnitude of a cell's control points the float sums could overflow: such cells
// keep the control points' range.
inline constexpr float kBezierMagnitudeLimit = 1e36f;

// The Bezier range of the cells of a plane z of cells, x fastest (as SpanRangeScanner::plane).
// One scanner per task; planes may be asked in any order (each is computed from its p+1 control
// planes). Cells with a control point that is not finite get meaningless values here: the
// caller checks the control points' range first.
class BezierRangeScanner {
 public:
  explicit BezierRangeScanner(const SplineView& spline);

  // need (optional, one byte per cell of the plane): only cells with a non-zero byte are asked
  // for; rows and blocks of 16 cells without one are not computed, and other cells' lo and hi
  // may be left as they were.
  void plane(std::int64_t z, float* lo, float* hi, const std::uint8_t* need = nullptr);

  // The spline's value at the centre of the cells of plane z (those `need` asks for, as for
  // plane()), computed in float: a cell whose centre is visible cannot be empty, which spares
  // computing its Bezier range (about 12 operations a cell against 336 for p = 3).
  void centres(std::int64_t z, float* value, const std::uint8_t* need = nullptr);

  // Bound on |computed coefficient - exact one| / max |control point of the cell|, for cells
  // whose control points are finite and at most kBezierMagnitudeLimit in magnitude.
  double relativeRounding() const;

 private:
  SplineView v_;
  int p_[3];
  std::int64_t n_[3], cells_[3];
  // Per axis, the conversion of each cell (span c + p): the weight of control point c + i in
  // Bezier coefficient j, at [(j * (p+1) + i) * stride_ + c] (cells fastest, so that the x
  // axis's transform runs as vectors over the cells of a row; its stride is padded to whole
  // blocks of cells).
  std::int64_t stride_[3];
  std::vector<float> weights_[3];
  std::vector<float> centreWeights_[3];  // the basis at each span's centre: [i * stride_ + c]
  float weight(int axis, int j, int i, std::int64_t c) const {
    return weights_[axis][static_cast<size_t>((j * (p_[axis] + 1) + i) * stride_[axis] + c)];
  }
  float centreWeight(int axis, int i, std::int64_t c) const {
    return centreWeights_[axis][static_cast<size_t>(i * stride_[axis] + c)];
  }
  std::vector<float> planeZ_;  // (p2+1) planes of N0 x N1: the z transform of the control points
  std::vector<float> rowYZ_;   // (p1+1)(p2+1) rows of rowStride_: a cell row's y and z transforms
  std::int64_t rowStride_ = 0;
  std::vector<char> rowDone_;  // plane(): control rows whose z transform is in planeZ_
};

}  // namespace mfadvr
