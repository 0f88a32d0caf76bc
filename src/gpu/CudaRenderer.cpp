#include "gpu/CudaRenderer.h"

#include <chrono>
#include <limits>
#include <vector>

#include "core/field/PaddedGrid.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"
#include "gpu/CudaRayLaunch.h"
#include "gpu/DeviceArray.h"
#include "gpu/DeviceArrays.h"

namespace mfadvr::gpu {

namespace {

using Clock = std::chrono::steady_clock;

std::string mib(std::size_t bytes) {
  return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB";
}

// Copies `arrays` into `copies` (grown to match); returns the device addresses, in order.
std::vector<const void*> upload(const std::vector<HostArray>& arrays,
                                std::vector<DeviceArray>& copies) {
  if (copies.size() < arrays.size()) copies.resize(arrays.size());
  std::vector<const void*> addresses;
  for (std::size_t i = 0; i < arrays.size(); ++i) {
    copies[i].upload(arrays[i].data, arrays[i].bytes, arrays[i].what);
    addresses.push_back(copies[i].data());
  }
  return addresses;
}

// The model's arrays as a key: a model is the same while they are (see forgetModel()).
bool sameArrays(const std::vector<HostArray>& a, const std::vector<HostArray>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].data != b[i].data || a[i].bytes != b[i].bytes) return false;
  return true;
}

}  // namespace

struct CudaRenderer::Buffers {
  // The model, kept between frames, and the view relocated onto it.
  std::vector<HostArray> modelKey;
  std::vector<DeviceArray> model;
  std::vector<const void*> modelCopies;
  // The empty-space flags, kept while the field's cache hands out the same ones (held here,
  // so that the same address is the same flags).
  std::shared_ptr<const EmptySpaceFlags> flags;
  std::vector<DeviceArray> flagCopies;
  std::vector<const void*> flagAddresses;
  // The trilinear grid, kept between frames.
  const float* gridData = nullptr;
  std::size_t gridSize = 0;
  DeviceArray grid;
  // Per frame.
  std::vector<DeviceArray> frame;
  DeviceArray image, depth, counters;
};

CudaRenderer::CudaRenderer() : status_(cudaDeviceStatus()), buffers_(std::make_unique<Buffers>()) {
  if (!status_.usable) throw Error(status_.describe());
}

CudaRenderer::~CudaRenderer() = default;

std::string CudaRenderer::description() const {
  return "CUDA GPU " + status_.describe();
}

void CudaRenderer::forgetModel() {
  Buffers& b = *buffers_;
  b.modelKey.clear();
  b.model.clear();
  b.modelCopies.clear();
  b.flags = nullptr;
  b.flagCopies.clear();
  b.gridData = nullptr;
  b.grid.release();
}

namespace {

// The frame's arrays, image and counters; returns `params` relocated onto the device.
RayParams uploadFrame(const RayParams& params, std::vector<DeviceArray>& frame, DeviceArray& image,
                      DeviceArray& counters) {
  const RayParams d = relocateFrame(params, upload(frameArrays(params), frame));
  const std::size_t pixels = std::size_t(params.camera.width) * params.camera.height;
  image.reserve(pixels * 4 * sizeof(float), "the image");
  counters.reserve(sizeof(DeviceRayCounters), "counters");
  counters.zero(sizeof(DeviceRayCounters));
  return d;
}

void readBack(const RayParams& params, DeviceArray& image, const DeviceArray& counters, Image& out,
              RenderStats* stats) {
  image.download(out.rgba.data(), out.rgba.size() * sizeof(float));
  DeviceRayCounters c{};
  counters.download(&c, sizeof c);
  if (stats) {
    stats->rays = std::int64_t(params.camera.width) * params.camera.height;
    stats->raysHit = static_cast<std::int64_t>(c.hits);
    stats->samples = static_cast<std::int64_t>(c.samples);
    stats->terminated = static_cast<std::int64_t>(c.terminated);
    stats->skipped = static_cast<std::int64_t>(c.skipped);
  }
}

// One frame: its arrays up, `launch(params, image, counters)` on the relocated parameters, the
// image and counters back.
// With `keepDepth` (RenderSettings::depth) the rays' depths too, in `depth`.
template <class Launch>
Image renderFrame(const RayParams& hostParams, bool keepDepth, std::vector<DeviceArray>& frame,
                  DeviceArray& image, DeviceArray& depth, DeviceArray& counters, Launch&& launch,
                  RenderStats* stats, double& kernelSeconds) {
  RayParams params = uploadFrame(hostParams, frame, image, counters);
  const std::size_t pixels = std::size_t(params.camera.width) * params.camera.height;
  if (keepDepth) {
    const std::vector<float> none(pixels, std::numeric_limits<float>::quiet_NaN());
    depth.upload(none.data(), pixels * sizeof(float), "the depth image");
    params.depth = depth.as<float>();
  }
  kernelSeconds = launch(params, image.as<float>(), counters.as<DeviceRayCounters>());
  Image out(params.camera.width, params.camera.height);
  readBack(params, image, counters, out, stats);
  if (keepDepth) {
    out.depth.resize(pixels);
    depth.download(out.depth.data(), pixels * sizeof(float));
  }
  return out;
}

}  // namespace

Image CudaRenderer::renderModel(const ModelField& field, const RenderSettings& settings,
                                RenderStats* stats) {
  const auto start = Clock::now();
  const ModelRenderSetup setup(field, settings);
  Buffers& b = *buffers_;
  const std::vector<HostArray> arrays = modelArrays(setup.view());
  if (!sameArrays(arrays, b.modelKey)) {
    forgetModel();
    const std::size_t bytes = totalBytes(arrays);
    const CudaDeviceStatus now = cudaDeviceStatus();
    if (bytes > now.freeMemory)
      throw Error("the model needs " + mib(bytes) + " of GPU memory; " + status_.name + " has " +
                  mib(now.freeMemory) + " free of " + mib(now.totalMemory) +
                  " (render it on the CPU, or encode fewer control points)");
    b.modelCopies = upload(arrays, b.model);
    b.modelKey = arrays;
  }

  ModelView view = relocateModel(setup.view(), b.modelCopies);
  // The device's kernels skip in composite and iso renders only (RayIntegrator.h): the other
  // blends' skipping information stays on the host.
  const bool skips =
      setup.skips() && (settings.blend == BlendMode::Composite || settings.blend == BlendMode::Iso);
  view.empty = nullptr;
  view.extremeUpper = view.extremeLower = nullptr;
  view.extremeUpperPyramid = view.extremeLowerPyramid = nullptr;
  view.extremeUpperLevels = view.extremeLowerLevels = nullptr;
  view.extremeLevels = 0;
  if (const auto flags = skips ? setup.emptySpaceFlags() : nullptr) {
    if (flags != b.flags) {
      b.flags = nullptr;
      b.flagAddresses = upload(flagArrays(*flags), b.flagCopies);
      b.flags = flags;
    }
    view = relocateFlags(view, b.flagAddresses);
  }
  Image image = renderFrame(
      setup.params(), settings.depth, b.frame, b.image, b.depth, b.counters,
      [&](const RayParams& params, float* pixels, DeviceRayCounters* counters) {
        ModelLaunch l;
        l.params = params;
        l.view = view;
        l.masked = setup.masked();
        l.shade = settings.needsGradients();
        l.skip = skips;
        l.image = pixels;
        l.counters = counters;
        return launchModelRays(l);
      },
      stats, lastKernelSeconds_);
  if (stats) stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

Image CudaRenderer::renderTrilinear(const PaddedGrid& grid, const RenderSettings& settings,
                                    RenderStats* stats) {
  const auto start = Clock::now();
  settings.validate();
  Buffers& b = *buffers_;
  const GridView host = grid.view();
  if (b.gridData != host.data || b.gridSize != grid.paddedSize()) {
    b.gridData = nullptr;
    b.grid.upload(host.data, grid.paddedSize() * sizeof(float), "the grid");
    b.gridData = host.data;
    b.gridSize = grid.paddedSize();
  }
  const ClassificationTables tables(settings);
  const RayParams params = compileRayParams(settings, tables, grid.boxMin(), grid.boxMax());
  Image image = renderFrame(
      params, settings.depth, b.frame, b.image, b.depth, b.counters,
      [&](const RayParams& relocated, float* pixels, DeviceRayCounters* counters) {
        GridLaunch l;
        l.params = relocated;
        l.grid = host;
        l.grid.data = b.grid.as<const float>();
        l.shade = settings.needsGradients();
        l.image = pixels;
        l.counters = counters;
        return launchGridRays(l);
      },
      stats, lastKernelSeconds_);
  if (stats) stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

}  // namespace mfadvr::gpu
