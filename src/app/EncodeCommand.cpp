// mfadvr encode INPUT [-o MODEL.mfa] [--degree ...] [--ctrl ...]
#include <iostream>

#include "app/Commands.h"
#include "app/FitReportOutput.h"
#include "app/OptionParsing.h"
#include "core/encode/StructuredEncoder.h"
#include "core/model/ModelFile.h"
#include "io/VolumeLoader.h"

namespace mfadvr::app {

Command addEncodeCommand(CLI::App& app) {
  struct Options {
    std::string input, output, degree = "3", ctrl, spacing, origin, field;
    bool json = false, quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "encode", "Fit an MFA model (tensor-product B-spline) to a volume and report the fit");
  sub->add_option("input", o->input,
                  "Volume file or built-in function: builtin:NAME[:N|:NXxNYxNZ]\n" +
                      supportedVolumeFormats())
      ->required();
  sub->add_option("-o,--output", o->output,
                  "Model file to write (.mfa); without it only the report is printed");
  sub->add_option("--degree", o->degree, "Polynomial degree P or PX,PY,PZ (1..7)")
      ->capture_default_str();
  sub->add_option("--ctrl", o->ctrl,
                  "Control points N or NX,NY,NZ per axis (default: as many as samples, which "
                  "interpolates; fewer gives a smoothing least-squares fit)");
  sub->add_option("--spacing", o->spacing, "Sample spacing S or SX,SY,SZ (overrides the file's)");
  sub->add_option("--origin", o->origin,
                  "Position of the first sample X,Y,Z (overrides the file's)");
  sub->add_option("--field", o->field, "Scalar array to encode (default: the active/first one)");
  sub->add_flag("--json", o->json, "Print the report as JSON");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  auto run = [o]() -> int {
    StructuredFitOptions fit = parseFitOptions(o->degree, o->ctrl);
    const VolumeLoadOptions load = parseVolumeLoadOptions(o->spacing, o->origin, o->field);

    const bool progress = wantProgress(o->quiet || o->json);
    if (progress) std::cerr << "reading " << o->input << "\n";
    const StructuredGrid grid = loadStructuredVolume(o->input, load);
    if (progress) {
      fit.progress = [](double f, const std::string& stage) {
        printProgress("encoding", f, stage);
      };
    }
    FitReport report;
    const Model model = encodeStructured(grid, fit, &report);
    if (!o->output.empty()) saveModel(model, o->output);
    if (o->json)
      std::cout << fitReportJson(report, o->output).dump(2) << "\n";
    else
      std::cout << formatFitReport(report, o->output);
    return 0;
  };
  return {sub, run};
}

}  // namespace mfadvr::app
