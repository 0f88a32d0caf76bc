// mfadvr eval paper --out DIR [--quick] [--only NAME,...]: the paper's evaluation, reproduced
// (src/eval, docs/evaluation.md); mfadvr eval compression --out DIR: the compression study.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <utility>

#include "app/Commands.h"
#include "eval/PaperEvaluation.h"

namespace mfadvr::app {

namespace {

// Where the standard data sets are looked for: $MFADVR_DATA_DIR, else the folder the build was
// configured with (MFADVR_DATA_DIR, by default ../shared/data beside the source).
std::string defaultDataDir() {
  if (const char* d = std::getenv("MFADVR_DATA_DIR"); d && *d) return d;
  return MFADVR_DEFAULT_DATA_DIR;
}

// Prints where the report is; exit status 1 when an experiment failed, an input was skipped or
// the plots were not made.
int reportSummary(const eval::EvaluationSummary& s) {
  std::printf("report: %s (%d matches, %d differences with the paper), %.0f s\n", s.report.c_str(),
              s.matches, s.differences, s.seconds);
  int status = 0;
  for (const auto& f : s.failed) {
    std::fprintf(stderr, "mfadvr: error: experiment '%s' failed (see the report)\n", f.c_str());
    status = 1;
  }
  for (const auto& p : s.problems) {
    std::fprintf(stderr, "mfadvr: error: input skipped: %s\n", p.c_str());
    status = 1;
  }
  if (!s.plotError.empty()) {
    std::fprintf(stderr, "mfadvr: error: plots not made: %s\n", s.plotError.c_str());
    status = 1;
  }
  return status;
}

// The options of one `eval` subcommand.
struct EvalCliOptions {
  eval::EvalOptions eval;
  std::string out, dataDir = defaultDataDir();
  bool noPlots = false, noVtk = false, quiet = false;
};

// --out, --quick, --threads and -q, which every `eval` subcommand takes, and --volume and --data
// for those that read data (a volumeHelp).
void addSharedOptions(CLI::App* sub, EvalCliOptions& o, const std::string& quickHelp,
                      const std::string& volumeHelp, const std::string& dataSets) {
  sub->add_option("--out", o.out, "Output folder (created; files in it are replaced)")->required();
  sub->add_flag("--quick", o.eval.quick, quickHelp);
  if (!volumeHelp.empty()) {
    sub->add_option("--volume", o.eval.volumes, volumeHelp);
    sub->add_option(
           "--data", o.dataDir,
           "Folder with the standard data sets (" + dataSets + "); missing ones are skipped")
        ->capture_default_str();
  }
  sub->add_option("--threads", o.eval.threads, "Ray-casting threads (0: all cores)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_flag("-q,--quiet", o.quiet, "No progress on stderr");
}

// A subcommand running the one experiment `name` (no VTK renderers, no plots).
std::pair<std::shared_ptr<EvalCliOptions>, CLI::App*> addSingleExperiment(
    CLI::App* parent, const std::string& name, const std::string& description,
    const std::string& quickHelp, const std::string& volumeHelp, const std::string& dataSets) {
  auto options = std::make_shared<EvalCliOptions>();
  options->noPlots = options->noVtk = true;
  options->eval.only = {name};
  CLI::App* app = parent->add_subcommand(name, description);
  addSharedOptions(app, *options, quickHelp, volumeHelp, dataSets);
  return {options, app};
}

int runEvaluation(EvalCliOptions& o, const std::string& command) {
  o.eval.out = o.out;
  o.eval.dataDir = o.dataDir;
  o.eval.plots = !o.noPlots;
  o.eval.vtk = !o.noVtk;
  // One line per step (no progress bars), so a log file of a long run is useful too.
  o.eval.progress = !o.quiet;
  std::string commandLine = "mfadvr eval " + command + " --out " + o.out;
  if (o.eval.quick) commandLine += " --quick";
  if (command == "paper")
    for (std::size_t i = 0; i < o.eval.only.size(); ++i)
      commandLine += (i ? "," : " --only ") + o.eval.only[i];
  for (const auto& v : o.eval.volumes) commandLine += " --volume " + v;
  for (const auto& m : o.eval.meshes) commandLine += " --mesh " + m;
  if (command == "paper" && o.noVtk) commandLine += " --no-vtk";
  if (command == "paper" && o.noPlots) commandLine += " --no-plots";
  return reportSummary(eval::runPaperEvaluation(o.eval, commandLine));
}

}  // namespace

Command addEvalCommand(CLI::App& app) {
  auto o = std::make_shared<EvalCliOptions>();
  CLI::App* sub =
      app.add_subcommand("eval", "Run an evaluation and write its tables, plots and report");
  sub->require_subcommand(1);
  CLI::App* paper = sub->add_subcommand(
      "paper",
      "Reproduce the paper's results section: value accuracy (Gaussian beams), Tables 1-2 "
      "(Marschner-Lobb), real structured and unstructured data, parameter studies, render time "
      "vs data size, and beyond it the compression study; CSVs, plots, images and report.md in "
      "--out");
  addSharedOptions(paper, *o,
                   "Small grids, images and size ranges: a few minutes on 2 cores (the smoke test)",
                   "Add a structured volume to the real-data gallery and the compression study "
                   "(repeatable; any format `render` reads)",
                   "fuel, neghip, nucleon, bonsai, bluntfin, spx");
  paper
      ->add_option(
          "--only", o->eval.only,
          "Run only these experiments, comma-separated: " +
              [] {
                std::string s;
                for (const auto& n : eval::experimentNames()) s += (s.empty() ? "" : ", ") + n;
                return s;
              }())
      ->delimiter(',');
  paper->add_option("--mesh", o->eval.meshes,
                    "Add a tetrahedral mesh to the unstructured gallery (repeatable; .vtu, .vtk)");
  paper->add_flag("--no-plots", o->noPlots, "Do not run the plot script (python3-matplotlib)");
  paper->add_flag("--no-vtk", o->noVtk,
                  "Leave out VTK's renderers (they need an X display: use xvfb-run -a)");

  // `eval compression` and `eval denoise`: one experiment alone; neither needs VTK's renderers
  // nor the plot script (bench/compression_rd.py plots rate-distortion curves).
  const auto [c, compression] = addSingleExperiment(
      sub, "compression",
      "Rate-distortion of coded MFA models against ZFP (fixed-rate, fixed-accuracy) and "
      "downsampling at equal bytes: volume PSNR, rendered-image PSNR/SSIM and memory, on "
      "Marschner-Lobb, VTK's Wavelet source and the standard volumes (docs/compression.md); the "
      "same as `eval paper --only compression`",
      "Two small volumes at 0.5, 1 and 2 bits/sample, 96x96 images (seconds)",
      "Add a structured volume (repeatable; any format `render` reads)",
      "fuel, neghip, nucleon, bonsai");
  const auto [d, denoise] = addSingleExperiment(
      sub, "denoise",
      "Smoothing fits of noisy and quantized samples (Marschner-Lobb, the CT head phantom) "
      "against the clean function's truth, beside every grid filter, and real scans with and "
      "without smoothing (docs/denoise.md); the same as `eval paper --only denoise`",
      "41^3 grids, 8-bit and 3% noise only, 128x128 images (seconds)",
      "Add a real scan, rendered with and without smoothing (repeatable; any format `render` "
      "reads)",
      "neghip, bonsai");

  const auto [t, time] = addSingleExperiment(
      sub, "time",
      "One 4-D model of a time series (the built-in orbiting-blobs at 8, 16 and 32 steps) against "
      "the linear interpolation of neighbouring steps and the nearest step, halfway between "
      "steps: value PSNR, rendered images, and the coded model's size against per-step models "
      "and ZFP 4-D (docs/time-varying.md); the same as `eval paper --only time`",
      "24^3 grids, 8 and 16 steps, 128x128 images (seconds)", "", "");
  auto run = [o, c = c, d = d, t = t, paper, compression = compression, denoise = denoise,
              time = time]() -> int {
    if (compression->parsed()) return runEvaluation(*c, "compression");
    if (denoise->parsed()) return runEvaluation(*d, "denoise");
    if (time->parsed()) return runEvaluation(*t, "time");
    if (!paper->parsed()) return 2;
    return runEvaluation(*o, "paper");
  };
  return {sub, run};
}

}  // namespace mfadvr::app
