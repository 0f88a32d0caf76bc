// Compiles the shared per-sample code (spline kernel, ray sampler, per-ray integration) with
// nvcc in a __global__ function, so that every build proves that the hot path stays valid device
// code. Not linked into anything: the CUDA renderer (a driver around the same functions) is a
// separate library. One thread per pixel, as that driver will run it.
#include "core/render/kernel/RayIntegrator.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {

template <int P, bool Masked, bool Shade, bool Skip>
__global__ void integrateRaysCheck(RayParams params, ModelView model, float* image,
                                   unsigned long long* samples) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= params.camera.width || y >= params.camera.height) return;
  SplineRaySampler<P, Skip, Shade> sampler(model);
  RayCounters counters;
  integrateRay<Masked, Shade>(params, sampler, x, y,
                              image + 4 * (static_cast<long long>(y) * params.camera.width + x),
                              counters);
  atomicAdd(samples, static_cast<unsigned long long>(counters.samples));
}

// A fixed degree and the run-time one; every mask/shade/skip combination of one of them.
template __global__ void integrateRaysCheck<3, false, true, true>(RayParams, ModelView, float*,
                                                                  unsigned long long*);
template __global__ void integrateRaysCheck<2, true, false, false>(RayParams, ModelView, float*,
                                                                   unsigned long long*);
template __global__ void integrateRaysCheck<0, true, true, true>(RayParams, ModelView, float*,
                                                                 unsigned long long*);
template __global__ void integrateRaysCheck<0, false, false, false>(RayParams, ModelView, float*,
                                                                    unsigned long long*);

}  // namespace mfadvr
