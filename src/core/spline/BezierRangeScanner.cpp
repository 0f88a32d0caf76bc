#include "core/spline/BezierRangeScanner.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "core/spline/BasisFunctions.h"
#include "core/spline/KnotVector.h"

namespace mfadvr {
namespace {

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// The weights of one axis (layout: BezierRangeScanner::weights_). On span s the basis function
// N_{s-p+i} is a polynomial f(t) = sum_k a_k t^k in t = (u - U[s]) / h, with a_k its k-th
// derivative at U[s] times h^k / k!; its Bernstein coefficients are
// b_j = sum_{k <= j} C(j, k) / C(p, k) a_k. A span of zero length holds no sample: its cell
// gets the identity (the control points' own range). Cell c of row (j, i) at
// (j * (p+1) + i) * stride + c; stride >= cells.
std::vector<float> axisWeights(const KnotAxisView& a, std::int64_t stride) {
  const int p = a.degree, w = p + 1, cells = a.count - p;
  std::vector<float> out(static_cast<size_t>(w * w * stride), 0.0f);
  if (cells <= 0) return out;
  const KnotVector kv =
      KnotVector::fromKnots(p, std::vector<double>(a.knots, a.knots + a.count + p + 1));
  double ders[(kMaxDegree + 1) * (kMaxDegree + 1)];
  for (int c = 0; c < cells; ++c) {
    const int s = c + p;
    const double h = a.knots[s + 1] - a.knots[s];
    const auto at = [&](int j, int i) -> float& {
      return out[static_cast<size_t>((j * w + i) * stride + c)];
    };
    if (!(h > 0.0)) {
      for (int j = 0; j < w; ++j) at(j, j) = 1.0f;
      continue;
    }
    basisDerivatives(kv, p, s, a.knots[s], p, ders);
    for (int i = 0; i < w; ++i) {
      double coefficient[kMaxDegree + 1];
      double scale = 1.0;  // h^k / k!
      for (int k = 0; k <= p; ++k) {
        coefficient[k] = ders[k * w + i] * scale;
        scale *= h / (k + 1);
      }
      for (int j = 0; j < w; ++j) {
        double b = 0.0;
        for (int k = 0; k <= j; ++k) b += binomial(j, k) / binomial(p, k) * coefficient[k];
        at(j, i) = static_cast<float>(b);
      }
    }
  }
  return out;
}

// out[i] = sum_k weight[k] src[k][i] for i < n, in one pass (W known at compile time).
template <int W>
void combineRows(const float* const* src, const float* weight, std::int64_t n, float* out) {
  for (std::int64_t i = 0; i < n; ++i) {
    float sum = weight[0] * src[0][i];
    for (int k = 1; k < W; ++k) sum += weight[k] * src[k][i];
    out[i] = sum;
  }
}

template <int... W>
void combineRowsFor(int w, std::integer_sequence<int, W...>, const float* const* src,
                    const float* weight, std::int64_t n, float* out) {
  ((w == W + 1 ? combineRows<W + 1>(src, weight, n, out) : void()), ...);
}

inline constexpr int kCellBlock = 16;

// The x transform of a cell row and its least and greatest coefficient: `count` rows of the
// row's y and z transforms (stride rowStride) against the x weights, kCellBlock cells at a
// time as one vector (GCC / Clang vector extensions: a plain loop over the lanes was left
// scalar by GCC, 2x slower than the pass-per-weight loops), with the block's weights kept in
// registers (W: p0 + 1 known at compile time). Reads up to kCellBlock + W - 1 floats past a
// row's cells: the buffers are padded for it; lanes past the last cell are not stored.
typedef float CellVector __attribute__((vector_size(kCellBlock * sizeof(float))));

inline CellVector loadCells(const float* p) {
  CellVector v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Any of need[0 .. n-1] non-zero (need null: every cell is needed).
bool anyNeeded(const std::uint8_t* need, std::int64_t n) {
  return !need || std::any_of(need, need + n, [](std::uint8_t b) { return b != 0; });
}

template <int W>
void blockRanges(const float* rows, int count, std::int64_t rowStride, const float* weights,
                 std::int64_t weightStride, std::int64_t begin, std::int64_t end,
                 const std::uint8_t* need, float* lo, float* hi) {
  for (std::int64_t c0 = begin; c0 < end; c0 += kCellBlock) {
    const std::int64_t n = std::min<std::int64_t>(kCellBlock, end - c0);
    if (!anyNeeded(need ? need + c0 : nullptr, n)) continue;
    CellVector w[W][W];
    for (int j = 0; j < W; ++j)
      for (int i = 0; i < W; ++i) w[j][i] = loadCells(weights + (j * W + i) * weightStride + c0);
    const CellVector none = {};
    CellVector least = none + INFINITY, greatest = none - INFINITY;
    for (int r = 0; r < count; ++r) {
      const float* src = rows + r * rowStride + c0;
      CellVector x[W];
      for (int i = 0; i < W; ++i) x[i] = loadCells(src + i);
      for (int j = 0; j < W; ++j) {
        CellVector b = w[j][0] * x[0];
        for (int i = 1; i < W; ++i) b += w[j][i] * x[i];
        least = b < least ? b : least;
        greatest = b > greatest ? b : greatest;
      }
    }
    float l[kCellBlock], g[kCellBlock];
    std::memcpy(l, &least, sizeof l);
    std::memcpy(g, &greatest, sizeof g);
    std::copy_n(l, n, lo + c0);
    std::copy_n(g, n, hi + c0);
  }
}

template <int... W>
void blockRangesFor(int w, std::integer_sequence<int, W...>, const float* rows, int count,
                    std::int64_t rowStride, const float* weights, std::int64_t weightStride,
                    std::int64_t begin, std::int64_t end, const std::uint8_t* need, float* lo,
                    float* hi) {
  ((w == W + 1 ? blockRanges<W + 1>(rows, count, rowStride, weights, weightStride, begin, end, need,
                                    lo, hi)
               : void()),
   ...);
}

}  // namespace

BezierRangeScanner::BezierRangeScanner(const SplineView& v) : v_(v) {
  for (int a = 0; a < 3; ++a) {
    p_[a] = v.axis[a].degree;
    n_[a] = v.axis[a].count;
    cells_[a] = std::max<std::int64_t>(0, n_[a] - p_[a]);
    // x: whole blocks of cells (blockRanges reads a block's weights at once).
    stride_[a] = a == 0 ? (cells_[a] + kCellBlock - 1) / kCellBlock * kCellBlock : cells_[a];
    weights_[a] = axisWeights(v.axis[a], stride_[a]);
    // The centre of a span in Bernstein form: B_j(1/2) = C(p, j) / 2^p.
    const int w = p_[a] + 1;
    centreWeights_[a].assign(static_cast<size_t>(w * stride_[a]), 0.0f);
    for (int i = 0; i < w; ++i)
      for (std::int64_t c = 0; c < cells_[a]; ++c) {
        double sum = 0.0;
        for (int j = 0; j < w; ++j)
          sum += weight(a, j, i, c) * binomial(p_[a], j) / std::ldexp(1.0, p_[a]);
        centreWeights_[a][static_cast<size_t>(i * stride_[a] + c)] = static_cast<float>(sum);
      }
  }
  rowStride_ = stride_[0] + p_[0] + 1;  // >= n_[0], and room for a last block's reads
  planeZ_.resize(static_cast<size_t>((p_[2] + 1) * n_[0] * n_[1]));
  rowYZ_.assign(static_cast<size_t>((p_[1] + 1) * (p_[2] + 1) * rowStride_), 0.0f);
}

double BezierRangeScanner::relativeRounding() const {
  // Per axis: a coefficient is a sum of p+1 products of a float weight and a float input; the
  // weights carry their own rounding from double (u |w|) and the sum p+1 roundings, each
  // relative to sum |w| |input| <= S max |input|, S the largest row sum of |w| (1 up to
  // rounding). The inputs of the next axis are bounded by S times the previous bound.
  constexpr double u = 0x1p-24;
  double error = 0.0, magnitude = 1.0;
  for (int a = 0; a < 3; ++a) {
    const int w = p_[a] + 1;
    double rowSum = 1.0;
    for (int j = 0; j < w; ++j)
      for (std::int64_t c = 0; c < cells_[a]; ++c) {
        double sum = 0.0;
        for (int i = 0; i < w; ++i) sum += std::abs(weight(a, j, i, c));
        rowSum = std::max(rowSum, sum);
      }
    error = error * rowSum + (w + 1) * u * rowSum * magnitude;
    magnitude *= rowSum;
  }
  return 2.0 * error;  // a factor 2 for safety
}

void BezierRangeScanner::centres(std::int64_t z, float* value, const std::uint8_t* need) {
  const int w0 = p_[0] + 1, w1 = p_[1] + 1, w2 = p_[2] + 1;
  const std::int64_t N0 = n_[0], N1 = n_[1], X = cells_[0], Y = cells_[1];
  const std::int64_t controlPlane = N0 * N1;
  constexpr auto widths = std::make_integer_sequence<int, kMaxDegree + 1>();
  const float* src[kMaxDegree + 1];
  float factor[kMaxDegree + 1];
  for (int k = 0; k < w2; ++k) {
    src[k] = v_.ctrl + (z + k) * controlPlane;
    factor[k] = centreWeight(2, k, z);
  }
  float* planeZ = planeZ_.data();
  combineRowsFor(w2, widths, src, factor, controlPlane, planeZ);
  float* row = rowYZ_.data();
  for (std::int64_t cy = 0; cy < Y; ++cy) {
    if (!anyNeeded(need ? need + cy * X : nullptr, X)) continue;
    for (int k = 0; k < w1; ++k) {
      src[k] = planeZ + (cy + k) * N0;
      factor[k] = centreWeight(1, k, cy);
    }
    combineRowsFor(w1, widths, src, factor, N0, row);
    float* out = value + cy * X;
    const float* wx = centreWeights_[0].data();
    for (std::int64_t c = 0; c < X; ++c) out[c] = wx[c] * row[c];
    for (int i = 1; i < w0; ++i)
      for (std::int64_t c = 0; c < X; ++c) out[c] += wx[i * stride_[0] + c] * row[c + i];
  }
}

void BezierRangeScanner::plane(std::int64_t z, float* lo, float* hi, const std::uint8_t* need) {
  const int w0 = p_[0] + 1, w1 = p_[1] + 1, w2 = p_[2] + 1;
  const std::int64_t N0 = n_[0], N1 = n_[1], X = cells_[0], Y = cells_[1];
  const std::int64_t controlPlane = N0 * N1;
  constexpr auto widths = std::make_integer_sequence<int, kMaxDegree + 1>();
  const float* src[kMaxDegree + 1];
  float factor[kMaxDegree + 1];
  // Work in proportion to the cells asked for: the z transform of a control row only when a
  // cell row that needs it is asked for, the y transform of a row only over the columns of the
  // runs of 16-cell blocks that hold asked-for cells, the x transform per such block.
  float zWeight[kMaxDegree + 1][kMaxDegree + 1];  // [j2][k]: this plane's z transform
  for (int j2 = 0; j2 < w2; ++j2)
    for (int k = 0; k < w2; ++k) zWeight[j2][k] = weight(2, j2, k, z);
  rowDone_.assign(static_cast<size_t>(N1), 0);
  for (std::int64_t cy = 0; cy < Y; ++cy) {
    const std::uint8_t* rowNeed = need ? need + cy * X : nullptr;
    if (!anyNeeded(rowNeed, X)) continue;
    // z: control rows cy .. cy + p1 of the p2+1 Bezier planes of this cell plane.
    for (std::int64_t j = cy; j < cy + w1; ++j) {
      if (rowDone_[static_cast<size_t>(j)]) continue;
      rowDone_[static_cast<size_t>(j)] = 1;
      for (int k = 0; k < w2; ++k) src[k] = v_.ctrl + (z + k) * controlPlane + j * N0;
      for (int j2 = 0; j2 < w2; ++j2)
        combineRowsFor(w2, widths, src, zWeight[j2], N0,
                       planeZ_.data() + j2 * controlPlane + j * N0);
    }
    for (std::int64_t begin = 0; begin < X;) {
      // The next run of blocks with an asked-for cell: [begin, end).
      const auto asked = [&](std::int64_t c0) {
        return anyNeeded(rowNeed ? rowNeed + c0 : nullptr,
                         std::min<std::int64_t>(kCellBlock, X - c0));
      };
      while (begin < X && !asked(begin)) begin += kCellBlock;
      if (begin >= X) break;
      std::int64_t end = begin;
      while (end < X && asked(end)) end += kCellBlock;
      end = std::min(end, X);
      // y: the (p1+1)(p2+1) rows over the control columns the run's cells read (the lanes of
      // a last block past the row's end read further, and are not stored).
      const std::int64_t first = begin, count = std::min(end + w0 - 1, N0) - first;
      for (int j1 = 0; j1 < w1; ++j1) {
        for (int k = 0; k < w1; ++k) factor[k] = weight(1, j1, k, cy);
        for (int j2 = 0; j2 < w2; ++j2) {
          for (int k = 0; k < w1; ++k)
            src[k] = planeZ_.data() + j2 * controlPlane + (cy + k) * N0 + first;
          combineRowsFor(w1, widths, src, factor, count,
                         rowYZ_.data() + (j1 * w2 + j2) * rowStride_ + first);
        }
      }
      // x: each cell's coefficients and their least and greatest.
      blockRangesFor(w0, widths, rowYZ_.data(), w1 * w2, rowStride_, weights_[0].data(), stride_[0],
                     begin, end, rowNeed, lo + cy * X, hi + cy * X);
      begin = end;
    }
  }
}

}  // namespace mfadvr
