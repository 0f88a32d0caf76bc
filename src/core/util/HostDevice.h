#pragma once
// One macro for code that both the host compiler and nvcc compile: the per-sample hot path
// (spline kernel, transfer-function table, shading, per-ray integration) is written once over
// plain view structs and marked MFADVR_HD; under nvcc it becomes __host__ __device__, elsewhere
// nothing. Such code uses no std::vector, exceptions, Eigen expressions or function pointers.
//
// MFADVR_INLINE forces inlining: the hot functions take the degree as a compile-time constant
// and must unroll into their callers.
#if defined(__CUDACC__)
#define MFADVR_HD __host__ __device__
#define MFADVR_INLINE __forceinline__
#elif defined(__GNUC__)
#define MFADVR_HD
#define MFADVR_INLINE inline __attribute__((always_inline))
#else
#define MFADVR_HD
#define MFADVR_INLINE inline
#endif

#include <type_traits>

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

}  // namespace mfadvr
