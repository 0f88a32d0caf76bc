// mfadvr info MODEL [--json]
#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/Commands.h"
#include "app/FitReportOutput.h"
#include "core/model/ModelFile.h"
#include "core/model/ProvenanceJson.h"

namespace mfadvr::app {
namespace {

nlohmann::json infoJson(const Model& m, const std::string& path) {
  const TensorBSpline& s = m.spline();
  nlohmann::json knots = nlohmann::json::array();
  for (int a = 0; a < 3; ++a)
    knots.push_back(s.knots(a).isUniform()            ? "uniform"
                    : s.knots(a).hasRegularInterior() ? "regular-interior"
                                                      : "non-uniform");
  return {{"file", path},
          {"file_bytes", std::filesystem::file_size(path)},
          {"format_version", kModelFormatVersion},
          {"degree", s.degrees()},
          {"control_counts", s.counts()},
          {"knots", knots},
          {"domain_min", {m.domain().min[0], m.domain().min[1], m.domain().min[2]}},
          {"domain_max", {m.domain().max[0], m.domain().max[1], m.domain().max[2]}},
          {"value_range", {m.valueMin(), m.valueMax()}},
          {"provenance", provenanceToJson(m.provenance())}};
}

}  // namespace

Command addInfoCommand(CLI::App& app) {
  struct Options {
    std::string model;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("info", "Describe an .mfa model file");
  sub->add_option("model", o->model, "Model file (.mfa)")->required();
  sub->add_flag("--json", o->json, "Print as JSON");
  return {sub, [o]() {
            const Model m = loadModel(o->model);
            const nlohmann::json j = infoJson(m, o->model);
            if (o->json) {
              std::cout << j.dump(2) << "\n";
              return 0;
            }
            const auto& p = m.provenance();
            const double range = m.valueMax() - m.valueMin();
            std::ostringstream out;
            out << "file            " << o->model << "  ("
                << groupDigits(j["file_bytes"].get<std::int64_t>()) << " bytes, format v"
                << kModelFormatVersion << ")\n";
            out << "degree          " << j["degree"][0] << " " << j["degree"][1] << " "
                << j["degree"][2] << "\n";
            out << "control points  " << j["control_counts"][0] << " x " << j["control_counts"][1]
                << " x " << j["control_counts"][2] << "\n";
            out << "knots           " << j["knots"][0].get<std::string>() << ", "
                << j["knots"][1].get<std::string>() << ", " << j["knots"][2].get<std::string>()
                << "\n";
            out << "domain          [" << m.domain().min.transpose() << "] .. ["
                << m.domain().max.transpose() << "]\n";
            out << "value range     " << m.valueMin() << " .. " << m.valueMax() << "\n";
            out << "source          " << p.source << (p.field.empty() ? "" : "  field " + p.field)
                << "\n";
            out << "samples         " << p.sampleDims[0] << " x " << p.sampleDims[1] << " x "
                << p.sampleDims[2] << "  " << p.sampleType << "\n";
            out << "encoder         " << p.encoder << ", " << p.fitSeconds << " s, " << p.created
                << ", mfadvr " << p.toolVersion << "\n";
            out << "max error       " << p.maxError << "  ("
                << (range > 0 ? p.maxError / range : p.maxError) << " of the range)\n";
            out << "rms error       " << p.rmsError << "  ("
                << (range > 0 ? p.rmsError / range : p.rmsError) << " of the range)\n";
            std::cout << out.str();
            return 0;
          }};
}

}  // namespace mfadvr::app
