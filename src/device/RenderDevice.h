#pragma once
// Where the renderer runs (`mfadvr render --device`, vtkMFAVolumeMapper::SetDevice): auto, cpu
// or cuda. cpu: the TBB ray caster; cuda: the CUDA backend, or an error saying why it cannot
// run; auto: the GPU when this build has the CUDA backend, a usable GPU is present and the
// method runs there, else the CPU, with the reason. Builds without nvcc have only the CPU.
#include <memory>
#include <string>

#include "core/render/DeviceRenderer.h"
#include "core/render/ReconstructionMethod.h"

namespace mfadvr {

struct RenderDevice {
  std::unique_ptr<DeviceRenderer> renderer;  // null: the CPU
  std::string name;                          // "cpu" or "cuda"
  std::string description;                   // the device, and for auto why it was chosen
};

// `choice`: "auto", "cpu" or "cuda". Throws mfadvr::Error for "cuda" when no GPU can render
// `spec`, and for any other word.
RenderDevice openRenderDevice(const std::string& choice, const MethodSpec& spec);

}  // namespace mfadvr
