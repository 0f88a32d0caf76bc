#pragma once
// One experiment of the paper's evaluation (docs/architecture.md, Evaluation protocol): it renders,
// measures, writes its CSV and images under the output folder, and returns its section of
// report.md.
#include <string>
#include <vector>

#include "eval/EvalContext.h"

namespace mfadvr::eval {

struct ExperimentReport {
  // Markdown body of the section: settings, tables, and the comparison with the paper, one
  // sentence per difference.
  std::string markdown;
  std::vector<std::string> files;  // written, relative to the output folder
  // Inputs that could not be used (a volume that does not load, say): the section says why
  // and goes on without them; the run reports them and exits non-zero.
  std::vector<std::string> problems;

  // Records an input that could not be loaded and adds the section's sentence saying so.
  void skipInput(const std::string& path, const std::string& why) {
    problems.push_back(path + ": " + why);
    markdown += "`" + path + "` could not be loaded, skipped: " + why + "\n\n";
  }
};

struct Experiment {
  std::string name;   // what --only selects
  std::string title;  // section heading
  std::string paper;  // the figures/tables of the paper it reproduces
  ExperimentReport (*run)(const EvalContext&);
};

// The experiments of `mfadvr eval paper`, in the order they run.
const std::vector<Experiment>& paperExperiments();

ExperimentReport runValueAccuracy(const EvalContext&);        // Fig. 4-6 (and 13's data)
ExperimentReport runMarschnerLobbTables(const EvalContext&);  // Tables 1 and 2, Fig. 7
ExperimentReport runStructuredGallery(const EvalContext&);    // Fig. 8
ExperimentReport runUnstructuredGallery(const EvalContext&);  // Fig. 9
ExperimentReport runParameterQuality(const EvalContext&);     // Fig. 10
ExperimentReport runQueryTiming(const EvalContext&);          // Fig. 12
ExperimentReport runRenderPerformance(const EvalContext&);    // Fig. 11
ExperimentReport runCompressionStudy(const EvalContext&);     // beyond the paper: compression
ExperimentReport runDenoiseStudy(const EvalContext&);         // beyond the paper: noise reduction
ExperimentReport runTimeStudy(const EvalContext&);            // beyond the paper: time series

}  // namespace mfadvr::eval

namespace mfadvr::eval {

// One bullet of a section's comparison with the paper: whether our result matches the paper's
// statement, and the sentence that says so or why it differs.
inline std::string paperBullet(bool matches, const std::string& sentence) {
  return std::string("- ") + (matches ? "**Matches.** " : "**Differs.** ") + sentence + "\n";
}

}  // namespace mfadvr::eval
