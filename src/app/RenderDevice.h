#pragma once
// --device auto|cpu|cuda: where the renderer runs. cpu: the TBB ray caster; cuda: the CUDA
// backend, or an error (exit 1) saying why it cannot run; auto: the GPU when this build has the
// CUDA backend, a usable GPU is present and the method runs there, else the CPU.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "core/render/DeviceRenderer.h"
#include "core/render/ReconstructionMethod.h"

namespace mfadvr::app {

struct RenderDevice {
  std::unique_ptr<DeviceRenderer> renderer;  // null: the CPU
  std::string name;                          // "cpu" or "cuda"
  std::string description;                   // the device, and for auto why it was chosen
};

// Adds --device to `sub`, storing into `choice`.
void addDeviceOption(CLI::App* sub, std::string& choice);

// Throws mfadvr::Error for `cuda` when no GPU can render `spec`.
RenderDevice openRenderDevice(const std::string& choice, const MethodSpec& spec);

// Whether this build has the CUDA backend.
bool buildHasCuda();

}  // namespace mfadvr::app
