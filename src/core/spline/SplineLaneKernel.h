#pragma once
// The spline kernel for eight points at once, one SIMD lane per point (host, AVX2, one degree
// P = 1..3 on all axes): the values, and optionally the parametric gradients, of a batch of
// located points (SplineRaySampler's batches of samples along a ray).
//
// SplineKernel.h evaluates one point with its control rows as vectors: (p+1)^2 row loads, then
// multiply-adds over rows and a horizontal sum. Here each lane is a point: every lane's rows are
// loaded and transposed, so that the contraction over the (p+1)^3 control points runs on whole
// vectors with no horizontal step, and the basis of points in the shared spans of an axis
// (KnotAxisView::sharedFirst) comes from one set of coefficients. Per lane the arithmetic is the
// per-point kernel's, operation for operation (Horner's rule, the z, y, x contraction order,
// explicit fused multiply-adds, the final sum of unfused products), so each lane's result
// equals splineValue /
// splineValueGradient bit for bit (SplineLaneKernelTest); that keeps images identical whichever
// path a sample takes.
#include <cstdint>

#include "core/spline/SplineKernel.h"

#if defined(MFADVR_KERNEL_VECTOR_LANES) && defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define MFADVR_SPLINE_LANE_KERNEL 1
#endif

namespace mfadvr {

// Whether evaluateLanes exists for degree P on this build.
template <int P>
struct SplineLaneKernel {
#if defined(MFADVR_SPLINE_LANE_KERNEL)
  static constexpr bool kAvailable = P >= 1 && P <= 3;
#else
  static constexpr bool kAvailable = false;
#endif
};

#if defined(MFADVR_SPLINE_LANE_KERNEL)

using Lanes8 = LaneVector8;

// Whether any lane of a mask (each lane 0 or -1) is set, and how many are.
MFADVR_INLINE bool anyLane(LaneInt8 mask) {
  return _mm256_movemask_ps(reinterpret_cast<__m256>(mask)) != 0;
}
MFADVR_INLINE int countLanes(LaneInt8 mask) {
  return __builtin_popcount(_mm256_movemask_ps(reinterpret_cast<__m256>(mask)));
}

// x * y rounded on its own: the per-point kernel sums the lanes of a vector product (rowDot),
// which the compiler cannot fuse into its additions; the barrier keeps it from fusing these.
MFADVR_INLINE Lanes8 unfusedProduct(Lanes8 x, Lanes8 y) {
  Lanes8 r = x * y;
  asm("" : "+x"(r));
  return r;
}

// The first P+1 floats at rows[i] + offset of the eight lanes, transposed: X[x][i].
template <int P>
MFADVR_INLINE void transposeRows(const float* const rows[8], std::int64_t offset, Lanes8 X[4]) {
  const auto pair = [&](int lo, int hi) {
    return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(rows[lo] + offset)),
                                _mm_loadu_ps(rows[hi] + offset), 1);
  };
  const __m256 t0 = pair(0, 4), t1 = pair(1, 5), t2 = pair(2, 6), t3 = pair(3, 7);
  const __m256 u0 = _mm256_unpacklo_ps(t0, t1), u2 = _mm256_unpacklo_ps(t2, t3);
  X[0] = _mm256_shuffle_ps(u0, u2, _MM_SHUFFLE(1, 0, 1, 0));
  if constexpr (P >= 1) X[1] = _mm256_shuffle_ps(u0, u2, _MM_SHUFFLE(3, 2, 3, 2));
  if constexpr (P >= 2) {
    const __m256 u1 = _mm256_unpackhi_ps(t0, t1), u3 = _mm256_unpackhi_ps(t2, t3);
    X[2] = _mm256_shuffle_ps(u1, u3, _MM_SHUFFLE(1, 0, 1, 0));
    if constexpr (P >= 3) X[3] = _mm256_shuffle_ps(u1, u3, _MM_SHUFFLE(3, 2, 3, 2));
  }
}

// The basis of one axis at eight located points: N[r] (and D1[r] with Order 1) holds function
// r (derivative) at every lane. When every lane lies in the axis's shared spans the
// coefficients are broadcast from one span; otherwise each lane's are loaded and transposed like
// control rows. Horner's rule (hornerBasis, as in axisBasis) then runs per function over the lanes.
template <int P, int Order>
MFADVR_INLINE void laneBasis(const KnotAxisView& a, LaneInt8 s, Lanes8 t, Lanes8 N[P + 1],
                             Lanes8 D1[P + 1]) {
  constexpr int V = P + 1;
  const LaneInt8 outside = (s < a.sharedFirst) | (s > a.sharedLast);
  Lanes8 C[V][4];  // C[k][r]: the coefficients of tau^k of function r
  Lanes8 inv;      // d tau / du
  if (!anyLane(outside)) {
    const float* c = a.poly + static_cast<std::int64_t>(a.sharedFirst) * V * V;
#pragma GCC unroll 8
    for (int k = 0; k <= P; ++k)
#pragma GCC unroll 8
      for (int r = 0; r < V; ++r) C[k][r] = splatLanes<Lanes8>(c[k * V + r]);
    if constexpr (Order >= 1)
      inv = splatLanes<Lanes8>(static_cast<float>(a.inverseLength[a.sharedFirst]));
  } else {
    const float* rows[8];
#pragma GCC unroll 8
    for (int i = 0; i < 8; ++i) rows[i] = a.poly + static_cast<std::int64_t>(s[i]) * V * V;
#pragma GCC unroll 8
    for (int k = 0; k <= P; ++k) transposeRows<P>(rows, k * V, C[k]);
    if constexpr (Order >= 1) {
      const auto l = [&](int i) { return static_cast<float>(a.inverseLength[s[i]]); };
      inv =
          reinterpret_cast<Lanes8>(_mm256_setr_ps(l(0), l(1), l(2), l(3), l(4), l(5), l(6), l(7)));
    }
  }
#pragma GCC unroll 8
  for (int r = 0; r < V; ++r) {
    Lanes8 c[V], d1 = {}, unused = {};
#pragma GCC unroll 8
    for (int k = 0; k < V; ++k) c[k] = C[k][r];
    hornerBasis<P, Order>(c, t, N[r], d1, unused);
    if constexpr (Order >= 1) D1[r] = d1 * inv;
  }
}

// contractYX per lane: R = sum_j wj[j] T[j] (T[j][x]), then the sum of R[x] wi[x] in x order.
template <int P>
MFADVR_INLINE Lanes8 laneContractYX(const Lanes8 T[P + 1][P + 1], const Lanes8 wj[P + 1],
                                    const Lanes8 wi[P + 1]) {
  Lanes8 sum = splatLanes<Lanes8>(0.0f);
  Lanes8 R[P + 1];
#pragma GCC unroll 8
  for (int x = 0; x <= P; ++x) {
    R[x] = wj[0] * T[0][x];
#pragma GCC unroll 8
    for (int j = 1; j <= P; ++j) R[x] = fusedMultiplyAdd(wj[j], T[j][x], R[x]);
  }
#pragma GCC unroll 8
  for (int x = 0; x <= P; ++x) sum = sum + unfusedProduct(R[x], wi[x]);
  return sum;
}

// Values (and with Order 1 parametric gradients: grad[a] over the lanes) at eight located
// points: span[a][i], tau[a][i] as locateOnAxis gives them, for lanes i < n (1..8); the lanes
// from n on repeat lane 0. Returns false, computing nothing, when a lane's block would need the
// loads of the array's last cells (gatherBlock's narrow path) or the array has 2^31 floats or more:
// the caller evaluates that batch per point.
template <int P, int Order>
MFADVR_INLINE bool evaluateLanes(const SplineView& v, const int span[3][8], const float tau[3][8],
                                 int n, float value[8], float grad[3][8]) {
  static_assert(SplineLaneKernel<P>::kAvailable, "no lane kernel for this degree");
  const std::int64_t n0 = v.axis[0].count, n1 = v.axis[1].count;
  const std::int64_t total = n0 * n1 * v.axis[2].count;
  const std::int64_t lastRow = n0 * (P + n1 * P);
  // Each lane's block offset, as 32-bit vectors (arrays below 2^31 floats; larger ones take
  // the per-point path), and whether every lane's whole-vector row loads stay in the array.
  if (total >= (std::int64_t(1) << 31) - 64) return false;
  // Lanes from n on take lane 0's location, selected in registers: written lane by lane into
  // the arrays, they would stall the vector loads (no store forwarding).
  LaneInt8 s[3];
  Lanes8 t[3];
  __builtin_memcpy(s, span, sizeof s);
  __builtin_memcpy(t, tau, sizeof t);
  const LaneInt8 used = LaneInt8{0, 1, 2, 3, 4, 5, 6, 7} < n;
#pragma GCC unroll 8
  for (int a = 0; a < 3; ++a) {
    s[a] = used ? s[a] : LaneInt8{} + s[a][0];
    t[a] = used ? t[a] : splatLanes<Lanes8>(t[a][0]);
  }
  const LaneInt8 offset = (s[0] - P) + int(n0) * ((s[1] - P) + int(n1) * (s[2] - P));
  const LaneInt8 tooFar = offset > int(total - lastRow - 4);
  if (anyLane(tooFar)) return false;
  const float* rows[8];
#pragma GCC unroll 8
  for (int i = 0; i < 8; ++i) rows[i] = v.ctrl + offset[i];
  Lanes8 N[3][P + 1], D1[3][P + 1];
#pragma GCC unroll 8
  for (int a = 0; a < 3; ++a) laneBasis<P, Order>(v.axis[a], s[a], t[a], N[a], D1[a]);

  // z contraction, as contractZ: Tz[j][x] = sum_k N2[k] P(x, j, k) (and Td with D1 of z).
  Lanes8 Tz[P + 1][P + 1], Td[P + 1][P + 1];
#pragma GCC unroll 8
  for (int k = 0; k <= P; ++k)
#pragma GCC unroll 8
    for (int j = 0; j <= P; ++j) {
      Lanes8 X[4];
      transposeRows<P>(rows, n0 * (j + n1 * k), X);
#pragma GCC unroll 8
      for (int x = 0; x <= P; ++x) {
        if (k == 0) {
          Tz[j][x] = N[2][0] * X[x];
          if constexpr (Order >= 1) Td[j][x] = D1[2][0] * X[x];
        } else {
          Tz[j][x] = fusedMultiplyAdd(N[2][k], X[x], Tz[j][x]);
          if constexpr (Order >= 1) Td[j][x] = fusedMultiplyAdd(D1[2][k], X[x], Td[j][x]);
        }
      }
    }
  const Lanes8 result = laneContractYX<P>(Tz, N[1], N[0]);
  __builtin_memcpy(value, &result, sizeof result);
  if constexpr (Order >= 1) {
    // As contractPartials: d/du0 from Tz with D1 of x, d/du1 with D1 of y, d/du2 from Td.
    const Lanes8 g[3] = {laneContractYX<P>(Tz, N[1], D1[0]), laneContractYX<P>(Tz, D1[1], N[0]),
                         laneContractYX<P>(Td, N[1], N[0])};
#pragma GCC unroll 8
    for (int a = 0; a < 3; ++a) __builtin_memcpy(grad[a], &g[a], sizeof g[a]);
  }
  return true;
}

#endif  // MFADVR_SPLINE_LANE_KERNEL

}  // namespace mfadvr
