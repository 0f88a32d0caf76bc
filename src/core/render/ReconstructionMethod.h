#pragma once
// The reconstruction methods the renderer offers, by name, and one call that renders any of them
// through the same RayCaster (the template is instantiated here, once per method).
#include <optional>
#include <string>
#include <vector>

#include "core/analytic/BuiltinFunction.h"
#include "core/grid/StructuredGrid.h"
#include "core/image/Image.h"
#include "core/model/BlockModelFile.h"
#include "core/model/Model.h"
#include "core/render/DeviceRenderer.h"
#include "core/render/RenderSettings.h"

namespace mfadvr {

class EmptySpaceCache;
class TetLocator;

enum class ReconstructionMethod {
  Mfa,
  Truth,
  Nearest,
  Trilinear,
  Tricubic,
  CatmullRom,
  BSpline,
  Mesh  // a tetrahedral mesh's own field, linear in each tetrahedron (MeshField.h)
};

// mfa, truth, nearest, trilinear, tricubic, catmull-rom, bspline, mesh.
std::vector<std::string> reconstructionMethodNames();
std::string methodName(ReconstructionMethod m);
// Throws mfadvr::Error listing the names.
ReconstructionMethod parseReconstructionMethod(const std::string& name);
// The methods that filter a regular grid's samples (not mfa, truth or mesh).
bool isGridMethod(ReconstructionMethod m);

enum class GradientMode {
  Analytic,          // the derivative of the reconstructed function
  CentralDifference  // central differences of its values, one data spacing apart
};

struct MethodSpec {
  ReconstructionMethod method = ReconstructionMethod::Mfa;
  GradientMode gradient = GradientMode::Analytic;
  // The paper's gradient test (Table 1): the value comes from `method` (normally the truth),
  // the gradient from this method.
  std::optional<ReconstructionMethod> gradientFrom;
  // Render on this device (the CUDA backend) instead of the CPU. It renders 'mfa' (single and
  // multi-block models) and 'trilinear' with analytic gradients; other methods throw
  // mfadvr::Error. Borrowed.
  DeviceRenderer* device = nullptr;
};

// What a scene can be reconstructed from; a method needs its piece (mfa: model, grid methods:
// grid, truth: truth, mesh: mesh). Pointers are borrowed.
struct SceneData {
  const Model* model = nullptr;
  // A multi-block model (BlockModelFile.h): mfa renders each block in its region and composites
  // them in visibility order, with camera-aligned steps; `model` is then the first block's.
  const std::vector<ModelBlock>* blocks = nullptr;
  // Or a multi-block file read a block at a time: mfa reads each block as it renders it (and
  // again for every frame) and composites as it goes, so that one block is held at a time.
  const BlockModelStream* streamedBlocks = nullptr;
  const StructuredGrid* grid = nullptr;
  const BuiltinFunction* truth = nullptr;
  // A tetrahedral mesh located for sampling (method mesh).
  const TetLocator* mesh = nullptr;
  // Step of central differences, physical units per axis (normally the data spacing).
  Vec3d differenceStep = Vec3d::Constant(0.01);
  // Empty-space flags kept between renders by a caller that renders the scene repeatedly (they
  // are rebuilt only when the transfer function's transparent entries change): one cache for
  // `model`, or one per block of `blocks`. Null: each render builds its own.
  EmptySpaceCache* emptySpace = nullptr;
};

struct MethodRenderStats : RenderStats {
  double setupSeconds = 0.0;  // building the field (padding, prefiltering); 0 for mfa and truth
};

// Whether a DeviceRenderer can render `spec` (method mfa or trilinear, analytic gradients, no
// gradient test), and if not, why (a sentence for messages; empty when it can).
bool deviceRendersMethod(const MethodSpec& spec);
std::string whyNotOnDevice(const MethodSpec& spec);

// Throws mfadvr::Error when the scene lacks what the method needs.
Image renderMethod(const SceneData& scene, const MethodSpec& spec, const RenderSettings& settings,
                   MethodRenderStats* stats = nullptr);

// The value and gradient of `method` at each point (physical coordinates), as the ray caster
// samples them (the model's single-block field for mfa); in parallel. For measurements at points
// (the evaluation's value and gradient errors). Throws mfadvr::Error as renderMethod does.
std::vector<ValueGradient> sampleMethod(const SceneData& scene, ReconstructionMethod method,
                                        const std::vector<Vec3d>& points);

}  // namespace mfadvr
