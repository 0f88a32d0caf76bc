#include "eval/PaperEvaluation.h"

#include <sys/wait.h>
#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/util/AtomicFile.h"
#include "core/util/Error.h"
#include "core/util/UtcTime.h"
#include "eval/EvalPlotScript.h"
#include "eval/Experiment.h"
#include "eval/SystemInfo.h"
#include "vtkrender/DisplayCheck.h"

namespace mfadvr::eval {

const std::vector<Experiment>& paperExperiments() {
  static const std::vector<Experiment> experiments = {
      {"value", "Value accuracy: Gaussian beams at four zoom levels", "Fig. 4, 5, 6, 13",
       runValueAccuracy},
      {"tables", "Gradient and overall accuracy: Marschner-Lobb", "Tables 1 and 2, Fig. 7",
       runMarschnerLobbTables},
      {"structured", "Real structured data", "Fig. 8", runStructuredGallery},
      {"unstructured", "Real unstructured data", "Fig. 9", runUnstructuredGallery},
      {"params", "MFA parameters vs rendering quality", "Fig. 10", runParameterQuality},
      {"query", "MFA parameters vs query time", "Fig. 12", runQueryTiming},
      {"performance", "Render time vs data size", "Fig. 11", runRenderPerformance},
      {"compression", "Compact models: rate-distortion against ZFP and downsampling",
       "future work: compression", runCompressionStudy},
      {"denoise", "Noise reduction: smoothing fits of noisy and quantized samples",
       "future work: noise reduction", runDenoiseStudy},
      {"time", "Time series: one 4-D model against interpolating the steps in time",
       "beyond the paper: time-varying data", runTimeStudy},
  };
  return experiments;
}

std::vector<std::string> experimentNames() {
  std::vector<std::string> names;
  for (const auto& e : paperExperiments()) names.push_back(e.name);
  return names;
}

namespace {

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : separator) + s;
  return out;
}

std::string shellQuoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Debian's matplotlib belongs to /usr/bin/python3 (a python3 earlier on PATH may lack it);
// MFADVR_PYTHON overrides.
std::string pythonInterpreter() {
  if (const char* p = std::getenv("MFADVR_PYTHON"); p && *p) return p;
  std::error_code ec;
  return std::filesystem::exists("/usr/bin/python3", ec) ? "/usr/bin/python3" : "python3";
}

// Writes plots.py into the output folder and runs it; returns why it failed (empty on success).
std::string makePlots(const EvalContext& ctx) {
  const auto script = ctx.path("plots.py");
  writeFileAtomically(script, kEvalPlotScript);
  ctx.log("plots: " + pythonInterpreter() + " " + script.string());
  std::string command = shellQuoted(pythonInterpreter()) + " " + shellQuoted(script.string()) +
                        " " + shellQuoted(ctx.options().out.string());
  if (!ctx.options().progress) command += " > /dev/null";
  const int status = std::system(command.c_str());
  if (status == 0) return {};
  if (status == -1) return "could not start " + pythonInterpreter();
  if (WIFEXITED(status))
    return "the plot script exited with status " + std::to_string(WEXITSTATUS(status)) +
           " (its message is above)";
  return "the plot script was stopped by a signal";
}

int countOf(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string minutes(double seconds) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%d min %02d s", static_cast<int>(seconds) / 60,
                static_cast<int>(seconds) % 60);
  return buf;
}

// The figures of the plot script that belong to an experiment.
std::vector<std::string> figuresOf(const std::string& experiment) {
  if (experiment == "value")
    return {"fig04_value_images", "fig05_value_accuracy", "fig06_error_images",
            "fig13_quality_vs_time"};
  if (experiment == "tables") return {"fig07_marschner_lobb", "tables_psnr"};
  if (experiment == "structured") return {"fig08_structured"};
  if (experiment == "unstructured") return {"fig09_unstructured"};
  if (experiment == "params") return {"fig10_param_quality"};
  if (experiment == "query") return {"fig12_query_time"};
  if (experiment == "performance") return {"fig11_render_time"};
  return {};
}

}  // namespace

EvaluationSummary runPaperEvaluation(const EvalOptions& options, const std::string& commandLine) {
  const auto names = experimentNames();
  for (const auto& n : options.only)
    if (std::find(names.begin(), names.end(), n) == names.end())
      throw Error("unknown experiment '" + n + "' (known: " + joined(names, ", ") + ")");
  if (options.out.empty()) throw Error("no output folder");
  for (const auto& list : {options.volumes, options.meshes})
    for (const auto& f : list) {
      std::error_code fileError;
      if (!std::filesystem::is_regular_file(f, fileError))
        throw Error("input file not found (or not a file): " + f);
    }
  if (options.vtk) {
    try {
      requireRenderDisplay();
    } catch (const Error& e) {
      throw Error(std::string(e.what()) + "; or leave VTK's renderers out with --no-vtk");
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(options.out, ec);
  if (ec)
    throw Error("cannot create the output folder " + options.out.string() + ": " + ec.message());

  const EvalContext ctx(options);
  const std::string started = utcNow();
  EvaluationSummary summary;
  struct Section {
    const Experiment* experiment;
    ExperimentReport report;
    double seconds;
    std::string error;
  };
  std::vector<Section> sections;
  for (const auto& e : paperExperiments()) {
    if (!options.only.empty() &&
        std::find(options.only.begin(), options.only.end(), e.name) == options.only.end())
      continue;
    ctx.log("== " + e.name + ": " + e.title + " (paper " + e.paper + ")");
    const double t0 = ctx.elapsedSeconds();
    Section s{&e, {}, 0.0, {}};
    try {
      s.report = e.run(ctx);
      for (const auto& p : s.report.problems) {
        summary.problems.push_back(e.name + ": " + p);
        ctx.log("problem in " + e.name + ": " + p);
      }
    } catch (const std::exception& ex) {
      s.error = ex.what();
      summary.failed.push_back(e.name);
      ctx.log("error in " + e.name + ": " + s.error);
    }
    s.seconds = ctx.elapsedSeconds() - t0;
    sections.push_back(std::move(s));
  }
  if (options.plots) summary.plotError = makePlots(ctx);

  // report.md
  std::string md = "# mfadvr evaluation: the paper's results section, reproduced\n\n";
  md += "Generated by `" + commandLine + "`, started " + started + ", wall time " +
        minutes(ctx.elapsedSeconds()) + " (" + (options.quick ? "quick" : "full") +
        " configuration). The protocol is docs/architecture.md, Evaluation protocol; every method "
        "of ours renders "
        "through the same ray caster with the same rays and samples; VTK's renderers run through "
        "VTK 9.1 with the same camera, transfer function and sample distance. Each section ends "
        "with its comparison with the paper: **Matches** where our result agrees with the paper's "
        "number or statement, **Differs** with the reason where it does not.\n\n";
  md += "## Machine and software\n\n| | |\n|---|---|\n";
  for (const auto& [k, v] : systemDescription()) md += "| " + k + " | " + v + " |\n";
  md += "| threads (ray caster) | " +
        (options.threads ? std::to_string(options.threads) : std::string("all")) + " |\n";
  md += "| data folder | " + options.dataDir.string() + " |\n\n";
  md +=
      "## Summary\n\n| experiment | paper | wall time | matches | differs "
      "|\n|---|---|---|---|---|\n";
  for (const auto& s : sections) {
    const int m = countOf(s.report.markdown, "**Matches.**");
    const int d = countOf(s.report.markdown, "**Differs.**");
    summary.matches += m;
    summary.differences += d;
    md += "| " + s.experiment->name + " | " + s.experiment->paper + " | " + minutes(s.seconds) +
          " | " + (s.error.empty() ? std::to_string(m) : "failed") + " | " +
          (s.error.empty() ? std::to_string(d) : "-") + " |\n";
  }
  md += "\n";
  if (!summary.problems.empty()) {
    md += "Inputs skipped because they could not be used (each section says more):\n\n";
    for (const auto& p : summary.problems) md += "- " + p + "\n";
    md += "\n";
  }
  if (!summary.plotError.empty())
    md += "Plots were not made: " + summary.plotError +
          ". The CSVs hold every number; `python3 plots.py .` in this folder makes them once "
          "python3-matplotlib is installed.\n\n";
  int index = 0;
  for (const auto& s : sections) {
    md += "## " + std::to_string(++index) + ". " + s.experiment->title + " (paper " +
          s.experiment->paper + ")\n\n";
    md += "Wall time " + minutes(s.seconds) + ".\n\n";
    if (!s.error.empty()) {
      md += "**Failed:** " + s.error + "\n\n";
      continue;
    }
    md += s.report.markdown + "\n";
    for (const auto& f : figuresOf(s.experiment->name)) {
      const std::string rel = "plots/" + f + ".png";
      if (std::filesystem::exists(options.out / rel, ec)) md += "![" + f + "](" + rel + ")\n\n";
    }
    if (!s.report.files.empty())
      md += "Files: " +
            joined(
                [&] {
                  std::vector<std::string> q;
                  for (const auto& f : s.report.files) q.push_back("`" + f + "`");
                  return q;
                }(),
                ", ") +
            ".\n\n";
  }
  summary.report = (options.out / "report.md").string();
  writeFileAtomically(summary.report, md);
  summary.seconds = ctx.elapsedSeconds();
  return summary;
}

}  // namespace mfadvr::eval
