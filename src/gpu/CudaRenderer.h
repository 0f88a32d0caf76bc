#pragma once
// The CUDA backend of the ray caster: a DeviceRenderer that runs the shared per-ray integration
// (core/render/kernel/) with one GPU thread per pixel. Plain C++ header: no CUDA or VTK headers.
//
// A model's arrays (control points, knots, basis polynomials, mask) are uploaded once and kept
// for the next frames of the same model; per frame only the transfer-function table, the
// empty-space flags, ray ends (if any) and the image travel. A model is recognized by the
// addresses and sizes of its arrays: call forgetModel() after changing a model in place.
#include <memory>

#include "core/render/DeviceRenderer.h"
#include "gpu/CudaDevice.h"

namespace mfadvr::gpu {

class CudaRenderer final : public DeviceRenderer {
 public:
  // Throws mfadvr::Error with the reason when no usable CUDA GPU is present.
  CudaRenderer();
  ~CudaRenderer() override;

  std::string description() const override;
  Image renderModel(const ModelField& field, const RenderSettings& settings,
                    RenderStats* stats) override;
  Image renderTrilinear(const PaddedGrid& grid, const RenderSettings& settings,
                        RenderStats* stats) override;

  void forgetModel() override;
  const CudaDeviceStatus& device() const { return status_; }
  // GPU time of the last frame's ray kernel alone (no transfers), seconds.
  double lastKernelSeconds() const { return lastKernelSeconds_; }

 private:
  struct Buffers;
  CudaDeviceStatus status_;
  std::unique_ptr<Buffers> buffers_;
  double lastKernelSeconds_ = 0.0;
};

}  // namespace mfadvr::gpu
