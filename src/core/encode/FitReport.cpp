#include "core/encode/FitReport.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/model/ModelFile.h"

namespace mfadvr {

FitReport fitReportOf(const Model& model) {
  const Provenance& p = model.provenance();
  FitReport r;
  r.source = p.source;
  r.samples = p.sampleDims;
  r.points = p.inputPoints;
  r.degree = model.spline().degrees();
  r.controlCounts = model.spline().counts();
  r.seconds = p.fitSeconds;
  r.valueMin = model.valueMin();
  r.valueMax = model.valueMax();
  r.maxError = p.maxError;
  r.rmsError = p.rmsError;
  r.smoothing = p.smoothing;
  r.inputBytes = p.inputBytes;
  r.modelBytes = modelFileSize(model);
  r.encoder = p.encoder;
  r.field = p.field;
  r.fieldAssociation = p.fieldAssociation;
  r.coding = controlCoderName(model.controlCoding().coder);
  r.codingTolerance = model.controlCoding().tolerance;
  return r;
}

double psnrOf(double range, double rms) {
  if (rms <= 0.0) return std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(range / rms);
}

double FitReport::psnr() const {
  return psnrOf(valueRange(), rmsError);
}

double FitReport::bitsPerSample() const {
  const std::int64_t n = (points > 0 ? points : samples[0] * samples[1] * samples[2]) *
                         std::max<std::int64_t>(timeSteps, 1);
  return n > 0 ? 8.0 * static_cast<double>(modelBytes) / static_cast<double>(n) : 0.0;
}

}  // namespace mfadvr
