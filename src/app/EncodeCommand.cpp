// mfadvr encode INPUT [-o MODEL.mfa] [--degree ...] [--ctrl ...] [--max-error E ...]
//               [--blocks BX,BY,BZ [--ghost N]]
#include <iostream>

#include "app/CodingCliOptions.h"
#include "app/Commands.h"
#include "app/EncodeCliOptions.h"
#include "app/FitReportOutput.h"
#include "app/OptionParsing.h"
#include "app/SceneLoader.h"
#include "core/encode/Encoder.h"
#include "core/encode/PieceEncoder.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "core/util/MemoryBudget.h"
#include "io/ScatteredLoader.h"
#include "io/VolumeLoader.h"

namespace mfadvr::app {

namespace {

// Exit status when --strict is given and the bound was not reached.
constexpr int kBoundNotReached = 3;

// `encode --blocks`: fits the blocks, writes the multi-block file, reports per block.
int encodeBlocks(const StructuredGrid& grid, const std::string& blocksText, int ghost,
                 const EncodeOptions& options, const std::string& output, bool json) {
  const auto n = parseIntTriple("--blocks", blocksText);
  const Index3 blocks{n[0], n[1], n[2]};
  for (int a = 0; a < 3; ++a)
    if (blocks[a] < 1 || blocks[a] > grid.dims[a] - 1 + (grid.dims[a] == 1))
      throw CLI::ValidationError(
          "--blocks", "each axis needs 1 to (samples - 1) blocks; the grid has " +
                          std::to_string(grid.dims[0]) + "x" + std::to_string(grid.dims[1]) + "x" +
                          std::to_string(grid.dims[2]) + " samples");
  if (ghost < 0) ghost = defaultGhostLayers(options.degree);
  std::vector<FitReport> reports;
  const std::vector<ModelBlock> models =
      encodeStructuredBlocks(grid, blocks, ghost, options, &reports);
  if (!output.empty()) saveBlockModels(models, blocks, output);
  double worst = 0.0, seconds = 0.0;
  for (const FitReport& r : reports) {
    worst = std::max(worst, r.maxRelativeError());
    seconds += r.seconds;
  }
  if (json) {
    nlohmann::json list = nlohmann::json::array();
    for (size_t i = 0; i < reports.size(); ++i) {
      nlohmann::json j = fitReportJson(reports[i], "");
      const DomainBox& r = models[i].region;
      j["region"] = {r.min[0], r.max[0], r.min[1], r.max[1], r.min[2], r.max[2]};
      list.push_back(j);
    }
    std::cout << nlohmann::json{{"output", output},       {"blocks", blocks},
                                {"ghost_layers", ghost},  {"max_relative_error", worst},
                                {"fit_seconds", seconds}, {"block_reports", list}}
                     .dump(2)
              << "\n";
  } else {
    std::printf("%lld x %lld x %lld blocks of %s (%s samples), %d ghost layers\n",
                static_cast<long long>(blocks[0]), static_cast<long long>(blocks[1]),
                static_cast<long long>(blocks[2]), grid.source.c_str(),
                groupDigits(grid.sampleCount()).c_str(), ghost);
    for (size_t i = 0; i < reports.size(); ++i) {
      const auto& c = reports[i].controlCounts;
      std::printf("  block %zu: %lld x %lld x %lld control points, max error %.3g of the range\n",
                  i, static_cast<long long>(c[0]), static_cast<long long>(c[1]),
                  static_cast<long long>(c[2]), reports[i].maxRelativeError());
    }
    std::printf("max error over the blocks: %.3g of the value range; fit %.2f s\n", worst, seconds);
    if (!output.empty())
      std::printf(
          "wrote %s (%s bytes)\n", output.c_str(),
          groupDigits(static_cast<std::int64_t>(std::filesystem::file_size(output))).c_str());
  }
  return 0;
}

}  // namespace

Command addEncodeCommand(CLI::App& app) {
  struct Options {
    std::string input, output, spacing, origin, blocks;
    FieldOptionTexts field;
    int ghost = -1;
    bool json = false, quiet = false, strict = false;
    EncodeCliOptions encode;
    CodingCliOptions coding;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "encode", "Fit an MFA model (tensor-product B-spline) to a volume, mesh or point cloud");
  sub->add_option(
         "input", o->input,
         "Volume, mesh or point file, or a built-in function builtin:NAME[:N|:NXxNYxNZ]\n" +
             supportedVolumeFormats() + "\n" + supportedScatteredFormats())
      ->required();
  sub->add_option("-o,--output", o->output,
                  "Model file to write (.mfa); without it only the report is printed");
  o->encode.addTo(sub, "Encoding");
  o->coding.addTo(sub, "Storage (control-point coding, budgets; docs/compression.md)");
  sub->add_flag("--strict", o->strict,
                "With --max-error: exit with status 3 and write nothing when a limit stops "
                "refinement before the bound is reached");
  sub->add_option("--spacing", o->spacing,
                  "Grids: sample spacing S or SX,SY,SZ (overrides the file's)")
      ->group("Input");
  sub->add_option("--origin", o->origin,
                  "Grids: position of the first sample X,Y,Z (overrides the file's)")
      ->group("Input");
  o->field.addTo(sub, "Input");
  sub->add_option("--blocks", o->blocks,
                  "Grids: split into BX,BY,BZ blocks (or B on every axis), each fitted with "
                  "ghost layers around it, and write a multi-block model (for parallel "
                  "rendering: one block per MPI rank in ParaView)")
      ->group("Blocks");
  sub->add_option("--ghost", o->ghost,
                  "With --blocks: sample layers of the neighbouring blocks each block is fitted "
                  "with (default 2 x (degree + 1))")
      ->check(CLI::Range(0, 1024))
      ->group("Blocks");
  sub->add_flag("--json", o->json, "Print the report as JSON");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  auto run = [o]() -> int {
    EncodeOptions options = o->encode.parse();
    options.coding = o->coding.parse();
    const bool scattered = isScatteredInput(o->input);
    if (o->strict && !options.adaptive)
      throw CLI::ValidationError("--strict", "applies to adaptive encoding; give --max-error too");
    if (scattered && options.autoSmoothing)
      throw CLI::ValidationError("--smooth",
                                 "'auto' is for regular grids; give meshes and point clouds a "
                                 "weight (default 1e-2)");
    if (!scattered && (!o->encode.maskRes.empty() || o->encode.noMask))
      throw CLI::ValidationError("--mask-res/--no-mask", "apply to meshes and point clouds; " +
                                                             o->input + " is a regular grid");
    if (o->ghost >= 0 && o->blocks.empty())
      throw CLI::ValidationError("--ghost", "applies with --blocks");
    if (!o->blocks.empty() && scattered)
      throw CLI::ValidationError(
          "--blocks", "applies to regular grids; " + o->input + " holds scattered points");
    if (!o->blocks.empty() && (options.adaptive || o->strict))
      throw CLI::ValidationError("--blocks", "does not combine with --max-error yet");
    if (scattered && (!o->spacing.empty() || !o->origin.empty()))
      throw CLI::ValidationError("--spacing/--origin",
                                 "apply to regular grids; " + o->input + " holds scattered points");

    const bool progress = wantProgress(o->quiet || o->json);
    if (progress) std::cerr << "reading " << o->input << "\n";
    std::vector<AdaptiveRound> rounds;
    if (options.adaptive) {
      options.adaptive->onRound = [&rounds, progress](const AdaptiveRound& r) {
        rounds.push_back(r);
        if (progress)
          std::fprintf(stderr,
                       "  round %d: %lld x %lld x %lld control points, max error %.3e, %.1f s\n",
                       r.round, static_cast<long long>(r.controlCounts[0]),
                       static_cast<long long>(r.controlCounts[1]),
                       static_cast<long long>(r.controlCounts[2]), r.maxRelativeError, r.seconds);
      };
    } else if (progress) {
      options.progress = [](double f, const std::string& stage) {
        printProgress("encoding", f, stage);
      };
    }

    FitReport report;
    Model model;
    if (scattered) {
      ScatteredLoadOptions load;
      load.field = o->field.parse();
      const ScatteredData data = loadScatteredData(o->input, load);
      if (progress)
        std::cerr << "  " << data.kind << ": " << groupDigits(data.pointCount()) << " points"
                  << (data.hasCells()
                          ? ", " + groupDigits(static_cast<std::int64_t>(data.tets.size())) +
                                " tetrahedra"
                          : "")
                  << "\n";
      model = encodeScattered(data, options, &report);
    } else {
      if (isBuiltinSpec(o->input) && o->blocks.empty() && !options.adaptive) {
        // Known before sampling: refuse a fit that cannot fit in memory at once.
        const Index3 dims = parseBuiltinSpec(o->input).dims;
        Index3 counts = options.controlCounts;
        for (int a = 0; a < 3; ++a)
          if (counts[a] <= 0) counts[a] = dims[a];
        requireMemory(structuredFitPeakBytes(dims, counts),
                      "encoding " + o->input + " (fewer control points, --ctrl, need less)");
      }
      const VolumeLoadOptions load = parseVolumeLoadOptions(o->spacing, o->origin, o->field);
      const StructuredGrid grid = loadStructuredVolume(o->input, load);
      printReaderNotes(grid);
      for (const std::string& note : o->encode.fitDefaultDegreeToGrid(options, grid.dims))
        std::cerr << "mfadvr: note: " << note << "\n";
      CodingCliOptions::applyGridDefault(options.coding, grid.sampleType);
      if (!o->blocks.empty())
        return encodeBlocks(grid, o->blocks, o->ghost, options, o->output, o->json);
      model = encodeStructured(grid, options, &report);
    }
    if (report.points > 0 && report.solverResidual > 1e-4)
      std::cerr << "mfadvr: warning: the solver stopped at a relative residual of "
                << report.solverResidual
                << " (not converged); the fit may be inaccurate: a larger --smooth converges "
                   "faster\n";
    const bool failedStrict = o->strict && !report.reachedTarget;
    if (!o->output.empty() && !failedStrict) saveModel(model, o->output);
    report.peakMemoryBytes = peakResidentBytes();
    const std::string written = failedStrict ? std::string() : o->output;
    if (o->json) {
      nlohmann::json j = fitReportJson(report, written);
      if (options.adaptive) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& r : rounds)
          list.push_back({{"round", r.round},
                          {"control_counts", r.controlCounts},
                          {"max_relative_error", r.maxRelativeError},
                          {"rms_relative_error", r.rmsRelativeError},
                          {"seconds", r.seconds}});
        j["adaptive"]["history"] = list;
      }
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << formatFitReport(report, written);
    }
    if (options.adaptive && !report.reachedTarget) {
      std::cerr << "mfadvr: " << (o->strict ? "error" : "warning")
                << ": the error bound was not reached (" << report.stopReason << "); max error is "
                << report.maxRelativeError() << " of the value range";
      if (o->strict) {
        std::cerr << "; nothing written (--strict)\n";
        return kBoundNotReached;
      }
      std::cerr << (o->output.empty() ? "" : "; wrote the best model") << "\n";
    }
    return 0;
  };
  return {sub, run};
}

}  // namespace mfadvr::app
