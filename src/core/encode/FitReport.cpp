#include "core/encode/FitReport.h"

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
  r.inputBytes = p.inputBytes;
  r.modelBytes = modelFileSize(model);
  r.encoder = p.encoder;
  r.field = p.field;
  r.fieldAssociation = p.fieldAssociation;
  return r;
}

}  // namespace mfadvr
