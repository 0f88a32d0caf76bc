#pragma once
// A renderer that runs on another processor than the host's CPU cores: the CUDA backend
// (src/gpu/CudaRenderer.h) implements it. The core, the command and the VTK module see only this
// interface, so that none of them needs GPU headers, and a build without CUDA still links.
//
// An implementation runs the same per-ray integration and samplers as the CPU driver
// (render/kernel/), with the same RayParams, so that its images differ from the CPU's only by
// floating-point rounding.
#include <string>

#include "core/field/ModelField.h"
#include "core/image/Image.h"
#include "core/render/RenderSettings.h"

namespace mfadvr {

class PaddedGrid;

class DeviceRenderer {
 public:
  virtual ~DeviceRenderer() = default;
  // Which device, for messages and reports ("CUDA: NVIDIA H100 80GB HBM3 (compute 9.0, ...)").
  virtual std::string description() const = 0;
  // As renderModel() (RayCaster.h). The model's arrays stay on the device for later frames of
  // the same model. Throws mfadvr::Error (also when the model does not fit in device memory).
  virtual Image renderModel(const ModelField& field, const RenderSettings& settings,
                            RenderStats* stats) = 0;
  // Drops the model kept on the device, so that the next renderModel() uploads its model: a
  // kept model is recognized by its arrays' addresses, which a model read after another was
  // freed may reuse (blocks read one at a time).
  virtual void forgetModel() {}
  // As renderVolume(GridField<TrilinearFilter>): trilinear reconstruction of a padded grid.
  virtual Image renderTrilinear(const PaddedGrid& grid, const RenderSettings& settings,
                                RenderStats* stats) = 0;
};

}  // namespace mfadvr
