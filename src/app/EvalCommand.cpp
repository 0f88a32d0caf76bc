// mfadvr eval paper --out DIR [--quick] [--only NAME,...]: the paper's evaluation, reproduced
// (src/eval, docs/evaluation.md).
#include <cstdio>
#include <cstdlib>
#include <iostream>

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
  std::printf("report: %s (%d matches, %d differences with the paper), %.0f s\n",
              s.report.c_str(), s.matches, s.differences, s.seconds);
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

}  // namespace

Command addEvalCommand(CLI::App& app) {
  struct Options {
    eval::EvalOptions eval;
    std::string out, dataDir = defaultDataDir();
    bool noPlots = false, noVtk = false, quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub =
      app.add_subcommand("eval", "Run an evaluation and write its tables, plots and report");
  sub->require_subcommand(1);
  CLI::App* paper = sub->add_subcommand(
      "paper",
      "Reproduce the paper's results section: value accuracy (Gaussian beams), Tables 1-2 "
      "(Marschner-Lobb), real structured and unstructured data, parameter studies, render time "
      "vs data size; CSVs, plots, images and report.md in --out");
  paper->add_option("--out", o->out, "Output folder (created; files in it are replaced)")
      ->required();
  paper->add_flag("--quick", o->eval.quick,
                  "Small grids, images and size ranges: a few minutes on 2 cores (the smoke test)");
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
  paper->add_option("--volume", o->eval.volumes,
                    "Add a structured volume to the real-data gallery (repeatable; any format "
                    "`render` reads)");
  paper->add_option("--mesh", o->eval.meshes,
                    "Add a tetrahedral mesh to the unstructured gallery (repeatable; .vtu, .vtk)");
  paper
      ->add_option("--data", o->dataDir,
                   "Folder with the standard data sets (fuel, nucleon, bonsai, bluntfin, spx); "
                   "missing ones are skipped")
      ->capture_default_str();
  paper->add_option("--threads", o->eval.threads, "Ray-casting threads (0: all cores)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  paper->add_flag("--no-plots", o->noPlots, "Do not run the plot script (python3-matplotlib)");
  paper->add_flag("--no-vtk", o->noVtk,
                  "Leave out VTK's renderers (they need an X display: use xvfb-run -a)");
  paper->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  // `eval compression`: the compression study alone (the `compression` experiment), with the
  // options that apply to it.
  auto c = std::make_shared<Options>();
  CLI::App* compression = sub->add_subcommand(
      "compression",
      "Rate-distortion of coded MFA models against ZFP (fixed-rate, fixed-accuracy) and "
      "downsampling at equal bytes: volume PSNR, rendered-image PSNR/SSIM and memory, on "
      "Marschner-Lobb, VTK's Wavelet source and the standard volumes (docs/compression.md); the "
      "same as `eval paper --only compression`");
  compression->add_option("--out", c->out, "Output folder (created; files in it are replaced)")
      ->required();
  compression->add_flag("--quick", c->eval.quick,
                        "Two small volumes at 0.5, 1 and 2 bits/sample, 96x96 images (seconds)");
  compression->add_option("--volume", c->eval.volumes,
                          "Add a structured volume (repeatable; any format `render` reads)");
  compression
      ->add_option("--data", c->dataDir,
                   "Folder with the standard data sets (fuel, neghip, nucleon, bonsai); missing "
                   "ones are skipped")
      ->capture_default_str();
  compression->add_option("--threads", c->eval.threads, "Ray-casting threads (0: all cores)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  compression->add_flag("-q,--quiet", c->quiet, "No progress on stderr");

  auto run = [o, c, paper, compression]() -> int {
    if (compression->parsed()) {
      c->eval.only = {"compression"};
      c->noPlots = true;  // the study's table is its figure; bench/compression_rd.py plots
      c->noVtk = true;
      std::string commandLine = "mfadvr eval compression --out " + c->out;
      if (c->eval.quick) commandLine += " --quick";
      for (const auto& v : c->eval.volumes) commandLine += " --volume " + v;
      *o = *c;
      o->eval.out = o->out;
      o->eval.dataDir = o->dataDir;
      o->eval.plots = false;
      o->eval.vtk = false;
      o->eval.progress = !o->quiet;
      return reportSummary(eval::runPaperEvaluation(o->eval, commandLine));
    }
    if (!paper->parsed()) return 2;
    o->eval.out = o->out;
    o->eval.dataDir = o->dataDir;
    o->eval.plots = !o->noPlots;
    o->eval.vtk = !o->noVtk;
    // One line per step (no progress bars), so a log file of a long run is useful too.
    o->eval.progress = !o->quiet;
    std::string commandLine = "mfadvr eval paper --out " + o->out;
    if (o->eval.quick) commandLine += " --quick";
    for (std::size_t i = 0; i < o->eval.only.size(); ++i)
      commandLine += (i ? "," : " --only ") + o->eval.only[i];
    for (const auto& v : o->eval.volumes) commandLine += " --volume " + v;
    for (const auto& m : o->eval.meshes) commandLine += " --mesh " + m;
    if (o->noVtk) commandLine += " --no-vtk";
    if (o->noPlots) commandLine += " --no-plots";
    return reportSummary(eval::runPaperEvaluation(o->eval, commandLine));
  };
  return {sub, run};
}

}  // namespace mfadvr::app
