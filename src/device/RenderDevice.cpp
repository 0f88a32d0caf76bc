#include "device/RenderDevice.h"

#include <tbb/info.h>

#include "core/util/Error.h"
#if defined(MFADVR_HAVE_CUDA)
#include "gpu/CudaRenderer.h"
#endif

namespace mfadvr {

namespace {

const std::string kCudaRequired = "device 'cuda': ";

RenderDevice cpu(const std::string& why) {
  RenderDevice d;
  d.name = "cpu";
  d.description = "CPU (" + std::to_string(tbb::info::default_concurrency()) + " threads)";
  if (!why.empty()) d.description += "; " + why;
  return d;
}

}  // namespace

RenderDevice openRenderDevice(const std::string& choice, const MethodSpec& spec) {
  if (choice == "cpu") return cpu("");
  if (choice != "auto" && choice != "cuda")
    throw Error("unknown device '" + choice + "'; choose auto, cpu or cuda");
  const bool required = choice == "cuda";
  if (!deviceRendersMethod(spec)) {
    if (required) throw Error(kCudaRequired + whyNotOnDevice(spec));
    return cpu(whyNotOnDevice(spec));
  }
#if defined(MFADVR_HAVE_CUDA)
  const gpu::CudaDeviceStatus status = gpu::cudaDeviceStatus();
  if (!status.usable) {
    if (required) throw Error(kCudaRequired + status.describe());
    return cpu(status.describe());
  }
  RenderDevice d;
  d.renderer = std::make_unique<gpu::CudaRenderer>();
  d.name = "cuda";
  d.description = d.renderer->description();
  return d;
#else
  const std::string why =
      "this mfadvr was built without the CUDA backend (configured with -DMFADVR_CUDA=OFF, as the "
      "paraview preset is, or without nvcc)";
  if (required) throw Error(kCudaRequired + why);
  return cpu(why);
#endif
}

}  // namespace mfadvr
