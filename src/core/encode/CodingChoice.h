#pragma once
// How a grid's model is stored: the control counts and the control-point coding (ControlCoding.h)
// chosen together, for a byte or error budget (`encode --bits-per-sample`, `--psnr`,
// `--rms-error`), for an error bound (`--max-error`), or by the defaults.
//
// Every choice is judged on the decoded model at every input sample: the errors a model states
// are those of the model a reader loads. ZFP's tolerance only matters by its power of two (ZFP
// keeps the bit planes down to 2^floor(log2 tolerance)), so tolerances are searched over powers of
// two, by bisection: the file shrinks and the error grows with the tolerance.
#include <optional>
#include <string>

#include "core/encode/FitReport.h"
#include "core/encode/StructuredEncoder.h"
#include "core/model/ControlCoding.h"

namespace mfadvr {

enum class BudgetKind { kNone, kBitsPerSample, kPsnr, kRmsError };

struct ModelBudget {
  BudgetKind kind = BudgetKind::kNone;
  // bits per input sample (the control-point section; the header, knots and checksum add a
  // small fixed overhead), PSNR in dB over the value range, or RMS error in data units.
  double value = 0.0;
};

struct CodingOptions {
  // Unset: zfp with a budget, float32 (the fitted model as it is) otherwise.
  std::optional<ControlCoder> coder;
  double tolerance = 0.0;  // zfp, absolute; 0: chosen by the budget, the bound or the default
  ModelBudget budget;
};

// Integer-valued samples by default: the largest zfp tolerance, from this one up to 32 times it,
// whose decoded model stays within kIntegerRoundingBound of every sample (so that rounding the
// model gives the samples back), then larger if needed to keep the model within the input's size.
inline constexpr double kIntegerDefaultTolerance = 0.25;
inline constexpr double kIntegerRoundingBound = 0.5;
// The zfp tolerance of float samples when --coding zfp is given without a tolerance or a bound,
// relative to the value range.
inline constexpr double kFloatDefaultRelativeTolerance = 1e-5;

// uint8, int16, ..., int64: types whose samples are integers.
bool isIntegerSampleType(const std::string& type);

// The coder the options resolve to: the given one, else zfp with a budget and float32 without.
// (`mfadvr encode` gives zfp for integer samples: EncodeCommand.)
ControlCoder resolvedCoder(const CodingOptions& options);

// Codes a fitted model of `grid` as `options` ask (no budget). maxError (absolute, 0: none) is a
// bound the decoded model must keep (adaptive --max-error): the zfp tolerance then takes the
// room the fit left. countsGiven: the user chose the control counts (the default model of an
// integer scan is then not held to the input's size). Fills the coding fields of `report` and
// its errors, measured on the decoded model.
Model codeFittedModel(Model fit, const StructuredGrid& grid, const CodingOptions& options,
                      double maxError, bool countsGiven, FitReport* report);

// Fits and codes candidate models (control counts from the samples down, or fit.controlCounts
// when countsGiven) and returns the one that meets options.budget best: the smallest file whose
// PSNR / RMS error meets the target, or the most accurate model within the bits per sample.
// Throws mfadvr::Error naming what can be reached when nothing meets the budget.
Model encodeToBudget(const StructuredGrid& grid, const StructuredFitOptions& fit,
                     const CodingOptions& options, bool countsGiven, FitReport* report);

}  // namespace mfadvr
