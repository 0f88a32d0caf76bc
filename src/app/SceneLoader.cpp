#include "app/SceneLoader.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "app/OptionParsing.h"
#include "core/analytic/BuiltinSeries.h"
#include "core/model/BlockLocator.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "core/render/RenderMemory.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "io/ScatteredLoader.h"

namespace mfadvr::app {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

void takeGridFacts(LoadedScene& s) {
  const StructuredGrid& g = *s.grid;
  s.boxMin = g.boxMin();
  s.boxMax = g.boxMax();
  s.spacing = g.spacing;
  const auto [lo, hi] = std::minmax_element(g.values.begin(), g.values.end());
  s.valueMin = *lo;
  s.valueMax = *hi;
}

// Box, value range and spacing from the model alone (a .mfa file, or scattered data).
void takeModelFacts(LoadedScene& s) {
  const Model& m = *s.model;
  s.boxMin = m.domain().min;
  s.boxMax = m.domain().max;
  s.valueMin = m.valueMin();
  s.valueMax = m.valueMax();
  s.spacing = m.dataSpacing();
}

// Box, value range and spacing of scattered data that is not encoded: the spacing that
// takeModelFacts would find in the model `encodeScattered` makes with these options, so that the
// default step and opacity unit distance match those of --method mfa on the same input.
void takeScatteredFacts(LoadedScene& s, const ScatteredData& data, const EncodeOptions& encode) {
  s.boxMin = data.boxMin();
  s.boxMax = data.boxMax();
  const auto [lo, hi] = std::minmax_element(data.values.begin(), data.values.end());
  s.valueMin = *lo;
  s.valueMax = *hi;
  ScatteredFitOptions fit;
  fit.degree = encode.degree;
  fit.controlCounts = encode.controlCounts;
  const Index3 counts = resolveScatteredControlCounts(data, fit);
  const Index3 mask = encode.mask.enabled ? maskDimsFor(data, encode.mask) : Index3{1, 1, 1};
  for (int a = 0; a < 3; ++a) {
    const std::int64_t n = std::max(counts[a], mask[a]);
    s.spacing[a] = (s.boxMax[a] - s.boxMin[a]) / double(std::max<std::int64_t>(n - 1, 1));
  }
}

// Refuses, before anything is loaded, a model (or the blocks of one) that the renderer could
// not hold.
// oneAtATime: for blocks, the memory of rendering them one at a time (also too much).
void requireRenderMemory(const std::string& input, const std::vector<ModelFileSummary>& models,
                         bool extremeBounds, std::int64_t oneAtATime = 0) {
  requireSceneRenderMemory(
      models, "rendering " + input,
      models.size() > 1
          ? " in " + std::to_string(models.size()) + " blocks, about " + formatBytes(oneAtATime) +
                " one at a time; ParaView's MFA reader spreads the blocks over "
                "MPI ranks"
          : "",
      extremeBounds);
}

}  // namespace

void printReaderNotes(const StructuredGrid& grid) {
  for (const std::string& note : grid.notes)
    std::cerr << "mfadvr: note: " << grid.source << ": " << note << "\n";
}

bool isModelFile(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".mfa") == 0;
}

bool isBlockModelInput(const std::string& path) {
  return isModelFile(path) && isBlockModelFile(path);
}

SceneData LoadedScene::view() const {
  SceneData d;
  d.model = model ? &*model : nullptr;
  d.blocks = blocks.empty() ? nullptr : &blocks;
  d.streamedBlocks = streamedBlocks ? &*streamedBlocks : nullptr;
  d.grid = grid ? &*grid : nullptr;
  d.truth = truth.get();
  d.mesh = mesh ? &*mesh : nullptr;
  d.differenceStep = spacing;
  d.emptySpace = emptySpace.get();
  return d;
}

namespace {
LoadedScene loadSceneData(const std::string& input, const SceneNeeds& needs,
                          const SceneLoadOptions& options) {
  LoadedScene s;
  s.input = input;
  const auto start = Clock::now();
  if (needs.mesh && (isModelFile(input) || !isScatteredInput(input)))
    throw Error("method 'mesh' renders a tetrahedral mesh's own field; " + input +
                (isModelFile(input) ? " is a model, which holds no mesh: render the mesh it was "
                                      "encoded from"
                                    : " is a regular grid: render it with a grid method "
                                      "(e.g. trilinear)"));
  if (isBlockModelInput(input)) {
    BlockIndex index = readBlockIndex(input);
    const std::vector<ModelFileSummary> summaries = summarizeBlocks(input, index);
    const bool bounds = options.extremeBounds;
    const std::int64_t all = sceneRenderBytes(summaries, bounds),
                       available = availableMemoryBytes();
    // Blocks are read one at a time as they are rendered (every frame reading them again)
    // when asked to, or when they do not fit in memory together; either way only if one at a
    // time fits (the largest, and the first, kept for the scene's facts). Otherwise all are
    // loaded, or refused with the figures for both.
    const auto largest =
        std::max_element(summaries.begin(), summaries.end(), [&](const auto& a, const auto& b) {
          return modelRenderBytes(a, bounds) < modelRenderBytes(b, bounds);
        });
    const std::vector<ModelFileSummary> held{summaries.front(), *largest};
    const std::int64_t oneAtATime = sceneRenderBytes(held, bounds);
    const bool tooLarge = available > 0 && all > available;
    const bool stream = summaries.size() > 1 && (options.streamBlocks || tooLarge) &&
                        (available <= 0 || oneAtATime <= available);
    if (needs.grid || needs.cells)
      throw Error("a multi-block model renders with --method mfa only (it holds no samples)");
    const DomainBox box = index.box;
    if (stream && tooLarge) {
      std::cerr << "mfadvr: note: " << input << ": its " << summaries.size()
                << " blocks would need about " << formatBytes(all) << " at once ("
                << formatBytes(available)
                << " available): they are read one at a time as each frame renders them\n";
    }
    if (stream) {
      s.model = loadBlock(input, index, 0);
      s.streamedBlocks = BlockModelStream{input, std::move(index)};
    } else {
      requireRenderMemory(input, summaries, bounds, oneAtATime);
      s.blocks = loadBlockModels(input);
      s.model = s.blocks.front().model;
    }
    takeModelFacts(s);
    s.boxMin = box.min;  // the union of the blocks' regions
    s.boxMax = box.max;
    s.loadSeconds = since(start);
    return s;
  }
  if (isModelFile(input)) {
    requireRenderMemory(input, {summarizeModelFile(input)}, options.extremeBounds);
    auto model = std::make_shared<TimeVaryingModel>(loadTimeVaryingModel(input));
    if (model->hasTime()) {
      const TimeAxis& axis = model->timeAxis();
      if (options.time && !axis.contains(*options.time)) {
        std::ostringstream m;
        m << "--time " << *options.time << " lies outside the time range of " << input << " ("
          << axis.begin << " .. " << axis.end << ")";
        throw Error(m.str());
      }
      s.timeVarying = model;
      const std::string& source = model->provenance().source;
      if (needs.grid || needs.cells) {
        if (!isBuiltinSeriesSpec(source))
          throw Error(
              "grid methods and VTK's renderers need the samples, which a model file "
              "does not hold; render one step of the series it was encoded from (" +
              source + ") instead");
        s.grid.emplace();  // filled by setTime
      }
      s.setTime(options.time.value_or(model->defaultTime()));
      s.loadSeconds = since(start);
      return s;
    }
    if (options.time)
      throw Error("--time applies to time-varying models; " + input + " has no time axis");
    s.model = model->first();
    model.reset();
    takeModelFacts(s);
    const Provenance& p = s.model->provenance();
    if (isBuiltinSpec(p.source)) {
      // A model of a built-in function: the truth is known, and its samples can be recomputed.
      s.truth = makeBuiltin(parseBuiltinSpec(p.source).name);
      if ((needs.grid || needs.cells) && p.sampleDims[0] > 0)
        s.grid = sampleBuiltin(*s.truth, p.sampleDims);
    }
    if (needs.grid && !s.grid)
      throw Error(
          "grid methods need the samples, which a model file does not hold; render the "
          "volume file it was encoded from (" +
          p.source + ") instead");
    if (needs.cells && !s.grid)
      throw Error(
          "VTK's renderers render the data, which a model file does not hold; render the "
          "file it was encoded from (" +
          p.source + ") instead");
    s.loadSeconds = since(start);
    return s;
  }
  if (options.progress) std::cerr << "reading " << input << "\n";
  EncodeOptions encode = options.encode;
  if (options.progress)
    encode.progress = [](double f, const std::string& stage) {
      printProgress("encoding", f, stage);
    };
  if (isScatteredInput(input)) {
    if (needs.grid)
      throw Error("grid methods need a regular grid; " + input +
                  " holds scattered points or a mesh: render it with --method mfa");
    ScatteredLoadOptions load;
    load.field = options.volume.field;
    ScatteredData data = loadScatteredData(input, load);
    s.loadSeconds = since(start);
    if (needs.model) {
      const auto encodeStart = Clock::now();
      s.model = encodeScattered(data, encode);
      s.encodeSeconds = since(encodeStart);
      takeModelFacts(s);
    } else {
      takeScatteredFacts(s, data, encode);
    }
    if (needs.mesh && data.hasCells()) {
      const auto locateStart = Clock::now();
      s.mesh.emplace(data);
      s.loadSeconds += since(locateStart);
    }
    if (needs.cells) s.scattered = std::move(data);
    return s;
  }
  s.grid = loadStructuredVolume(input, options.volume);
  printReaderNotes(*s.grid);
  if (isBuiltinSpec(input)) s.truth = makeBuiltin(parseBuiltinSpec(input).name);
  takeGridFacts(s);
  s.loadSeconds = since(start);
  if (needs.model) {
    const auto encodeStart = Clock::now();
    s.model = encodeStructured(*s.grid, encode);
    s.encodeSeconds = since(encodeStart);
  }
  return s;
}
}  // namespace

LoadedScene sceneOfModel(Model model, const std::string& name) {
  LoadedScene s;
  s.input = name;
  s.model = std::move(model);
  takeModelFacts(s);
  s.emptySpace = std::make_unique<EmptySpaceCache[]>(1);
  return s;
}

LoadedScene sceneOfGrid(StructuredGrid grid, const SceneNeeds& needs, const EncodeOptions& encode) {
  LoadedScene s;
  s.input = grid.source;
  s.grid = std::move(grid);
  takeGridFacts(s);
  if (needs.model) {
    const auto encodeStart = Clock::now();
    s.model = encodeStructured(*s.grid, encode);
    s.encodeSeconds = since(encodeStart);
  }
  s.emptySpace = std::make_unique<EmptySpaceCache[]>(1);
  return s;
}

LoadedScene sceneOfBlocks(std::vector<ModelBlock> blocks, const std::string& name) {
  if (blocks.empty()) throw Error(name + ": a multi-block model without blocks");
  LoadedScene s;
  s.input = name;
  s.blocks = std::move(blocks);
  s.model = s.blocks.front().model;
  takeModelFacts(s);
  const DomainBox box = regionsBox(s.blocks);
  s.boxMin = box.min;  // the union of the blocks' regions
  s.boxMax = box.max;
  s.emptySpace = std::make_unique<EmptySpaceCache[]>(s.blocks.size());
  return s;
}

void LoadedScene::setTime(double t) {
  if (!timeVarying) throw Error(input + " has no time axis");
  const TimeAxis& axis = timeVarying->timeAxis();
  time = std::clamp(t, axis.begin, axis.end);
  model = timeVarying->at(time);
  takeModelFacts(*this);
  const Provenance& p = model->provenance();
  if (isBuiltinSeriesSpec(p.source)) {
    const BuiltinVolumeSeries series(p.source);
    truth = builtinAtTime(series.sharedFunction(), time, p.sampleDims);
    if (grid) grid = series.sampleAt(time);
  }
}

LoadedScene loadScene(const std::string& input, const SceneNeeds& needs,
                      const SceneLoadOptions& options) {
  if (options.time && !isModelFile(input))
    throw Error(
        "--time applies to time-varying model files; encode the series first (mfadvr "
        "encode SERIES -o MODEL.mfa)");
  LoadedScene s = loadSceneData(input, needs, options);
  s.emptySpace = std::make_unique<EmptySpaceCache[]>(std::max<size_t>(s.blocks.size(), 1));
  return s;
}

}  // namespace mfadvr::app
