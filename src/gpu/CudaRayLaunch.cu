// One thread per pixel, 16 x 8 pixels per block (neighbouring rays walk neighbouring cells, so
// a block's gathers share cache lines). The degree is a template parameter for 1..4 on every
// axis, as on the CPU; other and mixed degrees take the run-time-degree kernel. The composite
// blend and the other blends are separate kernels (RayBlends), and the parameters are
// __grid_constant__ (read where they are, not copied to each thread's stack): together 1.9-2.4x
// faster composite kernels than one kernel for every blend with copied parameters
// (docs/benchmarks.md).
#include <cuda_runtime.h>

#include "core/render/kernel/RayIntegrator.h"
#include "gpu/CudaCheck.h"
#include "gpu/CudaRayLaunch.h"

namespace mfadvr::gpu {

namespace {

constexpr int kBlockX = 16, kBlockY = 8;

// Per-block sums of the counters, then one atomic per block and counter.
__device__ void addCounters(const RayCounters& c, DeviceRayCounters* total) {
  __shared__ unsigned long long sums[4];
  const int lane = threadIdx.x + blockDim.x * threadIdx.y;
  if (lane < 4) sums[lane] = 0;
  __syncthreads();
  atomicAdd(&sums[0], static_cast<unsigned long long>(c.samples));
  atomicAdd(&sums[1], static_cast<unsigned long long>(c.hits));
  atomicAdd(&sums[2], static_cast<unsigned long long>(c.terminated));
  atomicAdd(&sums[3], static_cast<unsigned long long>(c.skipped));
  __syncthreads();
  if (lane == 0) {
    atomicAdd(&total->samples, sums[0]);
    atomicAdd(&total->hits, sums[1]);
    atomicAdd(&total->terminated, sums[2]);
    atomicAdd(&total->skipped, sums[3]);
  }
}

// One ray per thread with a Sampler made from `view` (ModelView for the model, GridView for the
// trilinear grid), as the CPU driver's tiles do it.
template <bool Masked, bool Shade, RayBlends Blends, class Sampler, class View>
__global__ void __launch_bounds__(kBlockX* kBlockY)
    raysKernel(const __grid_constant__ RayParams params, const __grid_constant__ View view,
               float* image, DeviceRayCounters* counters) {
  const int x = blockIdx.x * blockDim.x + threadIdx.x;
  const int y = blockIdx.y * blockDim.y + threadIdx.y;
  RayCounters c;
  // Threads outside the image still take part in the block's counter sums.
  if (x < params.camera.width && y < params.camera.height) {
    Sampler sampler(view);
    integrateRay<Masked, Shade, Blends>(
        params, sampler, x, y, image + 4 * (static_cast<long long>(y) * params.camera.width + x),
        c);
  }
  addCounters(c, counters);
}

// Runs launch(grid, block) between two events; returns the GPU time in seconds.
template <class Launch>
double timedLaunch(const CameraRays& camera, Launch&& launch) {
  const dim3 block(kBlockX, kBlockY);
  const dim3 grid((camera.width + kBlockX - 1) / kBlockX, (camera.height + kBlockY - 1) / kBlockY);
  cudaEvent_t start, stop;
  cudaCheck(cudaEventCreate(&start), "creating an event");
  cudaCheck(cudaEventCreate(&stop), "creating an event");
  cudaEventRecord(start);
  launch(grid, block);
  cudaEventRecord(stop);
  const cudaError_t launched = cudaGetLastError();
  const cudaError_t finished = cudaEventSynchronize(stop);
  float ms = 0.0f;
  cudaEventElapsedTime(&ms, start, stop);
  cudaEventDestroy(start);
  cudaEventDestroy(stop);
  cudaCheck(launched, "launching the ray kernel");
  cudaCheck(finished, "running the ray kernel");
  return ms * 1e-3;
}

// The composite kernel or the other blends' kernel, as params.blend asks.
template <bool Masked, bool Shade, class Sampler, class View>
void launchBlend(const RayParams& params, const View& view, float* image,
                 DeviceRayCounters* counters, dim3 grid, dim3 block) {
  if (params.blend == BlendMode::Composite)
    raysKernel<Masked, Shade, RayBlends::Composite, Sampler, View>
        <<<grid, block>>>(params, view, image, counters);
  else
    raysKernel<Masked, Shade, RayBlends::Others, Sampler, View>
        <<<grid, block>>>(params, view, image, counters);
}

template <int P, bool Masked, bool Shade, bool Skip>
void launchModel(const ModelLaunch& l, dim3 grid, dim3 block) {
  launchBlend<Masked, Shade, SplineRaySampler<P, Skip, Shade>>(l.params, l.view, l.image,
                                                               l.counters, grid, block);
}

template <int P>
void launchForDegree(const ModelLaunch& l, dim3 grid, dim3 block) {
  // Eight kernels per degree and blend kind, as on the CPU: with and without the mask test (and
  // a mesh's boundary), shading, skipping.
  const int key = (l.masked ? 4 : 0) + (l.shade ? 2 : 0) + (l.skip ? 1 : 0);
  switch (key) {
    case 0:
      return launchModel<P, false, false, false>(l, grid, block);
    case 1:
      return launchModel<P, false, false, true>(l, grid, block);
    case 2:
      return launchModel<P, false, true, false>(l, grid, block);
    case 3:
      return launchModel<P, false, true, true>(l, grid, block);
    case 4:
      return launchModel<P, true, false, false>(l, grid, block);
    case 5:
      return launchModel<P, true, false, true>(l, grid, block);
    case 6:
      return launchModel<P, true, true, false>(l, grid, block);
    default:
      return launchModel<P, true, true, true>(l, grid, block);
  }
}

}  // namespace

double launchModelRays(const ModelLaunch& l) {
  return timedLaunch(l.params.camera, [&](dim3 grid, dim3 block) {
    const auto& axis = l.view.spline.axis;
    const int p = axis[0].degree;
    const bool same = p == axis[1].degree && p == axis[2].degree;
    switch (same ? p : 0) {
      case 1:
        return launchForDegree<1>(l, grid, block);
      case 2:
        return launchForDegree<2>(l, grid, block);
      case 3:
        return launchForDegree<3>(l, grid, block);
      case 4:
        return launchForDegree<4>(l, grid, block);
      default:
        return launchForDegree<0>(l, grid, block);
    }
  });
}

double launchGridRays(const GridLaunch& l) {
  return timedLaunch(l.params.camera, [&](dim3 grid, dim3 block) {
    if (l.shade)
      launchBlend<false, true, TrilinearRaySampler<true>>(l.params, l.grid, l.image, l.counters,
                                                          grid, block);
    else
      launchBlend<false, false, TrilinearRaySampler<false>>(l.params, l.grid, l.image, l.counters,
                                                            grid, block);
  });
}

std::string kernelImageProblem() {
  cudaFuncAttributes attributes;
  const cudaError_t status = cudaFuncGetAttributes(
      &attributes,
      raysKernel<false, true, RayBlends::Composite, SplineRaySampler<3, true, true>, ModelView>);
  if (status == cudaSuccess) return {};
  cudaGetLastError();
  if (status == cudaErrorNoKernelImageForDevice)
    return "this build has no code for its architecture (built for compute 7.5 and later)";
  if (status == cudaErrorUnsupportedPtxVersion)
    return "the driver is older than this build's CUDA; update the NVIDIA driver";
  return cudaGetErrorString(status);
}

}  // namespace mfadvr::gpu
