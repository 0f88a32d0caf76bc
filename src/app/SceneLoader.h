#pragma once
// Turns a render command's INPUT into what the methods reconstruct from: a model (loaded, or
// encoded on the fly from a volume, mesh or point cloud), the grid samples, the mesh or point
// cloud itself (for VTK's tetrahedral baselines, and located for the mesh method), and the analytic
// truth when the input is a built-in function (or a model encoded from one).
#include <memory>
#include <optional>
#include <string>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/Encoder.h"
#include "core/mesh/ScatteredData.h"
#include "core/mesh/TetLocator.h"
#include "core/model/BlockModelFile.h"
#include "core/model/Model.h"
#include "core/model/TimeVaryingModel.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/ReconstructionMethod.h"
#include "io/VolumeLoader.h"

namespace mfadvr::app {

struct SceneNeeds {
  bool model = false;  // some method is mfa
  bool grid = false;   // some method filters the grid
  // Some method renders the input's cells (VTK's tetrahedral mappers): a mesh or point cloud is
  // kept as it was read, a volume (or a model of a builtin) as its grid.
  bool cells = false;
  // Some method samples a mesh's own field (method mesh): a mesh input's tetrahedra are located
  // once (a point cloud has none: LoadedScene::mesh stays empty); other inputs are refused.
  bool mesh = false;
};

struct LoadedScene {
  std::string input;
  std::optional<Model> model;      // for a multi-block file: its first block's model
  std::vector<ModelBlock> blocks;  // a multi-block model file's blocks
  // Or its blocks to read one at a time, when they would not fit in memory at once.
  std::optional<BlockModelStream> streamedBlocks;
  std::optional<StructuredGrid> grid;
  std::optional<ScatteredData> scattered;  // a mesh or point cloud input, when needs.cells
  std::optional<TetLocator> mesh;          // a mesh input located for sampling, when needs.mesh
  std::unique_ptr<BuiltinFunction> truth;
  Vec3d boxMin = Vec3d::Zero(), boxMax = Vec3d::Ones();
  Vec3d spacing = Vec3d::Ones();          // of the data samples: default step and difference step
  double valueMin = 0.0, valueMax = 1.0;  // of the data samples: what the TF is relative to
  double loadSeconds = 0.0, encodeSeconds = 0.0;
  // The model's (or each block's) empty-space flags, kept from one frame to the next.
  std::unique_ptr<EmptySpaceCache[]> emptySpace;
  // A time-varying model file: every instant; `model` is the one at `time`.
  std::shared_ptr<const TimeVaryingModel> timeVarying;
  double time = 0.0;

  SceneData view() const;
  // A time-varying scene at time t (clamped onto the model's range): the model, and the truth and
  // samples of a model of a time-varying built-in. Throws mfadvr::Error without a time axis.
  void setTime(double t);
};

struct SceneLoadOptions {
  VolumeLoadOptions volume;
  EncodeOptions encode;  // when a volume, mesh or point cloud must be encoded for the mfa method
  bool progress = false;
  // A maximum or minimum intensity render: the memory check counts the cells' bounds it builds
  // (core/render/RenderMemory.h).
  bool extremeBounds = false;
  // The instant of a time-varying model file (default: its first step); an error for other
  // inputs.
  std::optional<double> time;
  // Read a multi-block file's blocks one at a time as they are rendered even when they would
  // fit in memory together (a single frame: each block is read once either way). Without it,
  // only blocks that do not fit together are.
  bool streamBlocks = false;
};

// Scenes of data already in memory (the Python module's arrays and models), with the facts
// loadScene would take from a file holding the same: `name` stands for the input.
LoadedScene sceneOfModel(Model model, const std::string& name);
// A grid, encoded with `encode` when needs.model.
LoadedScene sceneOfGrid(StructuredGrid grid, const SceneNeeds& needs, const EncodeOptions& encode);
// A multi-block model's blocks (non-empty; regions tiling their box), as a multi-block file's.
LoadedScene sceneOfBlocks(std::vector<ModelBlock> blocks, const std::string& name);

// Throws mfadvr::Error when the input cannot provide what `needs` asks for.
LoadedScene loadScene(const std::string& input, const SceneNeeds& needs,
                      const SceneLoadOptions& options);

// Prints what a volume reader applied or could not represent (StructuredGrid::notes) to stderr.
void printReaderNotes(const StructuredGrid& grid);

bool isModelFile(const std::string& path);
bool isBlockModelInput(const std::string& path);

}  // namespace mfadvr::app
