#pragma once
// What every experiment of `mfadvr eval` shares: the options, the output folder, progress on
// stderr, where the real data sets are, and whether VTK's renderers can run.
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "core/image/Image.h"

namespace mfadvr::eval {

struct EvalOptions {
  std::filesystem::path out;
  // The small configuration (smaller grids and images, fewer sizes): minutes on 2 cores.
  bool quick = false;
  std::vector<std::string> only;  // experiment names; empty: all
  // Extra inputs for the real-data galleries: structured volumes (Fig. 8) and meshes (Fig. 9).
  std::vector<std::string> volumes, meshes;
  std::filesystem::path dataDir;  // where the standard data sets are looked for
  int threads = 0;                // ray-casting threads; 0: all cores
  bool progress = true;
  bool plots = true;  // run the plot script (python3-matplotlib) after the experiments
  bool vtk = true;    // include VTK's renderers (they need an X display)
};

class EvalContext {
 public:
  explicit EvalContext(EvalOptions options);

  const EvalOptions& options() const { return options_; }
  bool quick() const { return options_.quick; }
  int threads() const { return options_.threads; }
  bool vtk() const { return options_.vtk; }

  // One progress line on stderr, prefixed with the elapsed wall time (unless quiet).
  void log(const std::string& line) const;
  double elapsedSeconds() const;

  // out/relative, with its parent folders created.
  std::filesystem::path path(const std::string& relative) const;
  // Writes `image` as a PNG at out/relative (atomically) and returns `relative`.
  std::string writeImage(const std::string& relative, const Image8& image) const;
  // A standard data set in the data folder; empty when it is not there.
  std::filesystem::path dataFile(const std::string& name) const;
  // The report's sentence naming the standard data sets that were not found (empty for none).
  std::string missingDataNote(const std::vector<std::string>& names) const;

 private:
  EvalOptions options_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mfadvr::eval
