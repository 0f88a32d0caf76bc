#include "core/render/ReconstructionMethod.h"

#include <chrono>
#include <optional>

#include <tbb/parallel_for.h>

#include "core/field/AnalyticField.h"
#include "core/field/DerivedFields.h"
#include "core/field/GridField.h"
#include "core/field/GridFilters.h"
#include "core/field/MeshField.h"
#include "core/field/ModelField.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/PieceCompositor.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"

namespace mfadvr {

namespace {

struct NamedMethod {
  ReconstructionMethod method;
  const char* name;
};
constexpr NamedMethod kMethods[] = {
    {ReconstructionMethod::Mfa, "mfa"},           {ReconstructionMethod::Truth, "truth"},
    {ReconstructionMethod::Nearest, "nearest"},   {ReconstructionMethod::Trilinear, "trilinear"},
    {ReconstructionMethod::Tricubic, "tricubic"}, {ReconstructionMethod::CatmullRom, "catmull-rom"},
    {ReconstructionMethod::BSpline, "bspline"},   {ReconstructionMethod::Mesh, "mesh"},
};

using Clock = std::chrono::steady_clock;

// Calls fn(field) with the field of `method`, built from the scene.
template <class Fn>
void withField(const SceneData& scene, ReconstructionMethod method, Fn&& fn) {
  auto needGrid = [&]() -> const StructuredGrid& {
    if (!scene.grid)
      throw Error("method '" + methodName(method) +
                  "' reconstructs from grid samples; give a volume file or a builtin spec "
                  "(or a model encoded from a builtin) as input");
    return *scene.grid;
  };
  switch (method) {
    case ReconstructionMethod::Mfa:
      if (!scene.model) throw Error("method 'mfa' needs a model");
      return fn(ModelField(*scene.model, scene.emptySpace));
    case ReconstructionMethod::Truth:
      if (!scene.truth)
        throw Error(
            "method 'truth' needs an analytic function: give a builtin spec as input, "
            "or a model encoded from one");
      return fn(AnalyticField(*scene.truth));
    case ReconstructionMethod::Nearest:
      return fn(GridField<NearestFilter>(needGrid()));
    case ReconstructionMethod::Trilinear:
      return fn(GridField<TrilinearFilter>(needGrid()));
    case ReconstructionMethod::Tricubic:
      return fn(GridField<TricubicFilter>(needGrid()));
    case ReconstructionMethod::CatmullRom:
      return fn(GridField<CatmullRomFilter>(needGrid()));
    case ReconstructionMethod::BSpline:
      return fn(GridField<BSplineFilter>(needGrid()));
    case ReconstructionMethod::Mesh:
      if (!scene.mesh)
        throw Error(
            "method 'mesh' renders a tetrahedral mesh's own field; give a mesh (.vtu, an "
            "unstructured .vtk, .vts) as input");
      return fn(MeshField(*scene.mesh));
  }
  throw Error("unknown reconstruction method");
}

}  // namespace

std::vector<std::string> reconstructionMethodNames() {
  std::vector<std::string> names;
  for (const auto& m : kMethods) names.emplace_back(m.name);
  return names;
}

std::string methodName(ReconstructionMethod m) {
  for (const auto& n : kMethods)
    if (n.method == m) return n.name;
  return "?";
}

ReconstructionMethod parseReconstructionMethod(const std::string& name) {
  for (const auto& m : kMethods)
    if (name == m.name) return m.method;
  std::string list;
  for (const auto& m : kMethods) list += std::string(list.empty() ? "" : ", ") + m.name;
  throw Error("unknown method '" + name + "'; choose one of: " + list);
}

bool isGridMethod(ReconstructionMethod m) {
  return m != ReconstructionMethod::Mfa && m != ReconstructionMethod::Truth &&
         m != ReconstructionMethod::Mesh;
}

std::string whyNotOnDevice(const MethodSpec& spec) {
  if ((spec.method == ReconstructionMethod::Mfa ||
       spec.method == ReconstructionMethod::Trilinear) &&
      spec.gradient == GradientMode::Analytic && !spec.gradientFrom)
    return {};
  return "method '" + methodName(spec.method) + "'" +
         (spec.gradientFrom || spec.gradient != GradientMode::Analytic ? " with this gradient"
                                                                       : "") +
         " renders on the CPU only (the GPU renders 'mfa' and 'trilinear' with analytic "
         "gradients)";
}

bool deviceRendersMethod(const MethodSpec& spec) {
  return whyNotOnDevice(spec).empty();
}

Image renderMethod(const SceneData& scene, const MethodSpec& spec, const RenderSettings& settings,
                   MethodRenderStats* stats) {
  settings.validate();
  if (spec.device && !deviceRendersMethod(spec))
    throw Error(spec.device->description() + ": " + whyNotOnDevice(spec));
  if (spec.gradient == GradientMode::CentralDifference &&
      !(scene.differenceStep.array() > 0.0).all())
    throw Error("central differences need a positive step");
  const auto setupStart = Clock::now();
  Image image;
  auto render = [&]<class F>(const F& field) {
    if (stats)
      stats->setupSeconds = std::chrono::duration<double>(Clock::now() - setupStart).count();
    if constexpr (std::same_as<F, ModelField>) {
      if (spec.device) {
        image = spec.device->renderModel(field, settings, stats);
        return;
      }
    } else if constexpr (std::same_as<F, GridField<TrilinearFilter>>) {
      if (spec.device) {
        image = spec.device->renderTrilinear(field.grid(), settings, stats);
        return;
      }
    }
    image = renderVolume(field, settings, stats);
  };
  auto withGradientMode = [&](const auto& field) {
    if (spec.gradient == GradientMode::CentralDifference)
      render(CentralDifferenceField(field, scene.differenceStep));
    else
      render(field);
  };
  const BlockModelStream* stream = scene.streamedBlocks;
  if ((scene.blocks || stream) && spec.method == ReconstructionMethod::Mfa && !spec.gradientFrom) {
    std::vector<DomainBox> regions;
    if (stream)
      for (const BlockEntry& e : stream->index.entries) regions.push_back(e.region);
    else
      for (const ModelBlock& b : *scene.blocks) regions.push_back(b.region);
    image = renderPieces(
        settings, regions,
        [&](size_t i, const RenderSettings& piece, RenderStats* pieceStats) {
          // A streamed block is read here and freed after its piece is rendered; its flags are
          // built for this render only (kept, they would add up over the blocks).
          std::optional<Model> read;
          if (stream) read.emplace(loadBlock(stream->path, stream->index, i));
          const ModelField field(stream ? *read : (*scene.blocks)[i].model,
                                 !stream && scene.emptySpace ? &scene.emptySpace[i] : nullptr);
          if (spec.device) {
            if (stream) spec.device->forgetModel();  // this block may lie where the last one did
            return spec.device->renderModel(field, piece, pieceStats);
          }
          if (spec.gradient == GradientMode::CentralDifference)
            return renderVolume(CentralDifferenceField(field, scene.differenceStep), piece,
                                pieceStats);
          return renderVolume(field, piece, pieceStats);
        },
        stats);
    compositeOverBackground(image, settings.background);
    return image;
  }
  if (!spec.gradientFrom) {
    withField(scene, spec.method, withGradientMode);
    return image;
  }
  // Gradient test: value from the truth, gradient from the method under test. Only the truth
  // supplies values here, which keeps the number of ray-caster instantiations small.
  if (spec.method != ReconstructionMethod::Truth)
    throw Error("a gradient from another method is only supported with the value from 'truth'");
  if (!scene.truth)
    throw Error(
        "the gradient test needs the analytic function: give a builtin spec as input, "
        "or a model encoded from one");
  const AnalyticField truth(*scene.truth);
  withField(scene, *spec.gradientFrom, [&](const auto& gradientField) {
    if (spec.gradient == GradientMode::CentralDifference)
      render(GradientFromField(truth, CentralDifferenceField(gradientField, scene.differenceStep)));
    else
      render(GradientFromField(truth, gradientField));
  });
  return image;
}

std::vector<ValueGradient> sampleMethod(const SceneData& scene, ReconstructionMethod method,
                                        const std::vector<Vec3d>& points) {
  std::vector<ValueGradient> out(points.size());
  withField(scene, method, [&](const auto& field) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024), [&](const auto& r) {
      auto sampler = field.sampler();
      for (size_t i = r.begin(); i != r.end(); ++i) out[i] = sampler.valueGradient(points[i]);
    });
  });
  return out;
}

}  // namespace mfadvr
