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

#include "app/BlockChoice.h"
#include "app/CodingCliOptions.h"
#include "app/Commands.h"
#include "app/EncodeCliOptions.h"
#include "app/FitReportOutput.h"
#include "app/OptionParsing.h"
#include "app/SceneLoader.h"
#include "core/analytic/BuiltinGridSource.h"
#include "core/analytic/BuiltinSeries.h"
#include "core/encode/Encoder.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/TimeSeriesEncoder.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "io/InputFile.h"
#include "io/ScatteredLoader.h"
#include "io/StreamedVolumeReader.h"
#include "io/VolumeLoader.h"
#include "io/VolumeSeriesReader.h"

namespace mfadvr::app {

namespace {

// Exit status when --strict is given and the bound was not reached.
constexpr int kBoundNotReached = 3;

// The rounds of an adaptive encode (--max-error), printed as they finish and kept for --json.
struct RoundLog {
  std::vector<AdaptiveRound> rounds;
  void attachTo(AdaptiveOptions& adaptive, bool progress) {
    adaptive.onRound = [this, progress](const AdaptiveRound& r) {
      rounds.push_back(r);
      if (progress)
        std::fprintf(stderr,
                     "  round %d: %lld x %lld x %lld control points, max error %.3e, %.1f s\n",
                     r.round, static_cast<long long>(r.controlCounts[0]),
                     static_cast<long long>(r.controlCounts[1]),
                     static_cast<long long>(r.controlCounts[2]), r.maxRelativeError, r.seconds);
    };
  }
  nlohmann::json json() const {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& r : rounds)
      list.push_back({{"round", r.round},
                      {"control_counts", r.controlCounts},
                      {"max_relative_error", r.maxRelativeError},
                      {"rms_relative_error", r.rmsRelativeError},
                      {"seconds", r.seconds}});
    return list;
  }
};

// Prints the report (text or --json, with the adaptive history), then the warning of a bound
// not reached, or with --strict the error; returns the exit status.
int reportEncode(FitReport report, const std::string& written, bool json, const RoundLog* rounds,
                 bool strict, bool wroteModel) {
  report.peakMemoryBytes = peakResidentBytes();
  if (json) {
    nlohmann::json j = fitReportJson(report, written);
    if (rounds) j["adaptive"]["history"] = rounds->json();
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << formatFitReport(report, written);
  }
  if (rounds && !report.reachedTarget) {
    std::cerr << "mfadvr: " << (strict ? "error" : "warning")
              << ": the error bound was not reached (" << report.stopReason << "); max error is "
              << report.maxRelativeError() << " of the value range";
    if (strict) {
      std::cerr << "; nothing written (--strict)\n";
      return kBoundNotReached;
    }
    std::cerr << (wroteModel ? "; wrote the best model" : "") << "\n";
  }
  return 0;
}

// `encode --blocks`: fits the blocks one at a time, appends each to the multi-block file as it
// is done, reports per block.
int encodeBlocks(GridSampleSource& source, const Index3& blocks, int ghost, EncodeOptions options,
                 const std::string& output, bool json, bool progress) {
  const StructuredGrid& layout = source.layout();
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
  double worst = 0.0;
  for (const FitReport& r : reports) worst = std::max(worst, r.maxRelativeError());
  const double samples = double(layout.sampleCount());
  if (json) {
    std::cout << blockFitReportJson(reports, regions, blocks, ghost, seconds, peak,
                                    double(layout.inputBytes), output)
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

// The options of a time series (docs/time-varying.md).
struct SeriesCliOptions {
  int degree = kDefaultTimeDegree;
  int controlCount = 0;
  std::string times;
  CLI::Option* degreeOption = nullptr;
  CLI::Option* controlOption = nullptr;
  bool given() const {
    return degreeOption->count() > 0 || controlOption->count() > 0 || !times.empty();
  }
};

// `encode SERIES`: one 4-D model of every step.
int encodeSeries(const std::string& input, const VolumeLoadOptions& load,
                 const SeriesCliOptions& cli, EncodeOptions options, const std::string& output,
                 bool json, bool progress, bool strict) {
  std::optional<std::vector<double>> times;
  if (!cli.times.empty()) times = parseNumberList("--times", cli.times, 2, 1 << 20);
  std::unique_ptr<VolumeSeries> series;
  if (isBuiltinSeriesSpec(input)) {
    if (load.spacing || load.origin || load.field.chosen())
      throw CLI::ValidationError("--spacing/--origin/--field",
                                 "apply to files, not to built-in functions");
    auto builtin = std::make_unique<BuiltinVolumeSeries>(input);
    if (times)
      builtin =
          std::make_unique<BuiltinVolumeSeries>(std::shared_ptr<const BuiltinSeriesFunction>(
                                                    makeBuiltinSeries(builtin->function().name())),
                                                builtin->dims(), *times);
    series = std::move(builtin);
  } else {
    series = openVolumeSeries(input, load, times);
  }
  if (progress)
    std::cerr << "  " << series->size() << " steps, t = " << series->time(0) << " .. "
              << series->time(series->size() - 1) << "\n";
  RoundLog rounds;
  if (options.adaptive) {
    rounds.attachTo(*options.adaptive, progress);
    options.progress = nullptr;  // the rounds say how it goes
  }
  TimeSeriesOptions time;
  time.degree = cli.degree;
  time.controlCount = cli.controlCount;
  time.zfpForIntegerSamples = true;
  FitReport report;
  std::vector<std::string> notes;
  const TimeVaryingModel model = encodeTimeSeries(*series, options, time, &report, &notes);
  for (const std::string& note : notes) std::cerr << "mfadvr: note: " << note << "\n";
  const bool failedStrict = strict && !report.reachedTarget;
  if (!output.empty() && !failedStrict) saveModel(model, output);
  return reportEncode(report, failedStrict ? std::string() : output, json,
                      options.adaptive ? &rounds : nullptr, strict, !output.empty());
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
    SeriesCliOptions series;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "encode", "Fit an MFA model (tensor-product B-spline) to a volume, mesh or point cloud");
  sub->add_option(
         "input", o->input,
         "Volume, mesh or point file, a built-in function builtin:NAME[:N|:NXxNYxNZ], or a time "
         "series (a .pvd or .series collection, a pattern name_%03d.nrrd, a folder of numbered "
         "volumes, builtin:orbiting-blobs[:NXxNYxNZxNT])\n" +
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
  o->series.degreeOption =
      sub->add_option("--time-degree", o->series.degree,
                      "Time series: degree of the model in time (1..7; lowered to steps - 1 for "
                      "fewer steps)")
          ->capture_default_str()
          ->check(CLI::Range(1, 7))
          ->group("Time series (docs/time-varying.md)");
  o->series.controlOption =
      sub->add_option("--time-ctrl", o->series.controlCount,
                      "Time series: control points in time (default: as many as steps, "
                      "interpolating every step; fewer: a least-squares fit in time)")
          ->check(CLI::PositiveNumber)
          ->group("Time series (docs/time-varying.md)");
  sub->add_option("--times", o->series.times,
                  "Time series: the time of each step T0,T1,... (increasing; default: the "
                  "collection's times, else the file numbers)")
      ->group("Time series (docs/time-varying.md)");
  sub->add_flag("--json", o->json, "Print the report as JSON");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  auto run = [o]() -> int {
    EncodeOptions options = o->encode.parse();
    options.coding = o->coding.parse();
    const bool series =
        isBuiltinSeriesSpec(o->input) ||
        isVolumeSeriesInput(o->input,
                            parseVolumeLoadOptions(o->spacing, o->origin, o->field).field);
    if (series) {
      if (!o->blocks.empty() || !o->memoryLimit.empty() || o->ghost >= 0)
        throw CLI::ValidationError("--blocks", "does not apply to time series yet");
      if (o->strict && !options.adaptive)
        throw CLI::ValidationError("--strict",
                                   "applies to adaptive encoding; give --max-error too");
      if (o->encode.scatteredOnlyGiven())
        throw CLI::ValidationError(
            "--mask-res/--no-mask/--no-boundary/--knot-density/--cell-samples",
            "apply to meshes and point clouds");
      const bool progress = wantProgress(o->quiet || o->json);
      if (progress) {
        std::cerr << "reading the series " << o->input << "\n";
        options.progress = [](double f, const std::string& stage) {
          printProgress("encoding", f, stage);
        };
      }
      return encodeSeries(o->input, parseVolumeLoadOptions(o->spacing, o->origin, o->field),
                          o->series, options, o->output, o->json, progress, o->strict);
    }
    if (o->series.given())
      throw CLI::ValidationError("--time-degree/--time-ctrl/--times",
                                 "apply to time series; " + o->input +
                                     " is one volume (docs/time-varying.md lists the series "
                                     "inputs)");
    const bool scattered = isScatteredInput(o->input);
    if (o->strict && !options.adaptive)
      throw CLI::ValidationError("--strict", "applies to adaptive encoding; give --max-error too");
    if (!scattered && o->encode.scatteredOnlyGiven())
      throw CLI::ValidationError(
          "--mask-res/--no-mask/--no-boundary/--knot-density/--cell-samples",
          "apply to meshes and point clouds; " + o->input + " is a regular grid");
    const BlockRequest blockRequest{o->blocks, o->ghost, o->memoryLimit};
    if (!o->blocks.empty() && scattered)
      throw CLI::ValidationError(
          "--blocks", "applies to regular grids; " + o->input + " holds scattered points");
    requireBlockOptions(blockRequest, options, o->strict);
    if (scattered && (!o->spacing.empty() || !o->origin.empty()))
      throw CLI::ValidationError("--spacing/--origin",
                                 "apply to regular grids; " + o->input + " holds scattered points");

    const bool progress = wantProgress(o->quiet || o->json);
    if (progress) std::cerr << "reading " << o->input << "\n";
    RoundLog rounds;
    if (options.adaptive) {
      rounds.attachTo(*options.adaptive, progress);
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
      // The blocks to encode: given, or chosen when an in-core encoding would not fit.
      auto chooseBlocksOf = [&](const StructuredGrid& layout) {
        for (const std::string& note : o->encode.fitDefaultDegreeToGrid(options, layout.dims))
          std::cerr << "mfadvr: note: " << note << "\n";
        CodingCliOptions::applyGridDefault(options.coding, layout.sampleType);
        BlockChoice choice = chooseBlocks(layout, blockRequest, options);
        if (!choice.note.empty()) std::cerr << "mfadvr: note: " << choice.note << "\n";
        return choice;
      };
      // --smooth auto chooses lambda on the whole grid: it is read into memory first.
      if (boxes && !options.autoSmoothing) {
        if (const BlockChoice choice = chooseBlocksOf(boxes->layout()); choice.blocks) {
          printReaderNotes(boxes->layout());
          return encodeBlocks(*boxes, *choice.blocks, choice.ghost, options, o->output, o->json,
                              progress);
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
      if (const BlockChoice choice = chooseBlocksOf(grid); choice.blocks) {
        InMemoryGridSource inMemory(grid);
        return encodeBlocks(inMemory, *choice.blocks, choice.ghost, options, o->output, o->json,
                            progress);
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
    return reportEncode(report, failedStrict ? std::string() : o->output, o->json,
                        options.adaptive ? &rounds : nullptr, o->strict, !o->output.empty());
  };
  return {sub, run};
}

}  // namespace mfadvr::app
