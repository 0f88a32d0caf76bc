#pragma once
// One macro for code that both the host compiler and nvcc compile: the per-sample hot path
// (spline kernel, transfer-function table, shading, per-ray integration) is written once over
// plain view structs and marked MFADVR_HD; under nvcc it becomes __host__ __device__, elsewhere
// nothing. Such code uses no std::vector, exceptions, Eigen expressions or function pointers.
//
// MFADVR_INLINE forces inlining: the hot functions take the degree as a compile-time constant
// and must unroll into their callers.
//
// MFADVR_OUTLINE keeps a function out of its callers: per-ray paths taken by a ray as a whole
// (the blend modes other than composite), which inlined into every ray loop of every kernel
// variant would multiply the compile time and code size for nothing.
#if defined(__CUDACC__)
#define MFADVR_HD __host__ __device__
#define MFADVR_INLINE __forceinline__
#define MFADVR_OUTLINE __noinline__
#elif defined(__GNUC__)
#define MFADVR_HD
#define MFADVR_INLINE inline __attribute__((always_inline))
#define MFADVR_OUTLINE inline __attribute__((noinline))
#else
#define MFADVR_HD
#define MFADVR_INLINE inline
#define MFADVR_OUTLINE inline
#endif

#include <cmath>
#include <type_traits>

#if !defined(__CUDACC__) && defined(__AVX__)
#include <immintrin.h>
#endif

namespace mfadvr {

// Number conversion for a scalar (static_cast) or, on the host, a GCC vector
// (__builtin_convertvector): formulas written once for one value and for SIMD lanes use it.
template <class To, class From>
MFADVR_HD MFADVR_INLINE To convertLanes(From x) {
  if constexpr (std::is_arithmetic_v<From>) {
    return static_cast<To>(x);
  } else {
#if !defined(__CUDACC__)
    return __builtin_convertvector(x, To);
#endif
  }
}

// f applied to each lane of a host vector of floats (F), for functions with no vector form.
template <class F, class Fn>
MFADVR_INLINE F mapLanes(F x, Fn f) {
  F r;
  for (unsigned l = 0; l < sizeof(F) / sizeof(float); ++l) r[l] = f(x[l]);
  return r;
}

// The correctly rounded square root of a float or, on the host, of each lane of a vector of
// eight floats (sqrtf per lane; one instruction with AVX).
template <class F>
MFADVR_HD MFADVR_INLINE F squareRoot(F x) {
  if constexpr (std::is_arithmetic_v<F>) {
    return sqrtf(x);
  } else {
#if !defined(__CUDACC__) && defined(__AVX__)
    if constexpr (sizeof(F) == 32)
      return reinterpret_cast<F>(_mm256_sqrt_ps(reinterpret_cast<__m256>(x)));
#endif
    return mapLanes(x, [](float v) { return sqrtf(v); });
  }
}

// a * b + c for floats or, on the host, vectors of 4 or 8 floats: rounded once where the target
// has FMA (and on the device), twice otherwise, whatever the optimizer would contract. Formulas
// computed both for one value and for SIMD lanes (the spline kernels, shading) make every
// multiply-add explicit through here, so that each lane rounds as the single value does; left
// to the compiler, which product of `a * b + c * d` it fuses depends on the code around it.
template <class F>
MFADVR_HD MFADVR_INLINE F fusedMultiplyAdd(F a, F b, F c) {
  if constexpr (std::is_arithmetic_v<F>) {
#if defined(__CUDACC__) || defined(__FMA__)
    return fmaf(a, b, c);
#else
    return a * b + c;
#endif
  } else {
#if !defined(__CUDACC__) && defined(__FMA__)
    if constexpr (sizeof(F) == 16)
      return reinterpret_cast<F>(_mm_fmadd_ps(
          reinterpret_cast<__m128>(a), reinterpret_cast<__m128>(b), reinterpret_cast<__m128>(c)));
    if constexpr (sizeof(F) == 32)
      return reinterpret_cast<F>(_mm256_fmadd_ps(
          reinterpret_cast<__m256>(a), reinterpret_cast<__m256>(b), reinterpret_cast<__m256>(c)));
#endif
    return a * b + c;  // no FMA on x86: two roundings; the eight-lane kernel needs FMA anyway
  }
}

}  // namespace mfadvr
