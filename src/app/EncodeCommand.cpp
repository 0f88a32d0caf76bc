// mfadvr encode INPUT [-o MODEL.mfa] [--degree ...] [--ctrl ...] [--max-error E ...]
//               [--blocks BX,BY,BZ [--ghost N]]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numeric>
#include <optional>

#include "app/CodingCliOptions.h"
#include "app/Commands.h"
#include "app/EncodeCliOptions.h"
#include "app/FitReportOutput.h"
#include "app/OptionParsing.h"
#include "app/SceneLoader.h"
#include "core/analytic/BuiltinGridSource.h"
#include "core/encode/Encoder.h"
#include "core/encode/PieceEncoder.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "io/InputFile.h"
#include "io/ScatteredLoader.h"
#include "io/StreamedVolumeReader.h"
#include "io/VolumeLoader.h"

namespace mfadvr::app {

namespace {

// Exit status when --strict is given and the bound was not reached.
constexpr int kBoundNotReached = 3;

// "8G", "512MB", "2e9": bytes, decimal units.
std::int64_t parseByteCount(const std::string& option, const std::string& text) {
  size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string unit = text.substr(used);
  std::transform(unit.begin(), unit.end(), unit.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  if (!unit.empty() && unit.back() == 'B') unit.pop_back();
  const double scale = unit.empty()  ? 1.0
                       : unit == "K" ? 1e3
                       : unit == "M" ? 1e6
                       : unit == "G" ? 1e9
                       : unit == "T" ? 1e12
                                     : 0.0;
  if (used == 0 || scale == 0.0 || !(value > 0.0) || !std::isfinite(value * scale) ||
      value * scale > 9e18)
    throw CLI::ValidationError(option,
                               "expected a positive size such as 8G, 512M or 2e9 (bytes), "
                               "got '" +
                                   text + "'");
  return static_cast<std::int64_t>(value * scale);
}

// The memory an in-core encoding of `dims` samples needs: the fit's peak, and for zfp coding
// one decoded candidate and its code beside the fit (measured: 15 B per sample at 512^3, 9 B
// with float32 coding).
std::int64_t inCoreEncodeBytes(const Index3& dims, const EncodeOptions& options) {
  Index3 counts = options.controlCounts;
  for (int a = 0; a < 3; ++a)
    if (counts[a] <= 0) counts[a] = dims[a];
  const std::int64_t ctrl = counts[0] * counts[1] * counts[2];
  const bool zfp = resolvedCoder(options.coding) == ControlCoder::kZfp;
  return structuredFitPeakBytes(dims, counts) + (zfp ? 8 * ctrl : 0);
}

// --blocks auto: at most kDefaultBlockIntervals intervals per block, then halved along the longest
// block axis until one block's encoding (ghost layers included) fits `limit`, or the blocks
// are as small as is worth it (ghost layers would then outweigh the block; the fit refuses with
// its own estimate when the memory really lacks).
constexpr std::int64_t kMinAutoBlockIntervals = 32;
Index3 autoBlockCounts(const Index3& dims, int ghost, const EncodeOptions& options,
                       std::int64_t limit) {
  Index3 blocks = defaultBlockCounts(dims);
  auto blockDims = [&](const Index3& b) {
    Index3 d;
    for (int a = 0; a < 3; ++a)
      d[a] = std::min<std::int64_t>(dims[a], (dims[a] - 1 + b[a] - 1) / b[a] + 1 + 2 * ghost);
    return d;
  };
  while (limit > 0 && inCoreEncodeBytes(blockDims(blocks), options) > limit) {
    const Index3 d = blockDims(blocks);
    int axis = -1;
    for (int a = 0; a < 3; ++a)
      if ((dims[a] - 1) / (2 * blocks[a]) >= kMinAutoBlockIntervals && (axis < 0 || d[a] > d[axis]))
        axis = a;
    if (axis < 0) break;
    blocks[axis] *= 2;
  }
  return blocks;
}

// `encode --blocks`: fits the blocks one at a time, appends each to the multi-block file as it
// is done, reports per block.
int encodeBlocks(GridSampleSource& source, const Index3& blocks, int ghost, EncodeOptions options,
                 const std::string& output, bool json, bool progress) {
  const StructuredGrid& layout = source.layout();
  for (int a = 0; a < 3; ++a)
    if (blocks[a] < 1 || blocks[a] > layout.dims[a] - 1 + (layout.dims[a] == 1))
      throw CLI::ValidationError(
          "--blocks", "each axis needs 1 to (samples - 1) blocks; the grid has " +
                          std::to_string(layout.dims[0]) + "x" + std::to_string(layout.dims[1]) +
                          "x" + std::to_string(layout.dims[2]) + " samples");
  if (ghost < 0) ghost = defaultGhostLayers(options.degree);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const double megabytes = double(layout.inputBytes) / 1e6;
  options.progress = nullptr;
  if (progress) options.progress = ThroughputProgress("encoding", double(layout.inputBytes));
  std::optional<BlockModelFileWriter> file;
  if (!output.empty()) file.emplace(output, blocks);
  std::vector<FitReport> reports;
  std::vector<DomainBox> regions;
  encodeStructuredBlocks(source, blocks, ghost, options,
                         [&](ModelBlock&& b, const FitReport& report) {
                           if (file) file->append(b);
                           reports.push_back(report);
                           regions.push_back(b.region);
                         });
  if (file) file->commit();
  const double seconds = elapsed();
  const std::int64_t peak = peakResidentBytes();
  double worst = 0.0, fitSeconds = 0.0;
  for (const FitReport& r : reports) {
    worst = std::max(worst, r.maxRelativeError());
    fitSeconds += r.seconds;
  }
  const double samples = double(layout.sampleCount());
  if (json) {
    nlohmann::json list = nlohmann::json::array();
    for (size_t i = 0; i < reports.size(); ++i) {
      nlohmann::json j = fitReportJson(reports[i], "");
      const DomainBox& r = regions[i];
      j["region"] = {r.min[0], r.max[0], r.min[1], r.max[1], r.min[2], r.max[2]};
      list.push_back(j);
    }
    std::cout << nlohmann::json{{"output", output},
                                {"blocks", blocks},
                                {"ghost_layers", ghost},
                                {"max_relative_error", worst},
                                {"fit_seconds", fitSeconds},
                                {"seconds", seconds},
                                {"input_megabytes_per_second", megabytes / seconds},
                                {"peak_memory_bytes", peak},
                                {"block_reports", list}}
                     .dump(2)
              << "\n";
  } else {
    std::printf("%lld x %lld x %lld blocks of %s (%s samples), %d ghost layers\n",
                static_cast<long long>(blocks[0]), static_cast<long long>(blocks[1]),
                static_cast<long long>(blocks[2]), layout.source.c_str(),
                groupDigits(layout.sampleCount()).c_str(), ghost);
    // Hundreds of blocks (out-of-core volumes) would bury the summary: list the worst few.
    std::vector<size_t> order(reports.size());
    std::iota(order.begin(), order.end(), size_t{0});
    const size_t shown = reports.size() <= 16 ? reports.size() : 4;
    if (shown < reports.size())
      std::partial_sort(order.begin(), order.begin() + shown, order.end(), [&](size_t a, size_t b) {
        return reports[a].maxRelativeError() > reports[b].maxRelativeError();
      });
    if (shown < reports.size()) std::printf("  the %zu blocks of largest error:\n", shown);
    for (size_t n = 0; n < shown; ++n) {
      const size_t i = order[n];
      const auto& c = reports[i].controlCounts;
      std::printf("  block %zu: %lld x %lld x %lld control points, max error %.3g of the range\n",
                  i, static_cast<long long>(c[0]), static_cast<long long>(c[1]),
                  static_cast<long long>(c[2]), reports[i].maxRelativeError());
    }
    std::printf("max error over the blocks: %.3g of the value range\n", worst);
    std::printf("time: %.2f s (%.1f MB of input per second); peak memory %s (%s bytes/sample)\n",
                seconds, megabytes / seconds, formatBytes(peak).c_str(),
                bytesPerSampleText(double(peak) / samples).c_str());
    if (file) {
      const auto bytes = static_cast<std::int64_t>(std::filesystem::file_size(output));
      std::printf("wrote %s (%s bytes, %.3f bits/sample)\n", output.c_str(),
                  groupDigits(bytes).c_str(), 8.0 * double(bytes) / samples);
    }
  }
  return 0;
}

}  // namespace

Command addEncodeCommand(CLI::App& app) {
  struct Options {
    std::string input, output, spacing, origin, blocks, memoryLimit;
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
                  "Grids: split into BX,BY,BZ blocks (or B on every axis, or 'auto': at most 256 "
                  "sample intervals per block), each fitted with ghost layers around it, and write "
                  "a multi-block model (for parallel rendering: one block per MPI rank in "
                  "ParaView). Raw files and built-in functions are then read one block at a time "
                  "(out of core), and blocks are written as they are done")
      ->group("Blocks");
  sub->add_option("--memory-limit", o->memoryLimit,
                  "Grids: the memory an in-core encoding may plan for (e.g. 8G, 512M; default "
                  "half the available memory); without --blocks, an input that would need more "
                  "is encoded with --blocks auto")
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
      const VolumeLoadOptions load = parseVolumeLoadOptions(o->spacing, o->origin, o->field);
      // Built-in functions and files that store their samples plainly (raw, and NRRD,
      // MetaImage, NIfTI, legacy VTK payloads) can be read a box at a time (out of core).
      std::unique_ptr<GridSampleSource> boxes;
      if (isBuiltinSpec(o->input)) {
        if (!load.spacing && !load.origin && !load.field.chosen())
          boxes = std::make_unique<BuiltinGridSource>(o->input);
      } else {
        InflateProgress inflating;
        if (progress)
          inflating = [printer = ThroughputProgress("inflating")](
                          std::int64_t done, std::int64_t total) { printer.bytes(done, total); };
        boxes =
            openStreamedVolume(o->input, load, GzipPayloads::kInflateToTemporaryFile, inflating);
      }
      const std::int64_t limit = o->memoryLimit.empty()
                                     ? availableMemoryBytes() / 2
                                     : parseByteCount("--memory-limit", o->memoryLimit);
      // The blocks to encode: given, or chosen when an in-core encoding would not fit.
      auto chooseBlocks = [&](const StructuredGrid& layout) -> std::optional<Index3> {
        for (const std::string& note : o->encode.fitDefaultDegreeToGrid(options, layout.dims))
          std::cerr << "mfadvr: note: " << note << "\n";
        CodingCliOptions::applyGridDefault(options.coding, layout.sampleType);
        const int ghost = o->ghost >= 0 ? o->ghost : defaultGhostLayers(options.degree);
        if (o->blocks == "auto") return autoBlockCounts(layout.dims, ghost, options, limit);
        if (!o->blocks.empty()) {
          const auto n = parseIntTriple("--blocks", o->blocks);
          return Index3{n[0], n[1], n[2]};
        }
        const std::int64_t need = inCoreEncodeBytes(layout.dims, options);
        if (options.adaptive || limit <= 0 || need <= limit) return std::nullopt;
        const Index3 b = autoBlockCounts(layout.dims, ghost, options, limit);
        if (b[0] * b[1] * b[2] == 1) return std::nullopt;
        if (b[0] * b[1] * b[2] > kMaxBlockCount)
          throw mfadvr::Error(
              "encoding " + layout.source + " needs about " + formatBytes(need) +
              " of memory, more than " + formatBytes(limit) + " (" +
              (o->memoryLimit.empty() ? "half of what is available" : "--memory-limit") +
              "), and out of core it would take " + std::to_string(b[0] * b[1] * b[2]) +
              " blocks, more than a multi-block model holds (" + std::to_string(kMaxBlockCount) +
              ")");
        std::cerr << "mfadvr: note: encoding " << layout.source << " in memory would need about "
                  << formatBytes(need) << ", more than " << formatBytes(limit)
                  << (o->memoryLimit.empty() ? " (half the available memory)" : " (--memory-limit)")
                  << ": encoding it in " << b[0] << "x" << b[1] << "x" << b[2]
                  << " blocks (--blocks auto), a multi-block model\n";
        return b;
      };
      // --smooth auto chooses lambda on the whole grid: it is read into memory first.
      if (boxes && !options.autoSmoothing) {
        if (const auto blocks = chooseBlocks(boxes->layout())) {
          printReaderNotes(boxes->layout());
          return encodeBlocks(*boxes, *blocks, o->ghost, options, o->output, o->json, progress);
        }
      }
      if (isBuiltinSpec(o->input)) boxes.reset();  // sampled whole below, after a memory check
      if (isBuiltinSpec(o->input) && !options.adaptive) {
        // Known before sampling: refuse a fit that cannot fit in memory at once.
        const Index3 dims = parseBuiltinSpec(o->input).dims;
        Index3 counts = options.controlCounts;
        for (int a = 0; a < 3; ++a)
          if (counts[a] <= 0) counts[a] = dims[a];
        requireMemory(structuredFitPeakBytes(dims, counts),
                      "encoding " + o->input + " (fewer control points, --ctrl, need less)");
      }
      // A file source already open is read whole from it (gzip data is not inflated twice).
      StructuredGrid grid;
      if (boxes) {
        grid = boxes->read(wholeRange(boxes->layout().dims));
        grid.notes = boxes->layout().notes;
      } else {
        grid = loadStructuredVolume(o->input, load);
      }
      printReaderNotes(grid);
      if (const auto blocks = chooseBlocks(grid)) {
        InMemoryGridSource inMemory(grid);
        return encodeBlocks(inMemory, *blocks, o->ghost, options, o->output, o->json, progress);
      }
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
