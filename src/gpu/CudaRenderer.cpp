#include "gpu/CudaRenderer.h"

#include <chrono>

#include "core/field/PaddedGrid.h"
#include "core/render/ModelRenderSetup.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"
#include "gpu/CudaRayLaunch.h"
#include "gpu/DeviceArray.h"

namespace mfadvr::gpu {

namespace {

using Clock = std::chrono::steady_clock;

// What identifies an uploaded model: the addresses and sizes of its arrays.
struct ModelKey {
  const void* pointers[11] = {};
  std::int64_t sizes[6] = {};
  bool operator==(const ModelKey&) const = default;
};

std::size_t knotCount(const KnotAxisView& a) {
  return std::size_t(a.count) + a.degree + 1;
}
std::size_t polyCount(const KnotAxisView& a) {
  return std::size_t(a.count) * (a.degree + 1) * (a.degree + 1);
}
std::size_t maskNodeCount(const MaskView& m) {
  return m.nodes ? std::size_t(m.dims[0] * m.dims[1] * m.dims[2]) : 0;
}
std::size_t controlCount(const SplineView& v) {
  return std::size_t(v.axis[0].count) * v.axis[1].count * v.axis[2].count;
}

ModelKey keyOf(const ModelView& v) {
  ModelKey k;
  k.pointers[0] = v.spline.ctrl;
  for (int a = 0; a < 3; ++a) {
    k.pointers[1 + 3 * a] = v.spline.axis[a].knots;
    k.pointers[2 + 3 * a] = v.spline.axis[a].poly;
    k.pointers[3 + 3 * a] = v.spline.axis[a].inverseLength;
    k.sizes[a] = v.spline.axis[a].count;
    k.sizes[3 + a] = v.spline.axis[a].degree;
  }
  k.pointers[10] = v.mask.nodes;
  return k;
}

std::string mib(std::size_t bytes) {
  return std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB";
}

}  // namespace

struct CudaRenderer::Buffers {
  // The model, kept between frames.
  ModelKey modelKey;
  bool haveModel = false;
  DeviceArray ctrl, mask;
  DeviceArray knots[3], poly[3], inverseLength[3];
  // The trilinear grid, kept between frames.
  const float* gridData = nullptr;
  std::size_t gridSize = 0;
  DeviceArray grid;
  // The empty-space flags, kept while the field's cache hands out the same ones.
  std::shared_ptr<const EmptySpaceFlags> flags;
  DeviceArray emptyCells, emptyBlocks;
  // Per frame.
  DeviceArray tf, rayEnd, image, counters;
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
  b.haveModel = false;
  b.ctrl.release();
  b.mask.release();
  for (int a = 0; a < 3; ++a) {
    b.knots[a].release();
    b.poly[a].release();
    b.inverseLength[a].release();
  }
  b.gridData = nullptr;
  b.grid.release();
  b.flags = nullptr;
}

namespace {

// The frame's own arrays: the table, ray ends, the image and the counters; returns the device
// copy of `params` with its pointers replaced.
RayParams uploadFrame(const RayParams& params, DeviceArray& tf, DeviceArray& rayEnd,
                      DeviceArray& image, DeviceArray& counters) {
  RayParams d = params;
  tf.upload(params.tf.entries, std::size_t(params.tf.count) * sizeof(TfEntry),
            "the transfer-function table");
  d.tf.entries = tf.as<const TfEntry>();
  const std::size_t pixels = std::size_t(params.camera.width) * params.camera.height;
  if (params.rayEnd) {
    rayEnd.upload(params.rayEnd, pixels * sizeof(float), "the ray ends");
    d.rayEnd = rayEnd.as<const float>();
  }
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

}  // namespace

Image CudaRenderer::renderModel(const ModelField& field, const RenderSettings& settings,
                                RenderStats* stats) {
  const auto start = Clock::now();
  const ModelRenderSetup setup(field, settings);
  Buffers& b = *buffers_;
  const ModelView& host = setup.view();
  const ModelKey key = keyOf(host);
  if (!b.haveModel || !(b.modelKey == key)) {
    forgetModel();
    std::size_t bytes = controlCount(host.spline) * sizeof(float) + maskNodeCount(host.mask);
    for (const KnotAxisView& a : host.spline.axis)
      bytes += knotCount(a) * sizeof(double) + polyCount(a) * sizeof(float) +
               std::size_t(a.count) * sizeof(double);
    const CudaDeviceStatus now = cudaDeviceStatus();
    if (bytes > now.freeMemory)
      throw Error("the model needs " + mib(bytes) + " of GPU memory; " + status_.name + " has " +
                  mib(now.freeMemory) + " free of " + mib(now.totalMemory) +
                  " (render it with --device cpu, or encode fewer control points)");
    b.ctrl.upload(host.spline.ctrl, controlCount(host.spline) * sizeof(float),
                  "the control points");
    for (int a = 0; a < 3; ++a) {
      const KnotAxisView& axis = host.spline.axis[a];
      b.knots[a].upload(axis.knots, knotCount(axis) * sizeof(double), "the knots");
      b.poly[a].upload(axis.poly, polyCount(axis) * sizeof(float), "the basis polynomials");
      b.inverseLength[a].upload(axis.inverseLength, std::size_t(axis.count) * sizeof(double),
                                "the knot spans");
    }
    if (host.mask.nodes) b.mask.upload(host.mask.nodes, maskNodeCount(host.mask), "the mask");
    b.modelKey = key;
    b.haveModel = true;
  }

  ModelLaunch l;
  l.view = host;
  l.view.spline.ctrl = b.ctrl.as<const float>();
  for (int a = 0; a < 3; ++a) {
    l.view.spline.axis[a].knots = b.knots[a].as<const double>();
    l.view.spline.axis[a].poly = b.poly[a].as<const float>();
    l.view.spline.axis[a].inverseLength = b.inverseLength[a].as<const double>();
  }
  if (host.mask.nodes) l.view.mask.nodes = b.mask.as<const std::uint8_t>();
  if (const auto flags = setup.emptySpaceFlags()) {
    // Held here, so that the same address is the same flags: a viewer's frames upload them
    // once per transfer function.
    if (flags != b.flags) {
      b.flags = nullptr;
      b.emptyCells.upload(flags->cells.data(), flags->cells.size(), "the empty-space flags");
      b.emptyBlocks.upload(flags->blocks.data(), flags->blocks.size(), "the empty-space flags");
      b.flags = flags;
    }
    l.view.empty = b.emptyCells.as<const std::uint8_t>();
    l.view.emptyBlocks = b.emptyBlocks.as<const std::uint8_t>();
  }
  l.params = uploadFrame(setup.params(), b.tf, b.rayEnd, b.image, b.counters);
  l.masked = setup.masked();
  l.shade = settings.shade;
  l.skip = setup.skips();
  l.image = b.image.as<float>();
  l.counters = b.counters.as<DeviceRayCounters>();
  lastKernelSeconds_ = launchModelRays(l);

  Image image(settings.width, settings.height);
  readBack(l.params, b.image, b.counters, image, stats);
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
  const TransferFunctionTable table(
      settings.transferFunction,
      OpacityCorrection(settings.sampleDistance / settings.opacityUnitDistance));
  const RayParams params = compileRayParams(settings, table, grid.boxMin(), grid.boxMax());
  GridLaunch l;
  l.grid = host;
  l.grid.data = b.grid.as<const float>();
  l.params = uploadFrame(params, b.tf, b.rayEnd, b.image, b.counters);
  l.shade = settings.shade;
  l.image = b.image.as<float>();
  l.counters = b.counters.as<DeviceRayCounters>();
  lastKernelSeconds_ = launchGridRays(l);

  Image image(settings.width, settings.height);
  readBack(l.params, b.image, b.counters, image, stats);
  if (stats) stats->seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return image;
}

}  // namespace mfadvr::gpu
