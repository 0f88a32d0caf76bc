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
