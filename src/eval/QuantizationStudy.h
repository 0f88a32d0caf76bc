#pragma once
// The quantization rows of `eval denoise` (docs/denoise.md): analytic fields quantized to 6, 8
// and 10 bits, reconstructed by local filters and by MFA models (interpolating, `--smooth auto`,
// `--dequantize`), measured against the clean truth.
#include "eval/EvalContext.h"
#include "eval/Experiment.h"

namespace mfadvr::eval {

// Runs the study, writes denoise_quantized.csv and the images under denoise/, and appends its
// tables and goals to `report`.
void appendQuantizationStudy(const EvalContext& ctx, ExperimentReport& report);

}  // namespace mfadvr::eval
