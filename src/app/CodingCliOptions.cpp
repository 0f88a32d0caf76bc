#include "app/CodingCliOptions.h"

#include "app/OptionParsing.h"
#include "core/util/Error.h"

namespace mfadvr::app {

void CodingCliOptions::addTo(CLI::App* sub, const std::string& group) {
  sub->add_option("--coding", coding,
                  "How the file stores the control points: float32 (as in memory), lossless "
                  "(byte-shuffled float32 + zstd, bit for bit) or zfp (ZFP fixed accuracy: each "
                  "control point, hence the model, moves by at most the tolerance). Default: zfp "
                  "for integer samples (8/16-bit scans) and with a budget, float32 otherwise")
      ->group(group);
  sub->add_option("--coding-tolerance", tolerance,
                  "zfp: the largest change of a control point, in data units (used as the power "
                  "of two at or below it). Default: 0.25 for integer samples, raised if needed "
                  "to keep the model within the input's size; 1e-5 of the value range for "
                  "floats; with --max-error, the room the fit leaves under the bound")
      ->group(group);
  sub->add_flag("--lossless", lossless, "The same as --coding lossless")->group(group);
  sub->add_option("--bits-per-sample", bitsPerSample,
                  "Budget: the most accurate model whose control points take at most B bits "
                  "per input sample (the header and knots add a few hundred bytes); the encoder "
                  "chooses control counts and zfp tolerance and reports its candidates")
      ->group(group);
  sub->add_option("--psnr", psnr,
                  "Budget: the smallest model whose PSNR over the value range, measured at "
                  "every input sample on the decoded model, is at least D dB")
      ->group(group);
  sub->add_option("--rms-error", rmsError,
                  "Budget: the smallest model whose RMS error at the input samples is at most E "
                  "(data units)")
      ->group(group);
}

CodingOptions CodingCliOptions::parse() const {
  CodingOptions o;
  if (lossless && !coding.empty() && coding != "lossless")
    throw CLI::ValidationError("--lossless", "contradicts --coding " + coding);
  if (lossless) o.coder = ControlCoder::kLossless;
  if (!coding.empty()) {
    try {
      o.coder = parseControlCoder(coding);
    } catch (const Error& e) {
      throw CLI::ValidationError("--coding", e.what());
    }
  }
  auto positive = [](const char* option, const std::string& text) {
    const double v = parseNumberList(option, text, 1, 1)[0];
    if (!(v > 0.0)) throw CLI::ValidationError(option, "must be > 0, got '" + text + "'");
    return v;
  };
  if (!tolerance.empty()) {
    if (o.coder && *o.coder != ControlCoder::kZfp)
      throw CLI::ValidationError("--coding-tolerance", "applies to --coding zfp");
    o.coder = ControlCoder::kZfp;
    o.tolerance = positive("--coding-tolerance", tolerance);
  }
  int budgets = 0;
  if (!bitsPerSample.empty()) {
    o.budget = {BudgetKind::kBitsPerSample, positive("--bits-per-sample", bitsPerSample)};
    ++budgets;
  }
  if (!psnr.empty()) {
    o.budget = {BudgetKind::kPsnr, positive("--psnr", psnr)};
    ++budgets;
  }
  if (!rmsError.empty()) {
    o.budget = {BudgetKind::kRmsError, positive("--rms-error", rmsError)};
    ++budgets;
  }
  if (budgets > 1)
    throw CLI::ValidationError("--bits-per-sample/--psnr/--rms-error", "give one budget");
  if (budgets == 1 && o.tolerance > 0.0)
    throw CLI::ValidationError("--coding-tolerance",
                               "a budget chooses the tolerance; give one or the other");
  return o;
}

void CodingCliOptions::applyGridDefault(CodingOptions& options, const std::string& sampleType) {
  if (!options.coder && isIntegerSampleType(sampleType)) options.coder = ControlCoder::kZfp;
}

}  // namespace mfadvr::app
