#pragma once
// CUDA runtime errors as mfadvr::Error (for .cu files only).
#include <cuda_runtime.h>

#include <string>

#include "core/util/Error.h"

namespace mfadvr::gpu {

inline void cudaCheck(cudaError_t status, const std::string& what) {
  if (status != cudaSuccess)
    throw Error("CUDA: " + what + ": " + cudaGetErrorString(status) + " (" +
                cudaGetErrorName(status) + ")");
}

}  // namespace mfadvr::gpu
