#pragma once
// The CUDA kernels of the renderer: one thread per pixel runs the shared per-ray integration
// (core/render/kernel/RayIntegrator.h) over the shared samplers, exactly as the CPU driver's
// tiles do. Plain C++ interface: every pointer inside the structs passed here must already
// point to GPU memory (CudaRenderer.cpp makes those copies).
#include <string>

#include "core/render/kernel/RayParams.h"
#include "core/render/kernel/SplineRaySampler.h"
#include "core/render/kernel/TrilinearKernel.h"

namespace mfadvr::gpu {

// Totals of the per-thread RayCounters, in GPU memory (zeroed by the caller).
struct DeviceRayCounters {
  unsigned long long samples, hits, terminated, skipped;
};

struct ModelLaunch {
  RayParams params;
  ModelView view;
  bool masked = false, shade = false, skip = false;
  float* image = nullptr;  // width * height RGBA floats, row 0 at the top
  DeviceRayCounters* counters = nullptr;
};

struct GridLaunch {
  RayParams params;
  GridView grid;
  bool shade = false;
  float* image = nullptr;
  DeviceRayCounters* counters = nullptr;
};

// Runs the MFA model's rays and waits for them; throws mfadvr::Error on a CUDA error.
// Returns the kernel's own time in seconds (CUDA events).
double launchModelRays(const ModelLaunch& launch);
// The same for the trilinear grid filter.
double launchGridRays(const GridLaunch& launch);

// Empty when this build's kernels can run on the current device; else why not (no kernel
// image for its architecture, or a driver too old for the PTX).
std::string kernelImageProblem();

}  // namespace mfadvr::gpu
