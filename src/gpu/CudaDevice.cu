#include <cuda_runtime.h>

#include <cstdio>
#include <mutex>

#include "gpu/CudaDevice.h"
#include "gpu/CudaRayLaunch.h"

namespace mfadvr::gpu {

std::string cudaVersionString(int version) {
  return std::to_string(version / 1000) + "." + std::to_string((version % 1000) / 10);
}

std::string CudaDeviceStatus::describe() const {
  if (!usable) return "no usable CUDA GPU: " + reason;
  char text[256];
  std::snprintf(text, sizeof text, "%s (compute %d.%d, %.1f GiB, driver CUDA %s)", name.c_str(),
                computeMajor, computeMinor, double(totalMemory) / (1ull << 30),
                cudaVersionString(driverVersion).c_str());
  return text;
}

namespace {

CudaDeviceStatus probe() {
  CudaDeviceStatus s;
  cudaRuntimeGetVersion(&s.runtimeVersion);
  cudaDriverGetVersion(&s.driverVersion);
  if (s.driverVersion == 0) {
    s.reason = "no NVIDIA driver (libcuda.so) found";
    return s;
  }
  int count = 0;
  cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess || count == 0) {
    s.reason = status == cudaErrorInsufficientDriver
                   ? "the NVIDIA driver supports CUDA " + cudaVersionString(s.driverVersion) +
                         ", this build needs CUDA " + cudaVersionString(s.runtimeVersion)
               : status != cudaSuccess ? std::string(cudaGetErrorString(status))
                                       : std::string("no CUDA device");
    cudaGetLastError();
    return s;
  }
  cudaDeviceProp prop{};
  if ((status = cudaGetDeviceProperties(&prop, 0)) != cudaSuccess ||
      (status = cudaSetDevice(0)) != cudaSuccess || (status = cudaFree(nullptr)) != cudaSuccess) {
    s.reason = std::string("cannot use CUDA device 0: ") + cudaGetErrorString(status);
    cudaGetLastError();
    return s;
  }
  s.name = prop.name;
  s.computeMajor = prop.major;
  s.computeMinor = prop.minor;
  cudaMemGetInfo(&s.freeMemory, &s.totalMemory);
  const std::string kernelProblem = kernelImageProblem();
  if (!kernelProblem.empty()) {
    s.reason = s.name + " (compute " + std::to_string(prop.major) + "." +
               std::to_string(prop.minor) + "): " + kernelProblem;
    return s;
  }
  s.usable = true;
  return s;
}

}  // namespace

CudaDeviceStatus cudaDeviceStatus() {
  static std::once_flag once;
  static CudaDeviceStatus first;
  std::call_once(once, [] { first = probe(); });
  CudaDeviceStatus s = first;
  if (s.usable) cudaMemGetInfo(&s.freeMemory, &s.totalMemory);
  return s;
}

}  // namespace mfadvr::gpu
