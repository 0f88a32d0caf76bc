// mfadvr info MODEL [--json]
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/Commands.h"
#include "app/FitReportOutput.h"
#include "app/ModelInfoJson.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "core/model/ProvenanceJson.h"

namespace mfadvr::app {
namespace {
// Kind "none", dims 0 and inside fraction 1 for a model without a mask.
nlohmann::json maskJson(const DomainMask& mask) {
  if (mask.empty()) return {{"kind", "none"}, {"dims", {0, 0, 0}}, {"inside_fraction", 1.0}};
  return {{"kind", maskKindName(mask.kind())},
          {"dims", mask.dims()},
          {"inside_fraction", mask.insideFraction()}};
}

}  // namespace

nlohmann::json modelInfoJson(const Model& m, const std::string& path, std::uint32_t version) {
  const TensorBSpline& s = m.spline();
  nlohmann::json knots = nlohmann::json::array();
  for (int a = 0; a < 3; ++a)
    knots.push_back(s.knots(a).isUniform()            ? "uniform"
                    : s.knots(a).hasRegularInterior() ? "regular-interior"
                                                      : "non-uniform");
  nlohmann::json j = {
      {"degree", s.degrees()},
      {"control_counts", s.counts()},
      {"knots", knots},
      {"domain_min", {m.domain().min[0], m.domain().min[1], m.domain().min[2]}},
      {"domain_max", {m.domain().max[0], m.domain().max[1], m.domain().max[2]}},
      {"value_range", {m.valueMin(), m.valueMax()}},
      {"mask", maskJson(m.mask())},
      {"boundary", m.boundary() ? nlohmann::json{{"triangles", m.boundary()->triangles().size()},
                                                 {"vertices", m.boundary()->vertices().size()}}
                                : nlohmann::json(nullptr)},
      {"control_coding",
       {{"method", controlCoderName(m.controlCoding().coder)},
        {"tolerance", m.controlCoding().coder == ControlCoder::kZfp
                          ? nlohmann::json(m.controlCoding().tolerance)
                          : nlohmann::json(nullptr)}}},
      {"provenance", provenanceToJson(m.provenance())}};
  if (!path.empty()) {
    j["file"] = path;
    j["file_bytes"] = std::filesystem::file_size(path);
    j["format_version"] = version;
  }
  return j;
}

nlohmann::json timeAxisJson(const TimeVaryingModel& m) {
  if (!m.hasTime()) return nullptr;
  const TimeAxis& t = m.timeAxis();
  bool uniform = true;
  const double step = (t.end - t.begin) / static_cast<double>(t.steps.size() - 1);
  for (size_t i = 0; i < t.steps.size(); ++i)
    uniform = uniform && std::abs(t.steps[i] - (t.begin + step * static_cast<double>(i))) <=
                             1e-9 * std::abs(step) * t.steps.size();
  return {{"degree", t.degree()},
          {"control_count", t.controlCount()},
          {"range", {t.begin, t.end}},
          {"steps", t.steps},
          {"uniform_steps", uniform}};
}

nlohmann::json blockEntryJson(const Model& m, const DomainBox& region) {
  nlohmann::json b = modelInfoJson(m, "", 0);
  b["region"] = {region.min[0], region.max[0], region.min[1],
                 region.max[1], region.min[2], region.max[2]};
  return b;
}

nlohmann::json blockModelsInfoJson(const Index3& blocks, const DomainBox& box, double valueMin,
                                   double valueMax, nlohmann::json entries) {
  std::int64_t controlPoints = 0;
  for (const auto& e : entries) {
    const auto& c = e["control_counts"];
    controlPoints += c[0].get<std::int64_t>() * c[1].get<std::int64_t>() * c[2].get<std::int64_t>();
  }
  return {{"format", "mfadvr-blocks"},
          {"blocks", blocks},
          {"box", {box.min[0], box.max[0], box.min[1], box.max[1], box.min[2], box.max[2]}},
          {"value_range", {valueMin, valueMax}},
          {"control_points", controlPoints},
          {"entries", std::move(entries)}};
}

namespace {

// `info` of a multi-block file: the index, then each block's region and model (read one at a
// time).
int describeBlocks(const std::string& path, bool json) {
  const BlockIndex index = readBlockIndex(path);
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < index.entries.size(); ++i) {
    nlohmann::json b = blockEntryJson(loadBlock(path, index, i), index.entries[i].region);
    b["bytes"] = index.entries[i].bytes;
    list.push_back(std::move(b));
  }
  nlohmann::json j = {{"file", path}, {"file_bytes", std::filesystem::file_size(path)}};
  j.update(blockModelsInfoJson(index.blocks, index.box, index.valueMin, index.valueMax, list));
  j["format_version"] = kBlockFormatVersion;
  const std::int64_t controlPoints = j["control_points"];
  if (json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::ostringstream out;
  out << "file            " << path << "  (" << groupDigits(j["file_bytes"].get<std::int64_t>())
      << " bytes, multi-block format v" << kBlockFormatVersion << ")\n";
  out << "blocks          " << index.blocks[0] << " x " << index.blocks[1] << " x "
      << index.blocks[2] << "  (" << groupDigits(controlPoints) << " control points in all)\n";
  out << "box             [" << index.box.min.transpose() << "] .. [" << index.box.max.transpose()
      << "]\n";
  out << "value range     " << index.valueMin << " .. " << index.valueMax << "\n";
  for (size_t i = 0; i < list.size(); ++i) {
    const auto& b = list[i];
    const auto& r = index.entries[i].region;
    const auto& p = b["provenance"];
    out << "block " << i << "  region [" << r.min.transpose() << "] .. [" << r.max.transpose()
        << "], degree " << b["degree"][0] << " " << b["degree"][1] << " " << b["degree"][2] << ", "
        << b["control_counts"][0] << " x " << b["control_counts"][1] << " x "
        << b["control_counts"][2] << " control points, max error " << p["max_error"].get<double>()
        << "\n";
  }
  std::cout << out.str();
  return 0;
}

}  // namespace

Command addInfoCommand(CLI::App& app) {
  struct Options {
    std::string model;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("info", "Describe an .mfa model file");
  sub->add_option("model", o->model, "Model file (.mfa, one model or multi-block)")->required();
  sub->add_flag("--json", o->json, "Print as JSON");
  return {sub, [o]() {
            if (isBlockModelFile(o->model)) return describeBlocks(o->model, o->json);
            std::uint32_t version = 0;
            const TimeVaryingModel series = loadTimeVaryingModel(o->model, &version);
            const Model& m = series.first();
            nlohmann::json j = modelInfoJson(m, o->model, version);
            if (series.hasTime()) {
              // The coding of every slab, as the file stores it.
              const ControlCoding& c = series.controlCoding();
              j["control_coding"] = {
                  {"method", controlCoderName(c.coder)},
                  {"tolerance", c.coder == ControlCoder::kZfp ? nlohmann::json(c.tolerance)
                                                              : nlohmann::json(nullptr)}};
            }
            j["time"] = timeAxisJson(series);
            if (o->json) {
              std::cout << j.dump(2) << "\n";
              return 0;
            }
            const auto& p = m.provenance();
            const double range = m.valueMax() - m.valueMin();
            std::ostringstream out;
            out << "file            " << o->model << "  ("
                << groupDigits(j["file_bytes"].get<std::int64_t>()) << " bytes, format v" << version
                << ")\n";
            out << "control coding  " << j["control_coding"]["method"].get<std::string>();
            if (!j["control_coding"]["tolerance"].is_null())
              out << ", tolerance " << j["control_coding"]["tolerance"].get<double>();
            out << "\n";
            out << "degree          " << j["degree"][0] << " " << j["degree"][1] << " "
                << j["degree"][2] << "\n";
            out << "control points  " << j["control_counts"][0] << " x " << j["control_counts"][1]
                << " x " << j["control_counts"][2] << "\n";
            if (series.hasTime()) {
              const TimeAxis& t = series.timeAxis();
              out << "time            " << t.steps.size() << " steps, t = " << t.begin << " .. "
                  << t.end << "; degree " << t.degree() << ", " << t.controlCount()
                  << " control points in time"
                  << (j["time"]["uniform_steps"].get<bool>() ? "" : " (uneven steps)") << "\n";
            }
            out << "knots           " << j["knots"][0].get<std::string>() << ", "
                << j["knots"][1].get<std::string>() << ", " << j["knots"][2].get<std::string>()
                << "\n";
            out << "domain          [" << m.domain().min.transpose() << "] .. ["
                << m.domain().max.transpose() << "]\n";
            out << "value range     " << m.valueMin() << " .. " << m.valueMax() << "\n";
            if (m.mask().empty()) {
              out << "mask            none\n";
            } else {
              const Index3& d = m.mask().dims();
              std::ostringstream percent;
              percent.precision(3);
              percent << 100.0 * m.mask().insideFraction();
              out << "mask            " << maskKindName(m.mask().kind()) << ", " << d[0] << " x "
                  << d[1] << " x " << d[2] << " nodes, " << percent.str() << "% inside\n";
            }
            if (const DomainBoundary* b = m.boundary())
              out << "boundary        " << b->triangles().size() << " triangles, "
                  << b->vertices().size() << " vertices (exact; rays and queries use it)\n";
            out << "source          " << p.source << (p.field.empty() ? "" : "  field " + p.field)
                << "\n";
            if (p.inputPoints > 0)
              out << "samples         " << groupDigits(p.inputPoints) << " scattered points  "
                  << p.sampleType
                  << (p.fieldAssociation.empty() ? "" : "  (" + p.fieldAssociation + ")") << "\n";
            else
              out << "samples         " << p.sampleDims[0] << " x " << p.sampleDims[1] << " x "
                  << p.sampleDims[2] << "  " << p.sampleType
                  << (series.hasTime()
                          ? ", " + std::to_string(series.timeAxis().steps.size()) + " steps"
                          : std::string())
                  << "\n";
            out << "encoder         " << p.encoder << ", " << p.fitSeconds << " s, " << p.created
                << ", mfadvr " << p.toolVersion << "\n";
            if (p.smoothing > 0.0) out << "smoothing       lambda " << p.smoothing << "\n";
            out << "max error       " << p.maxError << "  ("
                << (range > 0 ? p.maxError / range : p.maxError) << " of the range)\n";
            out << "rms error       " << p.rmsError << "  ("
                << (range > 0 ? p.rmsError / range : p.rmsError) << " of the range)\n";
            std::cout << out.str();
            return 0;
          }};
}

}  // namespace mfadvr::app
