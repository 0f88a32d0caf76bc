#pragma once
// The per-point tensor B-spline evaluation, header-only over a SplineView: span lookup, basis
// functions, separable contraction of the control points, for the value, the value and gradient,
// or the value, gradient and Hessian (parametric derivatives). Host and device code (MFADVR_HD).
//
// The degree is a template parameter P, chosen once per render or batch (splineDegreeSwitch):
// with P > 0 all three axes have degree P and every loop unrolls; P = 0 reads the per-axis
// degrees at run time (mixed degrees). There is one formula for each quantity; the ray sampler
// (render/kernel/SplineRaySampler.h) calls the same functions on a gathered control block.
//
// Basis functions come from per-span polynomials (KnotVector::basisPolynomials, derived from
// The NURBS Book's A2.3): a point costs a span lookup and Horner's rule in the span's local
// coordinate, with no divisions and no recurrences.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "core/spline/SplineView.h"

#if (defined(__GNUC__) || defined(__clang__)) && !defined(__CUDACC__) && defined(__AVX__)
#include <immintrin.h>
#endif

namespace mfadvr {

inline constexpr int kSplineMaxDegree = 7;  // = kMaxDegree of KnotVector.h

// Compile-time degree P, or the run-time one when P = 0.
template <int P>
struct SplineDegree {
  static constexpr int kWidth = P > 0 ? P + 1 : kSplineMaxDegree + 1;  // array bound
  MFADVR_HD static constexpr int of(int runtime) { return P > 0 ? P : runtime; }
};

// W floats as one SIMD value where the host compiler offers vector extensions (GCC, Clang) and
// the degree is fixed; plain loops otherwise (nvcc: one thread per ray already). Horner's rule
// over the p+1 basis polynomials of an axis uses it; both forms compute the same sums.
#if (defined(__GNUC__) || defined(__clang__)) && !defined(__CUDACC__)
#define MFADVR_KERNEL_VECTOR_LANES 1
#endif

// 8-lane values only where the target has 256-bit registers (AVX): elsewhere degrees above 3
// take the plain loops rather than values the ABI would pass in memory.
template <int W, bool Fixed>
struct Lanes {
#if defined(MFADVR_KERNEL_VECTOR_LANES) && defined(__AVX__)
  static constexpr bool kVector = Fixed && W <= 8;
#elif defined(MFADVR_KERNEL_VECTOR_LANES)
  static constexpr bool kVector = Fixed && W <= 4;
#else
  static constexpr bool kVector = false;
#endif
};

#if defined(MFADVR_KERNEL_VECTOR_LANES)
typedef float LaneVector4 __attribute__((vector_size(16)));
typedef float LaneVector8 __attribute__((vector_size(32)));
template <int W>
using LaneVector = std::conditional_t<(W <= 4), LaneVector4, LaneVector8>;

// x in every lane (also -0: `V{} + x` would make it +0).
template <class V>
MFADVR_INLINE V splatLanes(float x) {
#if defined(__AVX__)
  if constexpr (sizeof(V) == 32) return reinterpret_cast<V>(_mm256_set1_ps(x));
  if constexpr (sizeof(V) == 16) return reinterpret_cast<V>(_mm_set1_ps(x));
#endif
  V v;
  for (unsigned i = 0; i < sizeof(V) / sizeof(float); ++i) v[i] = x;
  return v;
}

// Horner's rule for basis polynomials held as vectors: c[k] holds coefficients of tau^k
// (k = 0..P), t the local coordinate; n gets the values, d1 and d2 (Order >= 1, 2) the first
// and second derivatives with respect to tau. The per-point kernel holds an axis's p+1
// functions in one vector, the eight-lane kernel one function at eight points: both call this.
template <int P, int Order, class V>
MFADVR_INLINE void hornerBasis(const V c[P + 1], V t, V& n, V& d1, V& d2) {
  n = c[P];
  if constexpr (Order >= 1) d1 = float(P) * n;
  if constexpr (Order >= 2) d2 = float(P * (P - 1)) * n;
#pragma GCC unroll 8
  for (int k = P - 1; k >= 0; --k) {
    n = fusedMultiplyAdd(n, t, c[k]);
    if constexpr (Order >= 1)
      if (k >= 1) d1 = fusedMultiplyAdd(d1, t, float(k) * c[k]);
    if constexpr (Order >= 2)
      if (k >= 2) d2 = fusedMultiplyAdd(d2, t, float(k * (k - 1)) * c[k]);
  }
}

// n floats into a vector of type V (unused lanes zero). Full vectors are copied whole; shorter
// ones are built lane by lane, since a narrow copy into a wide stack value stalls the load that
// follows. n is a compile-time constant wherever this is inlined.
template <class V>
MFADVR_INLINE V loadLanesOf(const float* x, int n) {
  V v;
  if (n * sizeof(float) == sizeof(V)) {
    __builtin_memcpy(&v, x, sizeof(V));
  } else {
    v = V{};
    for (int i = 0; i < n; ++i) v[i] = x[i];
  }
  return v;
}
// A whole vector from x: its lanes past the p+1 a row uses read the floats that follow, which
// the arrays provide (kSplineRowPadding, gatherBlock) and no sum reads.
template <class V>
MFADVR_INLINE V loadWhole(const float* x) {
  V v;
  __builtin_memcpy(&v, x, sizeof(V));
  return v;
}
template <class V>
MFADVR_INLINE void storeWhole(const V& v, float* x) {
  __builtin_memcpy(x, &v, sizeof(V));
}
#endif

// Floats per basis row: a whole SIMD vector on the vector path (its lanes past p+1 are never
// summed), else the array bound.
template <int P>
struct BasisWidth {
#if defined(MFADVR_KERNEL_VECTOR_LANES)
  static constexpr int value = Lanes<P + 1, (P > 0)>::kVector
                                   ? static_cast<int>(sizeof(LaneVector<P + 1>) / sizeof(float))
                                   : SplineDegree<P>::kWidth;
#else
  static constexpr int value = SplineDegree<P>::kWidth;
#endif
};

// Where a parametric coordinate falls on one axis: its span and local coordinate in [-1/2, 1/2]
// (measured from the span's midpoint, as KnotAxisView::poly expects).
struct AxisLocation {
  int span;
  float tau;
};

// Where u (clamped to [0,1]) falls on the axis.
// On a regular axis the interior spans p+1 .. count-2 are equally long (to 1e-9 of their
// length, KnotVector), so a point inside them is located from u alone, without reading knots:
// the span from floor((u - first interior knot) / spacing), tau from the fraction. Within a
// rounding error of a knot this may pick the neighbouring span, at its end (|tau| = 1/2 plus a
// rounding error): the spline is continuous there, and every caller (values, gradients,
// empty-space cells) sees the same choice. The end spans, and irregular axes, search the knots.
template <int P = 0>
MFADVR_HD MFADVR_INLINE AxisLocation locateOnAxis(const KnotAxisView& a, double u) {
  u = !(u > 0.0) ? 0.0 : (u > 1.0 ? 1.0 : u);  // NaN maps to 0: a finite answer
  if (a.regular) {
    const int p = P > 0 ? P : a.degree;
    const double t = (u - a.firstInterior) * a.inverseSpacing;
    const double f = floor(t);
    if (f >= 0.0 && f < a.interiorSpans)
      return {p + 1 + static_cast<int>(f), static_cast<float>(t - f - 0.5)};
  }
  const int s = findSpan<P>(a, u);
  return {s, static_cast<float>((u - a.knots[s]) * a.inverseLength[s] - 0.5)};
}

#if defined(MFADVR_KERNEL_VECTOR_LANES)
typedef double LaneDouble4 __attribute__((vector_size(32)));
typedef double LaneDouble8 __attribute__((vector_size(64)));
typedef std::int64_t LaneMask8 __attribute__((vector_size(64)));
typedef std::int32_t LaneInt8 __attribute__((vector_size(32)));

// locateOnAxis for 8 points at once (host SIMD path): x[i] are physical coordinates, mapped to
// the parameter u = (x - boxMin) * inverseExtent first. The interior spans of a regular axis
// are located for all lanes as vectors; the others (end spans, irregular axes) take
// locateOnAxis one lane at a time. Each lane gets exactly what locateOnAxis gives its u,
// whatever the other lanes hold (for t >= 0, floor is the truncation the conversion does);
// lanes from n on are computed but not finished.
template <int P>
MFADVR_INLINE void locateLanesOnAxis(const KnotAxisView& a, double boxMin, double inverseExtent,
                                     LaneDouble8 x, int n, int* span, float* tau) {
  const int p = P > 0 ? P : a.degree;
  LaneMask8 interior = {};
  if (a.regular) {
    LaneDouble8 u = (x - boxMin) * inverseExtent;
    u = u > 0.0 ? u : 0.0;  // also NaN
    u = u > 1.0 ? 1.0 : u;
    const LaneDouble8 t = (u - a.firstInterior) * a.inverseSpacing;
    interior = (t >= 0.0) & (t < a.interiorSpans);
    const LaneInt8 i = __builtin_convertvector(interior ? t : 0.0, LaneInt8);
    const LaneDouble8 f = __builtin_convertvector(i, LaneDouble8);
    const LaneInt8 s = i + (p + 1);
    const LaneVector8 tl = __builtin_convertvector(t - f - 0.5, LaneVector8);
    __builtin_memcpy(span, &s, sizeof s);
    __builtin_memcpy(tau, &tl, sizeof tl);
  }
  for (int i = 0; i < n; ++i)
    if (!interior[i]) {
      const AxisLocation l = locateOnAxis<P>(a, (x[i] - boxMin) * inverseExtent);
      span[i] = l.span;
      tau[i] = l.tau;
    }
}

// Eight points, each stored as one vector {x, y, z, unused}, as three vectors of coordinates.
// Each point is written and read whole: building the coordinate vectors from lane-by-lane
// stores would make the processor wait for those stores (no store forwarding) on every batch.
MFADVR_INLINE void transposePoints(const LaneDouble4 points[8], LaneDouble8 xyz[3]) {
  LaneDouble8 q[4];  // q[i] = points i and i + 4
  for (int i = 0; i < 4; ++i)
    q[i] = __builtin_shufflevector(points[i], points[i + 4], 0, 1, 2, 3, 4, 5, 6, 7);
  // Even coordinates (x, z) and odd ones (y) of points {0, 1, 4, 5} and {2, 3, 6, 7}.
  const LaneDouble8 even01 = __builtin_shufflevector(q[0], q[1], 0, 8, 2, 10, 4, 12, 6, 14);
  const LaneDouble8 even23 = __builtin_shufflevector(q[2], q[3], 0, 8, 2, 10, 4, 12, 6, 14);
  const LaneDouble8 odd01 = __builtin_shufflevector(q[0], q[1], 1, 9, 3, 11, 5, 13, 7, 15);
  const LaneDouble8 odd23 = __builtin_shufflevector(q[2], q[3], 1, 9, 3, 11, 5, 13, 7, 15);
  xyz[0] = __builtin_shufflevector(even01, even23, 0, 1, 8, 9, 4, 5, 12, 13);
  xyz[1] = __builtin_shufflevector(odd01, odd23, 0, 1, 8, 9, 4, 5, 12, 13);
  xyz[2] = __builtin_shufflevector(even01, even23, 2, 3, 10, 11, 6, 7, 14, 15);
}
#endif

// The p+1 non-zero basis functions at `loc` (N), and with Order >= 1 their first, with Order 2
// also their second derivatives with respect to u (D1, D2). Each array holds BasisWidth<P>
// floats.
template <int P, int Order>
MFADVR_HD MFADVR_INLINE void axisBasis(const KnotAxisView& a, AxisLocation loc, float* N, float* D1,
                                       float* D2) {
  const int p = SplineDegree<P>::of(a.degree);
  const int w = p + 1;
  const float* c = a.poly + static_cast<std::int64_t>(loc.span) * w * w;
  const float t = loc.tau;
  const float inv = static_cast<float>(a.inverseLength[loc.span]);
#if defined(MFADVR_KERNEL_VECTOR_LANES)
  if constexpr (Lanes<P + 1, (P > 0)>::kVector) {
    // Horner's rule on all p+1 functions at once; d/du = d/dtau / (span length).
    constexpr int V = P + 1;
    using Vec = LaneVector<V>;
    Vec coefficients[V], n, d1 = {}, d2 = {};
    for (int k = 0; k < V; ++k) coefficients[k] = loadWhole<Vec>(c + k * V);
    hornerBasis<P, Order>(coefficients, splatLanes<Vec>(t), n, d1, d2);
    storeWhole(n, N);
    if constexpr (Order >= 1) storeWhole(d1 * inv, D1);
    if constexpr (Order >= 2) storeWhole(d2 * (inv * inv), D2);
    return;
  }
#endif
  for (int r = 0; r < w; ++r) N[r] = c[p * w + r];
  if constexpr (Order >= 1)
    for (int r = 0; r < w; ++r) D1[r] = static_cast<float>(p) * c[p * w + r];
  if constexpr (Order >= 2)
    for (int r = 0; r < w; ++r) D2[r] = static_cast<float>(p * (p - 1)) * c[p * w + r];
  for (int k = p - 1; k >= 0; --k) {
    for (int r = 0; r < w; ++r) N[r] = N[r] * t + c[k * w + r];
    if constexpr (Order >= 1)
      if (k >= 1)
        for (int r = 0; r < w; ++r) D1[r] = D1[r] * t + static_cast<float>(k) * c[k * w + r];
    if constexpr (Order >= 2)
      if (k >= 2)
        for (int r = 0; r < w; ++r)
          D2[r] = D2[r] * t + static_cast<float>(k * (k - 1)) * c[k * w + r];
  }
  if constexpr (Order >= 1) {
    for (int r = 0; r < w; ++r) D1[r] *= inv;
    if constexpr (Order >= 2)
      for (int r = 0; r < w; ++r) D2[r] *= inv * inv;
  }
}

// The basis of all three axes at one point.
template <int P, int Order>
struct PointBasis {
  static constexpr int W = BasisWidth<P>::value;
  int p[3];
  float N[3][W];
  float D1[3][Order >= 1 ? W : 1];
  float D2[3][Order >= 2 ? W : 1];
};

template <int P, int Order>
MFADVR_HD MFADVR_INLINE void pointBasis(const SplineView& v, const AxisLocation loc[3],
                                        PointBasis<P, Order>& b) {
  for (int a = 0; a < 3; ++a) {
    b.p[a] = SplineDegree<P>::of(v.axis[a].degree);
    axisBasis<P, Order>(v.axis[a], loc[a], b.N[a], Order >= 1 ? b.D1[a] : nullptr,
                        Order >= 2 ? b.D2[a] : nullptr);
  }
}

// The contraction works on the point's (p+1)^3 control points gathered into a block of rows:
// row (j, k) holds P(0..p0, j, k). First over z, T(j) = sum_k N2[k] row(j, k); then over y,
// R = sum_j N1[j] T(j); then the dot product of R with the x basis. On the host with a fixed
// degree a row is one SIMD value (LaneVector), so each step is a vector multiply-add; otherwise
// it is an array of floats with the same sums in loops. The ray sampler keeps the block while a
// ray stays in a cell.
template <int W>
struct ScalarRow {
  float v[W];
};

template <int P>
struct BlockRow {
#if defined(MFADVR_KERNEL_VECTOR_LANES)
  using type = std::conditional_t<Lanes<P + 1, (P > 0)>::kVector, LaneVector<P + 1>,
                                  ScalarRow<SplineDegree<P>::kWidth>>;
#else
  using type = ScalarRow<SplineDegree<P>::kWidth>;
#endif
};
template <int P>
using Row = typename BlockRow<P>::type;

template <int W>
MFADVR_HD MFADVR_INLINE void rowLoad(ScalarRow<W>& r, const float* src, int n) {
  for (int i = 0; i < n; ++i) r.v[i] = src[i];
}
template <int W>
MFADVR_HD MFADVR_INLINE void rowScale(ScalarRow<W>& acc, float w, const ScalarRow<W>& r, int n) {
  for (int i = 0; i < n; ++i) acc.v[i] = w * r.v[i];
}
template <int W>
MFADVR_HD MFADVR_INLINE void rowFma(ScalarRow<W>& acc, float w, const ScalarRow<W>& r, int n) {
  for (int i = 0; i < n; ++i) acc.v[i] += w * r.v[i];
}
template <int W>
MFADVR_HD MFADVR_INLINE float rowDot(const ScalarRow<W>& r, const float* basis, int n) {
  float s = 0.0f;
  for (int i = 0; i < n; ++i) s += basis[i] * r.v[i];
  return s;
}
template <int W>
MFADVR_HD MFADVR_INLINE float rowComponent(const ScalarRow<W>& r, int i) {
  return r.v[i];
}
#if defined(MFADVR_KERNEL_VECTOR_LANES)
// n is the row length W, fixed by the vector's type (4 lanes for W <= 4, else 8).
template <class V>
MFADVR_INLINE void rowLoad(V& r, const float* src, int n) {
  r = loadLanesOf<V>(src, n);
}
template <class V>
MFADVR_INLINE void rowScale(V& acc, float w, const V& r, int) {
  acc = w * r;
}
template <class V>
MFADVR_INLINE void rowFma(V& acc, float w, const V& r, int) {
  acc = fusedMultiplyAdd(splatLanes<V>(w), r, acc);
}
// basis: a whole vector (BasisWidth).
template <class V>
MFADVR_INLINE float rowDot(const V& r, const float* basis, int n) {
  const V m = r * loadWhole<V>(basis);
  float s = 0.0f;
  for (int i = 0; i < n; ++i) s += m[i];
  return s;
}
template <class V>
MFADVR_INLINE float rowComponent(const V& r, int i) {
  return r[i];
}
#endif

template <int P>
struct ControlBlock {
  static constexpr int W = SplineDegree<P>::kWidth;
  Row<P> rows[W * W];  // row (j, k) at j + W k
};

// Offset of the control block of the spans `loc` in the spline's control array.
template <int P>
MFADVR_HD MFADVR_INLINE std::int64_t blockOffset(const SplineView& v, const AxisLocation loc[3]) {
  const std::int64_t n0 = v.axis[0].count, n1 = v.axis[1].count;
  return (loc[0].span - SplineDegree<P>::of(v.axis[0].degree)) +
         n0 * ((loc[1].span - SplineDegree<P>::of(v.axis[1].degree)) +
               n1 * (loc[2].span - SplineDegree<P>::of(v.axis[2].degree)));
}

template <int P>
MFADVR_HD MFADVR_INLINE void gatherBlock(const SplineView& v, const AxisLocation loc[3],
                                         ControlBlock<P>& block) {
  constexpr int W = ControlBlock<P>::W;
  const std::int64_t n0 = v.axis[0].count, n1 = v.axis[1].count;
  const int p0 = SplineDegree<P>::of(v.axis[0].degree), p1 = SplineDegree<P>::of(v.axis[1].degree),
            p2 = SplineDegree<P>::of(v.axis[2].degree);
  const float* src = v.ctrl + blockOffset<P>(v, loc);
#if defined(MFADVR_KERNEL_VECTOR_LANES)
  if constexpr (Lanes<P + 1, (P > 0)>::kVector) {
    // Whole-vector rows read on into the next control points, except where the block's last
    // row ends the array: the last cells take the loads of p+1 floats below.
    const float* lastRow = src + n0 * (p1 + n1 * p2);
    if (lastRow + sizeof(Row<P>) / sizeof(float) <= v.ctrl + n0 * n1 * v.axis[2].count) {
      // Row pointers stepped by the strides rather than indexed: the indexed form made the
      // compiler keep (p+1)^2 precomputed offsets, spilled to the stack.
      const float* slab = src;
      for (int k = 0; k <= p2; ++k, slab += n0 * n1) {
        const float* row = slab;
        for (int j = 0; j <= p1; ++j, row += n0) block.rows[j + W * k] = loadWhole<Row<P>>(row);
      }
      return;
    }
  }
#endif
  for (int k = 0; k <= p2; ++k)
    for (int j = 0; j <= p1; ++j) rowLoad(block.rows[j + W * k], src + n0 * (j + n1 * k), p0 + 1);
}

// T(j) = sum_k wk[k] row(j, k), j <= p1.
template <int P>
MFADVR_HD MFADVR_INLINE void contractZ(const ControlBlock<P>& B, const int p[3], const float* wk,
                                       Row<P>* T) {
  constexpr int W = ControlBlock<P>::W;
  const int n = SplineDegree<P>::of(p[0]) + 1, p1 = SplineDegree<P>::of(p[1]),
            p2 = SplineDegree<P>::of(p[2]);
  for (int j = 0; j <= p1; ++j) {
    rowScale(T[j], wk[0], B.rows[j], n);
    for (int k = 1; k <= p2; ++k) rowFma(T[j], wk[k], B.rows[j + W * k], n);
  }
}

// R = sum_j wj[j] T(j), then the dot product with wi.
template <int P>
MFADVR_HD MFADVR_INLINE float contractYX(const Row<P>* T, const int p[3], const float* wj,
                                         const float* wi) {
  const int n = SplineDegree<P>::of(p[0]) + 1, p1 = SplineDegree<P>::of(p[1]);
  Row<P> R;
  rowScale(R, wj[0], T[0], n);
  for (int j = 1; j <= p1; ++j) rowFma(R, wj[j], T[j], n);
  return rowDot(R, wi, n);
}

// Value: sum over the block of P(i,j,k) N0[i] N1[j] N2[k]. Tz (W rows) keeps the z contraction
// for a gradient that may follow.
template <int P, int Order>
MFADVR_HD MFADVR_INLINE float contractValue(const ControlBlock<P>& B, const PointBasis<P, Order>& b,
                                            Row<P>* Tz) {
  contractZ<P>(B, b.p, b.N[2], Tz);
  return contractYX<P>(Tz, b.p, b.N[1], b.N[0]);
}

// The three parametric partials from the block, given the value's z contraction Tz:
// d/du0 = (Tz . N1) . D0, d/du1 = (Tz . D1) . N0, d/du2 = (sum_k D2[k] rows) . N1 . N0.
template <int P, int Order>
MFADVR_HD MFADVR_INLINE void contractPartials(const ControlBlock<P>& B,
                                              const PointBasis<P, Order>& b, const Row<P>* Tz,
                                              float g[3]) {
  static_assert(Order >= 1, "the gradient needs first derivatives of the basis");
  Row<P> Td[ControlBlock<P>::W];
  contractZ<P>(B, b.p, b.D1[2], Td);
  g[0] = contractYX<P>(Tz, b.p, b.N[1], b.D1[0]);
  g[1] = contractYX<P>(Tz, b.p, b.D1[1], b.N[0]);
  g[2] = contractYX<P>(Td, b.p, b.N[1], b.N[0]);
}

// Value, gradient and Hessian, out = {v, gx, gy, gz, xx, xy, xz, yy, yz, zz}; accumulated in
// double (this path serves queries, not the renderer's inner loop).
template <int P>
MFADVR_HD MFADVR_INLINE void contractHessian(const ControlBlock<P>& B, const PointBasis<P, 2>& b,
                                             float out[10]) {
  constexpr int W = ControlBlock<P>::W;
  const int p0 = SplineDegree<P>::of(b.p[0]), p1 = SplineDegree<P>::of(b.p[1]),
            p2 = SplineDegree<P>::of(b.p[2]);
  // acc[a][c][e]: sum of P * N0^(a) N1^(c) N2^(e) for derivative orders a + c + e <= 2.
  double acc[3][3][3] = {};
  for (int k = 0; k <= p2; ++k) {
    const float zk[3] = {b.N[2][k], b.D1[2][k], b.D2[2][k]};
    for (int j = 0; j <= p1; ++j) {
      const float yj[3] = {b.N[1][j], b.D1[1][j], b.D2[1][j]};
      const Row<P>& row = B.rows[j + W * k];
      double x[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i <= p0; ++i) {
        const double c = rowComponent(row, i);
        x[0] += double(b.N[0][i]) * c;
        x[1] += double(b.D1[0][i]) * c;
        x[2] += double(b.D2[0][i]) * c;
      }
      for (int a = 0; a < 3; ++a)
        for (int c = 0; a + c < 3; ++c)
          for (int e = 0; a + c + e < 3; ++e) acc[a][c][e] += x[a] * yj[c] * zk[e];
    }
  }
  const double r[10] = {acc[0][0][0], acc[1][0][0], acc[0][1][0], acc[0][0][1], acc[2][0][0],
                        acc[1][1][0], acc[1][0][1], acc[0][2][0], acc[0][1][1], acc[0][0][2]};
  for (int i = 0; i < 10; ++i) out[i] = static_cast<float>(r[i]);
}

// P: as for findSpan.
template <int P = 0>
MFADVR_HD MFADVR_INLINE void locatePoint(const SplineView& v, const double u[3],
                                         AxisLocation loc[3]) {
  // Written out: the compiler keeps a loop over the axes rolled, which serializes them.
  loc[0] = locateOnAxis<P>(v.axis[0], u[0]);
  loc[1] = locateOnAxis<P>(v.axis[1], u[1]);
  loc[2] = locateOnAxis<P>(v.axis[2], u[2]);
}

// Point queries at a parametric coordinate u (clamped to [0,1]^3).
template <int P>
MFADVR_HD MFADVR_INLINE float splineValue(const SplineView& v, const double u[3]) {
  AxisLocation loc[3];
  locatePoint<P>(v, u, loc);
  PointBasis<P, 0> b;
  pointBasis<P, 0>(v, loc, b);
  ControlBlock<P> block;
  gatherBlock<P>(v, loc, block);
  Row<P> Tz[ControlBlock<P>::W];
  return contractValue<P, 0>(block, b, Tz);
}

// out = {value, d/du0, d/du1, d/du2}.
template <int P>
MFADVR_HD MFADVR_INLINE void splineValueGradient(const SplineView& v, const double u[3],
                                                 float out[4]) {
  AxisLocation loc[3];
  locatePoint<P>(v, u, loc);
  PointBasis<P, 1> b;
  pointBasis<P, 1>(v, loc, b);
  ControlBlock<P> block;
  gatherBlock<P>(v, loc, block);
  Row<P> Tz[ControlBlock<P>::W];
  out[0] = contractValue<P, 1>(block, b, Tz);
  contractPartials<P, 1>(block, b, Tz, out + 1);
}

// out = {value, gradient (3), Hessian xx, xy, xz, yy, yz, zz}.
template <int P>
MFADVR_HD MFADVR_INLINE void splineValueGradientHessian(const SplineView& v, const double u[3],
                                                        float out[10]) {
  AxisLocation loc[3];
  locatePoint<P>(v, u, loc);
  PointBasis<P, 2> b;
  pointBasis<P, 2>(v, loc, b);
  ControlBlock<P> block;
  gatherBlock<P>(v, loc, block);
  contractHessian<P>(block, b, out);
}

// The highest degree with a loop of its own (compile-time P); higher degrees take the run-time
// degree path (P = 0), which computes the same function. Each unrolled degree is a set of ray
// loops to compile (degree 7's are the largest), so builds that only test the code (the
// sanitizer and fuzzing presets) set MFADVR_MAX_UNROLLED_DEGREE=3 and compile in a fraction of
// the time (CMakeLists.txt).
#ifndef MFADVR_MAX_UNROLLED_DEGREE
#define MFADVR_MAX_UNROLLED_DEGREE 7
#endif
inline constexpr int kMaxUnrolledDegree = MFADVR_MAX_UNROLLED_DEGREE;
static_assert(kMaxUnrolledDegree >= 0 && kMaxUnrolledDegree <= 7,
              "MFADVR_MAX_UNROLLED_DEGREE is 0..7");

// Calls f.template operator()<P>() with the compile-time degree for `v`: P = 1..MaxP when all
// three degrees are equal, P = 0 (run-time degrees) otherwise. The one switch per render.
template <int MaxP = kMaxUnrolledDegree, class F>
decltype(auto) splineDegreeSwitch(const SplineView& v, F&& f) {
  static_assert(MaxP >= 0 && MaxP <= kMaxUnrolledDegree);
  const int p = v.axis[0].degree;
  if (p == v.axis[1].degree && p == v.axis[2].degree) {
    switch (p) {
      case 1:
        if constexpr (MaxP >= 1) return f.template operator()<1>();
        break;
      case 2:
        if constexpr (MaxP >= 2) return f.template operator()<2>();
        break;
      case 3:
        if constexpr (MaxP >= 3) return f.template operator()<3>();
        break;
      case 4:
        if constexpr (MaxP >= 4) return f.template operator()<4>();
        break;
      case 5:
        if constexpr (MaxP >= 5) return f.template operator()<5>();
        break;
      case 6:
        if constexpr (MaxP >= 6) return f.template operator()<6>();
        break;
      case 7:
        if constexpr (MaxP >= 7) return f.template operator()<7>();
        break;
      default:
        break;
    }
  }
  return f.template operator()<0>();
}

}  // namespace mfadvr
