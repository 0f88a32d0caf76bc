#include "core/encode/Encoder.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include "core/encode/CodingChoice.h"
#include "core/encode/Dequantizer.h"
#include "core/encode/ScatteredSmoothingChoice.h"
#include "core/mask/DomainBoundary.h"
#include "core/mask/MaskVoxelizer.h"
#include "core/mesh/CellSamples.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"

namespace mfadvr {

namespace {

// The fit the encode options ask for (smoothing resolved: no automatic choice left).
StructuredFitOptions fitOptionsOf(const EncodeOptions& options) {
  StructuredFitOptions fit;
  fit.degree = options.degree;
  fit.controlCounts = options.controlCounts;
  fit.smoothing = options.smoothing.value_or(0.0);
  fit.progress = options.progress;
  return fit;
}

Model encodeStructuredFit(const StructuredGrid& grid, const EncodeOptions& options,
                          FitReport* report) {
  const StructuredFitOptions fit = fitOptionsOf(options);
  const CodingOptions& coding = options.coding;
  const bool countsGiven = options.controlCounts[0] > 0;
  if (coding.budget.kind != BudgetKind::kNone) {
    if (options.adaptive)
      throw Error(
          "a size or quality budget chooses the control points itself; it does not "
          "combine with an error bound (--max-error)");
    return encodeToBudget(grid, fit, coding, countsGiven, report);
  }
  if (!coding.coder) {
    if (options.adaptive) return fitStructuredAdaptive(grid, fit, *options.adaptive, report);
    return fitStructured(grid, fit, report);
  }
  FitReport local;
  FitReport& r = report ? *report : local;
  if (!options.adaptive)
    return codeFittedModel(fitStructured(grid, fit, &r), grid, coding, 0.0, countsGiven, &r);
  AdaptiveOptions adaptive = *options.adaptive;
  const bool lossy = *coding.coder == ControlCoder::kZfp;
  if (lossy && coding.tolerance == 0.0) adaptive.maxRelativeError *= 0.5;
  const Model fitted = fitStructuredAdaptive(grid, fit, adaptive, &r);
  const double bound = options.adaptive->maxRelativeError * (fitted.valueMax() - fitted.valueMin());
  Model m = codeFittedModel(fitted, grid, coding, lossy ? bound : 0.0, countsGiven, &r);
  if (lossy && coding.tolerance == 0.0 && bound > 0.0) {
    // The interpolating model, coded to the same bound, is often the smaller file: its control
    // points are as smooth as the data, where a least-squares fit with slightly fewer points
    // than samples has rough ones (measured on an 8-bit scan: 0.67 against 6.9 bits/sample).
    FitReport interpolating;
    StructuredFitOptions all = fit;
    all.controlCounts = {0, 0, 0};
    all.progress = nullptr;
    Model alt = codeFittedModel(fitStructured(grid, all, &interpolating), grid, coding, bound,
                                countsGiven, &interpolating);
    if (interpolating.maxError <= bound && interpolating.modelBytes < r.modelBytes) {
      interpolating.rounds = r.rounds;
      interpolating.stopReason = r.stopReason;
      interpolating.seconds += r.seconds;
      interpolating.codingNote +=
          "; chosen over the adaptive fit (" + std::to_string(r.controlCounts[0]) + "x" +
          std::to_string(r.controlCounts[1]) + "x" + std::to_string(r.controlCounts[2]) +
          " control points, " + std::to_string(r.modelBytes) + " bytes): smaller";
      r = interpolating;
      m = std::move(alt);
    }
  }
  // The bound the user gave, judged on the decoded model.
  r.targetRelativeError = options.adaptive->maxRelativeError;
  r.reachedTarget = r.maxRelativeError() <= r.targetRelativeError;
  if (!r.reachedTarget && r.stopReason.empty()) r.stopReason = "the coded model misses the bound";
  return m;
}

// --dequantize: the targets within the quantization intervals (Dequantizer.h), the model fitted
// to them, coded and judged against the samples themselves (within half a step).
Model encodeDequantized(const StructuredGrid& grid, const EncodeOptions& options,
                        FitReport* report) {
  refuseWithDequantize(options);
  double step = *options.dequantizeStep;
  if (step == 0.0) {
    if (!isIntegerSampleType(grid.sampleType))
      throw Error("--dequantize: " + grid.source + " holds " + grid.sampleType +
                  " samples; give the step they were quantized with (--dequantize STEP)");
    step = 1.0;
  }
  StructuredFitOptions fit = fitOptionsOf(options);
  fit.smoothing = 0.0;
  const std::array<KnotVector, 3> knots = knotsOfFit(grid, fit);
  DequantizeOptions dq;
  dq.step = step;
  if (options.smoothing) dq.smoothing = *options.smoothing;
  if (options.progress)
    dq.progress = [&](double f, const std::string& stage) { options.progress(0.6 * f, stage); };
  DequantizeResult d = dequantizeTargets(grid, knots, dq);
  StructuredGrid targets = grid;
  targets.values = std::move(d.targets);
  FitReport local;
  FitReport& r = report ? *report : local;
  if (options.progress)
    fit.progress = [&](double f, const std::string& stage) {
      options.progress(0.6 + 0.3 * f, stage);
    };
  Model fitted = fitStructuredWithKnots(targets, knots, fit, &r);
  targets = {};
  // Its errors are those against the samples, not the targets.
  const SampleErrors e = errorsOnGrid(fitted.spline(), grid);
  Provenance& p = fitted.provenance();
  p.maxError = e.max;
  p.rmsError = e.rms;
  p.encoder = "structured-dequantize";
  p.smoothing = dq.smoothing;
  p.fitSeconds += d.seconds;
  CodingOptions coding = options.coding;
  if (!coding.coder) coding.coder = ControlCoder::kFloat32;
  Model m = codeFittedModel(std::move(fitted), grid, coding, std::nextafter(0.5 * step, 0.0),
                            options.controlCounts[0] > 0, &r);
  r.smoothing = 0.0;  // not a smoothing fit: dequantizeLambda is the roughness it minimized
  r.dequantizeLambda = dq.smoothing;
  r.dequantizeStep = step;
  r.dequantizeIterations = d.iterations;
  r.dequantizeConverged = d.converged;
  r.dequantizeEdgeShare = d.edgeShare;
  r.dequantizeSeconds = d.seconds;
  return m;
}

}  // namespace

void refuseWithDequantize(const EncodeOptions& options) {
  if (!options.dequantizeStep) return;
  if (options.adaptive)
    throw Error("--dequantize does not combine with --max-error (its bound is half a step)");
  if (options.coding.budget.kind != BudgetKind::kNone)
    throw Error("--dequantize does not combine with a size or quality budget yet");
  if (options.autoSmoothing)
    throw Error(
        "--dequantize chooses the smoothest model within the quantization; --smooth auto does "
        "not combine with it (--smooth LAMBDA sets the smoother whose roughness it minimizes)");
}

EncodeOptions withChosenSmoothing(const StructuredGrid& grid, const EncodeOptions& options,
                                  SmoothingChoice* choice) {
  EncodeOptions out = options;
  if (!options.autoSmoothing) return out;
  if (options.smoothing)
    throw Error("give either a smoothing weight or automatic smoothing, not both");
  StructuredFitOptions fit;
  fit.degree = options.degree;
  fit.controlCounts = options.adaptive ? Index3{0, 0, 0} : options.controlCounts;
  fit.progress = options.progress;
  SmoothingSearch search;
  search.quantizationStep = options.quantizationStep.value_or(0.0);
  SmoothingChoice c = chooseSmoothing(grid, fit, search);
  out.smoothing = c.lambda;
  out.autoSmoothing = false;
  if (choice) *choice = std::move(c);
  return out;
}

Model encodeStructured(const StructuredGrid& grid, const EncodeOptions& options,
                       FitReport* report) {
  if (options.smoothing) validateSmoothing(*options.smoothing);
  if (options.dequantizeStep) return encodeDequantized(grid, options, report);
  SmoothingChoice choice;
  const EncodeOptions resolved = withChosenSmoothing(grid, options, &choice);
  FitReport local;
  FitReport& r = report ? *report : local;
  Model m = encodeStructuredFit(grid, resolved, &r);
  r.smoothing = resolved.smoothing.value_or(0.0);
  if (options.autoSmoothing) {
    r.noiseEstimate = choice.noiseRms;
    r.smoothingNote = choice.note;
  }
  return m;
}

Model encodeStructured(const StructuredGrid& layout, const GridSamples& samples,
                       const EncodeOptions& options, FitReport* report) {
  const bool planeByPlane =
      !options.autoSmoothing && !options.adaptive && !options.dequantizeStep &&
      options.coding.budget.kind == BudgetKind::kNone && !options.coding.coder;
  if (!planeByPlane) {
    StructuredGrid grid = layout;
    grid.values = samples.toFloats();
    return encodeStructured(grid, options, report);
  }
  if (options.smoothing) validateSmoothing(*options.smoothing);
  const StructuredFitOptions fit = fitOptionsOf(options);
  FitReport local;
  FitReport& r = report ? *report : local;
  Model m = fitStructured(layout, samples, fit, &r);
  r.smoothing = fit.smoothing;
  return m;
}

Index3 maskDimsFor(const ScatteredData& data, const MaskOptions& options) {
  if (options.dims[0] > 0) return options.dims;
  const DomainBox box{data.boxMin(), data.boxMax()};
  const int longest = options.longestAxisNodes > 0 ? options.longestAxisNodes
                      : data.hasCells()            ? kDefaultMeshMaskNodes
                                                   : defaultCoverageResolution(data.pointCount());
  return defaultMaskDims(box, longest);
}

int defaultCellSamples(const ScatteredData& data, const EncodeOptions& options) {
  return data.hasCells() && !options.adaptive && !options.autoSmoothing ? kDefaultMeshCellSamples
                                                                        : 0;
}

Model encodeScattered(const ScatteredData& data, const EncodeOptions& options, FitReport* report) {
  ScatteredFitOptions fit;
  fit.degree = options.degree;
  fit.controlCounts = options.controlCounts;
  if (options.dequantizeStep)
    throw Error("--dequantize is for regular grids of quantized samples, not meshes or points");
  fit.smoothing = options.smoothing.value_or(kDefaultSmoothing);
  fit.knotDensity = options.knotDensity.value_or(data.hasCells() ? kDefaultMeshKnotDensity : 0.0);
  // With cell samples the fit sees more samples than the mesh has points; its default control
  // counts stay those of the points (the mesh's own resolution; adaptive fits start small
  // anyway).
  std::optional<ScatteredData> withCells;
  const int cellSamples = options.cellSamples.value_or(defaultCellSamples(data, options));
  if (cellSamples != 0) {
    if (!data.hasCells())
      throw Error(data.source +
                  ": cell samples (--cell-samples) need a mesh; a point cloud has no cells");
    if (!options.adaptive) fit.controlCounts = resolveScatteredControlCounts(data, fit);
    withCells = withCellSamples(data, cellSamples);
  }
  const ScatteredData& fitData = withCells ? *withCells : data;
  std::string smoothingNote;
  if (options.autoSmoothing) {
    // The choice takes most of the time: several fits of 7/8 of the points.
    ScatteredFitOptions choose = fit;
    if (options.progress)
      choose.progress = [&](double f, const std::string& stage) {
        options.progress(0.7 * f, stage);
      };
    const ScatteredSmoothingChoice choice = chooseScatteredSmoothing(fitData, choose);
    fit.smoothing = choice.lambda;
    smoothingNote = choice.note;
    if (options.progress)
      fit.progress = [&](double f, const std::string& stage) {
        options.progress(0.7 + 0.3 * f, stage);
      };
  } else {
    fit.progress = options.progress;
  }
  if (options.coding.budget.kind != BudgetKind::kNone ||
      (options.coding.coder && *options.coding.coder == ControlCoder::kZfp))
    throw Error(
        "meshes and point clouds take --coding float32 or lossless; zfp coding and "
        "budgets (--bits-per-sample, --psnr, --rms-error) are for regular grids");
  FitReport local;
  FitReport& r = report ? *report : local;
  Model model = options.adaptive ? fitScatteredAdaptive(fitData, fit, *options.adaptive, &r)
                                 : fitScattered(fitData, fit, &r);
  r.smoothingNote = smoothingNote;
  r.cellSamples = fitData.pointCount() - data.pointCount();
  r.points = data.pointCount();
  model.provenance().inputPoints = data.pointCount();
  if (options.mask.enabled) {
    const Index3 dims = maskDimsFor(data, options.mask);
    DomainMask mask = data.hasCells()
                          ? meshOccupancyMask(data.points, data.tets, model.domain(), dims)
                          : pointCoverageMask(data.points, model.domain(), dims);
    if (mask.insideFraction() == 0.0)
      throw Error(data.source +
                  ": the domain mask is empty (no mask node lies inside the data); use a finer "
                  "--mask-res or --no-mask");
    model.setMask(std::move(mask));
    r.maskKind = maskKindName(model.mask().kind());
    r.maskDims = model.mask().dims();
    r.maskInsideFraction = model.mask().insideFraction();
    if (data.hasCells() && options.mask.boundary) {
      const auto start = std::chrono::steady_clock::now();
      auto boundary =
          std::make_shared<const DomainBoundary>(boundaryOfTetrahedra(data.points, data.tets));
      r.boundaryTriangles = static_cast<std::int64_t>(boundary->triangles().size());
      r.boundaryVertices = static_cast<std::int64_t>(boundary->vertices().size());
      model.setBoundary(std::move(boundary));
      r.boundarySeconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    r.modelBytes = modelFileSize(model);
  }
  if (options.coding.coder) {
    model.setControlCoding({*options.coding.coder, 0.0});
    r.coding = controlCoderName(*options.coding.coder);
    r.modelBytes = modelFileSize(model);
  }
  return model;
}

}  // namespace mfadvr
