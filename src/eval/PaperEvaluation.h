#pragma once
// `mfadvr eval paper`: runs the experiments of the paper's results section (docs/architecture.md,
// Evaluation protocol), writes a CSV per table and figure, the images and image grids, the plot
// script and its PNG plots, and report.md, which sets our numbers beside the paper's.
#include <string>
#include <vector>

#include "eval/EvalContext.h"

namespace mfadvr::eval {

std::vector<std::string> experimentNames();

struct EvaluationSummary {
  std::string report;               // path of report.md
  double seconds = 0.0;             // wall time
  std::vector<std::string> failed;  // experiments that stopped with an error
  // Inputs an experiment skipped because they could not be used, as "experiment: why".
  std::vector<std::string> problems;
  std::string plotError;  // why the plots were not made (empty when they were or not asked)
  int matches = 0, differences = 0;  // the report's comparison bullets
};

// Throws mfadvr::Error before running anything for an unknown experiment name, a --volume or
// --mesh file that does not exist, an output folder that cannot be created, or (with
// options.vtk) no X display for VTK's renderers. An experiment that fails is reported in
// report.md and in the summary; the others still run. An input that exists but cannot be
// loaded is skipped by its gallery and listed in the summary's problems.
EvaluationSummary runPaperEvaluation(const EvalOptions& options, const std::string& commandLine);

}  // namespace mfadvr::eval
