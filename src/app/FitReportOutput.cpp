#include "app/FitReportOutput.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace mfadvr::app {

std::string groupDigits(std::int64_t v) {
  std::string digits = std::to_string(v < 0 ? -v : v), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return v < 0 ? "-" + out : out;
}

namespace {
std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
}  // namespace

std::string formatFitReport(const FitReport& r, const std::string& modelPath) {
  std::ostringstream o;
  o << "source          " << r.source << "\n";
  if (r.points > 0)
    o << "input           " << (r.inputKind.empty() ? "points" : r.inputKind) << ", "
      << groupDigits(r.points) << " points  (" << groupDigits(r.inputBytes) << " bytes)"
      << (r.cellSamples > 0 ? "; fitted with " + groupDigits(r.cellSamples) +
                                  " samples inside the cells (errors at both)"
                            : std::string())
      << "\n";
  if (!r.field.empty())
    o << "field           " << r.field
      << (r.fieldAssociation.empty() ? "" : "  (" + r.fieldAssociation + ")") << "\n";
  else
    o << "samples         " << r.samples[0] << " x " << r.samples[1] << " x " << r.samples[2]
      << "  (" << groupDigits(r.inputBytes) << " bytes)\n";
  o << "value range     " << fmt("%.6g", r.valueMin) << " .. " << fmt("%.6g", r.valueMax) << "\n";
  if (r.timeSteps > 0)
    o << "time steps      " << r.timeSteps << "  (one 4-D model: degree " << r.timeDegree << " and "
      << r.timeControlCount << " control points in time)\n";
  o << "degree          " << r.degree[0] << " " << r.degree[1] << " " << r.degree[2] << "\n";
  o << "control points  " << r.controlCounts[0] << " x " << r.controlCounts[1] << " x "
    << r.controlCounts[2] << "\n";
  if (r.points > 0)
    o << "smoothing       " << fmt("%g", r.smoothing) << "  (solver: " << r.solverIterations
      << " CG iterations, residual " << fmt("%.2e", r.solverResidual) << ")"
      << (r.smoothingNote.empty() ? "" : "\n                " + r.smoothingNote) << "\n";
  else if (r.smoothing > 0.0 || !r.smoothingNote.empty())
    o << "smoothing       "
      << (r.smoothingNote.empty() ? "lambda " + fmt("%g", r.smoothing) : r.smoothingNote) << "\n";
  if (r.dequantizeStep > 0.0)
    o << "dequantize      step " << fmt("%g", r.dequantizeStep) << ", roughness of lambda "
      << fmt("%g", r.dequantizeLambda) << ": " << r.dequantizeIterations << " iterations"
      << (r.dequantizeConverged ? "" : " (NOT converged)") << ", "
      << fmt("%.1f", 100.0 * r.dequantizeEdgeShare) << " % of the samples on an "
      << "interval's edge, " << fmt("%.2f", r.dequantizeSeconds) << " s; max |model - sample| "
      << fmt("%.3g", r.maxError) << (r.maxError <= 0.5 * r.dequantizeStep ? " <= " : " > ")
      << "step/2\n";
  if (r.rounds > 0)
    o << "adaptive        bound " << fmt("%.3e", r.targetRelativeError)
      << " of the value range: " << (r.reachedTarget ? "reached" : "NOT reached") << " after "
      << r.rounds << " round" << (r.rounds == 1 ? "" : "s")
      << (r.reachedTarget ? "" : " (" + r.stopReason + ")") << "\n";
  o << "fit time        " << fmt("%.3f", r.seconds) << " s\n";
  o << "max error       " << fmt("%.4g", r.maxError) << "  (" << fmt("%.3e", r.maxRelativeError())
    << " of the value range)\n";
  o << "rms error       " << fmt("%.4g", r.rmsError) << "  (" << fmt("%.3e", r.rmsRelativeError())
    << " of the value range)\n";
  if (!r.maskKind.empty())
    o << "domain mask     " << r.maskKind << ", " << r.maskDims[0] << " x " << r.maskDims[1]
      << " x " << r.maskDims[2] << " nodes, " << fmt("%.1f", 100.0 * r.maskInsideFraction)
      << "% inside\n";
  if (r.boundaryTriangles > 0)
    o << "boundary        " << r.boundaryTriangles << " triangles, " << r.boundaryVertices
      << " vertices (exact; extracted in " << fmt("%.2f", r.boundarySeconds) << " s)\n";
  o << "psnr            "
    << (std::isfinite(r.psnr()) ? fmt("%.2f", r.psnr()) + " dB" : std::string("exact"))
    << "  (value range over the rms error)\n";
  o << "coding          " << r.coding;
  if (r.coding == "zfp") o << ", tolerance " << fmt("%.4g", r.codingTolerance);
  o << "\n";
  if (!r.codingNote.empty()) {
    // The note may span lines (a budget's candidates); indent them under the label.
    std::string note = r.codingNote;
    while (!note.empty() && note.back() == '\n') note.pop_back();
    size_t at = 0;
    while ((at = note.find('\n', at)) != std::string::npos) {
      note.replace(at, 1, "\n                ");
      at += 17;
    }
    o << "                " << note << "\n";
  }
  o << "model size      " << groupDigits(r.modelBytes) << " bytes, "
    << fmt("%.3f", r.bitsPerSample()) << " bits/sample"
    << (modelPath.empty() ? std::string("  (not written: no -o)") : "  -> " + modelPath) << "\n";
  o << "compression     " << fmt("%.2f", r.compressionRatio())
    << (r.points > 0 ? " : 1  (bytes of the input values / model bytes; coordinates and cells "
                       "not counted)\n"
                     : " : 1  (input bytes / model bytes)\n");
  if (r.peakMemoryBytes > 0) {
    const std::int64_t samples =
        r.samples[0] * r.samples[1] * r.samples[2] * std::max<std::int64_t>(r.timeSteps, 1);
    const double perSample = static_cast<double>(r.peakMemoryBytes) /
                             static_cast<double>(std::max<std::int64_t>(samples, 1));
    o << "peak memory     " << groupDigits(r.peakMemoryBytes) << " bytes"
      << (r.points == 0 && samples > 0 ? ", " + bytesPerSampleText(perSample) + " bytes/sample"
                                       : "")
      << "  (the whole process, reading and writing included)\n";
  }
  return o.str();
}

nlohmann::json fitReportJson(const FitReport& r, const std::string& modelPath) {
  nlohmann::json j = {
      {"source", r.source},
      {"encoder", r.encoder},
      {"points", r.points},
      {"cell_samples", r.cellSamples},
      {"input_kind", r.inputKind},
      {"field", r.field},
      {"field_association", r.fieldAssociation},
      {"samples", r.samples},
      {"value_min", r.valueMin},
      {"value_max", r.valueMax},
      {"degree", r.degree},
      {"control_counts", r.controlCounts},
      {"fit_seconds", r.seconds},
      {"max_error", r.maxError},
      {"rms_error", r.rmsError},
      {"max_relative_error", r.maxRelativeError()},
      {"rms_relative_error", r.rmsRelativeError()},
      {"input_bytes", r.inputBytes},
      {"model_bytes", r.modelBytes},
      {"peak_memory_bytes",
       r.peakMemoryBytes > 0 ? nlohmann::json(r.peakMemoryBytes) : nlohmann::json(nullptr)},
      {"compression_ratio", r.compressionRatio()},
      {"bits_per_sample", r.bitsPerSample()},
      {"psnr", std::isfinite(r.psnr()) ? nlohmann::json(r.psnr()) : nlohmann::json(nullptr)},
      {"coding",
       {{"method", r.coding},
        {"tolerance",
         r.coding == "zfp" ? nlohmann::json(r.codingTolerance) : nlohmann::json(nullptr)},
        {"note", r.codingNote}}},
      {"model", modelPath.empty() ? nlohmann::json(nullptr) : nlohmann::json(modelPath)}};
  j["solver"] = r.points > 0 ? nlohmann::json{{"smoothing", r.smoothing},
                                              {"iterations", r.solverIterations},
                                              {"residual", r.solverResidual}}
                             : nlohmann::json(nullptr);
  j["smoothing"] = {
      {"lambda", r.smoothing},
      {"automatic", !r.smoothingNote.empty()},
      {"noise_estimate", r.smoothingNote.empty() || r.points > 0 ? nlohmann::json(nullptr)
                                                                 : nlohmann::json(r.noiseEstimate)},
      {"note", r.smoothingNote}};
  j["dequantize"] = r.dequantizeStep > 0.0
                        ? nlohmann::json{{"step", r.dequantizeStep},
                                         {"lambda", r.dequantizeLambda},
                                         {"iterations", r.dequantizeIterations},
                                         {"converged", r.dequantizeConverged},
                                         {"edge_share", r.dequantizeEdgeShare},
                                         {"seconds", r.dequantizeSeconds},
                                         {"rounds_back", r.maxError <= 0.5 * r.dequantizeStep}}
                        : nlohmann::json(nullptr);
  j["adaptive"] = r.rounds > 0 ? nlohmann::json{{"max_relative_error_bound", r.targetRelativeError},
                                                {"rounds", r.rounds},
                                                {"reached", r.reachedTarget},
                                                {"stop_reason", r.stopReason}}
                               : nlohmann::json(nullptr);
  j["mask"] = r.maskKind.empty() ? nlohmann::json(nullptr)
                                 : nlohmann::json{{"kind", r.maskKind},
                                                  {"dims", r.maskDims},
                                                  {"inside_fraction", r.maskInsideFraction}};
  j["boundary"] = r.boundaryTriangles > 0 ? nlohmann::json{{"triangles", r.boundaryTriangles},
                                                           {"vertices", r.boundaryVertices},
                                                           {"seconds", r.boundarySeconds}}
                                          : nlohmann::json(nullptr);
  j["time"] = r.timeSteps > 0 ? nlohmann::json{{"steps", r.timeSteps},
                                               {"degree", r.timeDegree},
                                               {"control_count", r.timeControlCount}}
                              : nlohmann::json(nullptr);
  return j;
}

std::string bytesPerSampleText(double v) {
  return fmt(v >= 10.0 ? "%.0f" : v >= 1.0 ? "%.1f" : "%.2g", v);
}

}  // namespace mfadvr::app
