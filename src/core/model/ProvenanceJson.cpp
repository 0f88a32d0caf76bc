#include "core/model/ProvenanceJson.h"

namespace mfadvr {

nlohmann::json provenanceToJson(const Provenance& p) {
  nlohmann::json j = {{"source", p.source},
                      {"field", p.field},
                      {"sample_type", p.sampleType},
                      {"sample_dims", p.sampleDims},
                      {"input_points", p.inputPoints},
                      {"field_association", p.fieldAssociation},
                      {"input_bytes", p.inputBytes},
                      {"encoder", p.encoder},
                      {"created", p.created},
                      {"tool_version", p.toolVersion},
                      {"fit_seconds", p.fitSeconds},
                      {"max_error", p.maxError},
                      {"rms_error", p.rmsError}};
  if (p.smoothing > 0.0) j["smoothing"] = p.smoothing;
  return j;
}

}  // namespace mfadvr
