#pragma once
// Whether a CUDA GPU can run the renderer here, and which. Plain C++ interface.
#include <cstddef>
#include <string>

namespace mfadvr::gpu {

struct CudaDeviceStatus {
  bool usable = false;
  std::string reason;  // when not usable: no driver, no device, driver too old, no kernel image
  std::string name;    // device 0
  int computeMajor = 0, computeMinor = 0;
  std::size_t totalMemory = 0, freeMemory = 0;  // bytes
  int driverVersion = 0;   // CUDA version the driver supports (e.g. 13000), 0 without a driver
  int runtimeVersion = 0;  // CUDA runtime this program was built with

  // "NVIDIA H100 80GB HBM3 (compute 9.0, 79 GiB, driver CUDA 13.0)" or the reason.
  std::string describe() const;
};

// Probes device 0: creates its context and checks that this build's kernels load on it (a
// driver older than the build's PTX, or a GPU older than sm_75, is reported here rather than at
// the first frame). Cheap after the first call.
CudaDeviceStatus cudaDeviceStatus();

// "13.0" from 13000.
std::string cudaVersionString(int version);

}  // namespace mfadvr::gpu
