#include "core/encode/CodingChoice.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "core/encode/ToleranceSearch.h"
#include "core/model/ModelFile.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// A coded model and what it costs and loses, measured.
struct Coded {
  Model model;
  SampleErrors errors;
  std::int64_t controlBytes = 0;
  int exponent = 0;  // zfp tolerance 2^exponent
};

// What coding with one tolerance gives, measured on the decoded model.
struct Measured {
  SampleErrors errors;
  std::int64_t controlBytes = 0;
};

// Codes a zfp-coded fit at the tolerances a search asks for. Each tolerance is coded once for
// its size, and its decoded model is measured at every sample only when a search asks for its
// errors (the measurement costs more than the coding, and searches on size need none); only the
// last coded model is held, so that a search holds one candidate at a time (a decoded candidate
// is as large as the fit).
class Coder {
 public:
  Coder(const Model& fit, const StructuredGrid& grid) : fit_(fit), grid_(grid) {}

  // Bytes of the control points coded with tolerance 2^exponent.
  std::int64_t bytes(int exponent) {
    auto it = known_.find(exponent);
    if (it == known_.end()) it = code(exponent);
    return it->second.controlBytes;
  }

  // Errors of the model coded with tolerance 2^exponent, measured on the decoded model.
  const SampleErrors& errors(int exponent) {
    auto it = known_.find(exponent);
    if (it == known_.end()) it = code(exponent);
    if (!it->second.errors) {
      if (!last_ || last_->exponent != exponent) code(exponent);
      it->second.errors = errorsOnGrid(last_->model.spline(), grid_);
    }
    return *it->second.errors;
  }

  // Whether the model coded with tolerance 2^exponent stays within `limit` at every sample;
  // a failing one is measured only up to the slab where it fails.
  bool within(int exponent, double limit) {
    auto it = known_.find(exponent);
    if (it == known_.end()) it = code(exponent);
    if (it->second.errors) return it->second.errors->max <= limit;
    if (it->second.exceeds && *it->second.exceeds <= limit) return false;
    if (!last_ || last_->exponent != exponent) code(exponent);
    const auto e = errorsOnGridWithin(last_->model.spline(), grid_, limit);
    if (!e) {
      it->second.exceeds = limit;
      return false;
    }
    it->second.errors = *e;
    return e->max <= limit;
  }

  // The model coded with tolerance 2^exponent, with its errors (coded again unless it was the
  // last one).
  Coded take(int exponent) {
    const SampleErrors e = errors(exponent);
    if (!last_ || last_->exponent != exponent) code(exponent);
    Coded out = std::move(*last_);
    out.errors = e;
    last_.reset();
    return out;
  }

 private:
  struct Known {
    std::optional<SampleErrors> errors;
    std::optional<double> exceeds;  // a limit some sample's error is known to exceed
    std::int64_t controlBytes = 0;
  };

  std::map<int, Known>::iterator code(int exponent) {
    last_.reset();
    Coded k{
        codeControlPoints(fit_, {ControlCoder::kZfp, std::ldexp(1.0, exponent)}), {}, 0, exponent};
    k.controlBytes = codedControlBytes(k.model);
    const auto it = known_.try_emplace(exponent).first;
    it->second.controlBytes = k.controlBytes;
    last_ = std::move(k);
    return it;
  }

  const Model& fit_;
  const StructuredGrid& grid_;
  std::map<int, Known> known_;
  std::optional<Coded> last_;
};

// Bytes of a fit's control points stored with a coder that is not zfp (float32: no coding).
std::int64_t codedSize(const Model& m, ControlCoder coder) {
  const std::span<const float> ctrl = m.spline().controlPoints();
  if (coder == ControlCoder::kFloat32) return 4 * static_cast<std::int64_t>(ctrl.size());
  return static_cast<std::int64_t>(
      encodeControlPoints(ctrl, m.spline().counts(), {coder, 0.0}).size());
}

std::pair<int, int> exponentRange(const Model& fit) {
  return toleranceExponentRange(fit.valueMin(), fit.valueMax());
}

// largestPassing (ToleranceSearch.h), searched outward from `start` (a likely answer): a candidate
// next to the answer fails there, and failures are cheap to find (Coder::within), so this measures
// fewer candidates in full than halving the interval.
template <class Pass>
int largestPassingFrom(int lo, int hi, int start, Pass pass) {
  int k = std::clamp(start, lo, hi);
  if (pass(k)) {
    while (k < hi && pass(k + 1)) ++k;
    return k;
  }
  while (--k >= lo && !pass(k)) {
  }
  return k;
}

// The coded model with the errors it states measured on it; `report` (optional) becomes its
// report, keeping the fit's time and adaptive history.
Model finish(Coded c, FitReport* report, const std::string& note) {
  Provenance& p = c.model.provenance();
  p.maxError = c.errors.max;
  p.rmsError = c.errors.rms;
  if (report) {
    p.fitSeconds = report->seconds;
    FitReport r = fitReportOf(c.model);
    r.rounds = report->rounds;
    r.targetRelativeError = report->targetRelativeError;
    r.reachedTarget = report->reachedTarget;
    r.stopReason = report->stopReason;
    r.codingNote = note;
    *report = r;
  }
  return std::move(c.model);
}

}  // namespace

bool isIntegerSampleType(const std::string& type) {
  static const char* kTypes[] = {"int8",  "uint8",  "int16", "uint16",
                                 "int32", "uint32", "int64", "uint64"};
  return std::find(std::begin(kTypes), std::end(kTypes), type) != std::end(kTypes);
}

ControlCoder resolvedCoder(const CodingOptions& options) {
  if (options.coder) return *options.coder;
  return options.budget.kind != BudgetKind::kNone ? ControlCoder::kZfp : ControlCoder::kFloat32;
}

Model codeFittedModel(Model fit, const StructuredGrid& grid, const CodingOptions& options,
                      double maxError, bool countsGiven, FitReport* report) {
  const auto start = std::chrono::steady_clock::now();
  const ControlCoder coder = resolvedCoder(options);
  auto seconds = [&] {
    if (report)
      report->seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  if (coder != ControlCoder::kZfp) {
    // float32 stores the fit as it is and lossless codes it bit for bit: the fit itself is the
    // model (no decoded copy), its errors those the fit measured.
    const bool lossless = coder == ControlCoder::kLossless;
    const ControlCoding coding{coder, 0.0};
    std::shared_ptr<const std::string> payload;
    if (lossless)
      payload = std::make_shared<const std::string>(
          encodeControlPoints(fit.spline().controlPoints(), fit.spline().counts(), coding));
    const SampleErrors errors{fit.provenance().maxError, fit.provenance().rmsError};
    fit.setControlCoding(coding, std::move(payload));
    const std::int64_t bytes = codedControlBytes(fit);
    seconds();
    return finish(Coded{std::move(fit), errors, bytes, 0}, report,
                  lossless ? "lossless (byte-shuffled float32, zstd): the fitted model bit for bit"
                           : "float32, uncoded");
  }
  Coder coded(fit, grid);
  std::string note;
  int k = 0;
  {
    const auto [lo, hi] = exponentRange(fit);
    const bool integer = isIntegerSampleType(grid.sampleType);
    if (options.tolerance > 0.0) {
      k = static_cast<int>(std::floor(std::log2(options.tolerance)));
      note = "zfp tolerance " + tolerancePhrase(k) + " (--coding-tolerance " +
             numberText(options.tolerance) + ", rounded down to a power of two)";
    } else if (maxError > 0.0) {
      // The room the fit left under the bound is a tolerance that surely keeps it (the model
      // moves by at most the tolerance); the B-spline averages the coding errors, so up to 32
      // times that is tried, each measured.
      const double room = maxError - fit.provenance().maxError;
      const int sure = std::max(
          lo, static_cast<int>(std::floor(std::log2(std::max(room, std::ldexp(1.0, lo))))));
      k = largestPassing(lo, std::min(hi, sure + 5),
                         [&](int e) { return coded.within(e, maxError); });
      if (k < lo) {
        // No tolerance keeps the bound: store the fit losslessly instead.
        CodingOptions lossless = options;
        lossless.coder = ControlCoder::kLossless;
        Model m = codeFittedModel(std::move(fit), grid, lossless, 0.0, countsGiven, report);
        if (report)
          report->codingNote =
              "lossless: the fit leaves no room for a zfp tolerance under the "
              "error bound";
        return m;
      }
      note = "zfp tolerance " + tolerancePhrase(k) + ": the largest that keeps the error bound " +
             numberText(maxError) + " (the fit alone: " + numberText(fit.provenance().maxError) +
             ")";
    } else if (integer) {
      // The largest tolerance whose decoded model still rounds to every sample: the B-spline
      // averages the control points' coding errors, so the model moves far less than the
      // tolerance (measured, not assumed).
      const int floorK = static_cast<int>(std::floor(std::log2(kIntegerDefaultTolerance)));
      // Usually the answer is the top or close below it (tolerance 4 for 8-bit scans).
      const double below = std::nextafter(kIntegerRoundingBound, 0.0);
      k = largestPassingFrom(floorK, floorK + 5, floorK + 4,
                             [&](int e) { return coded.within(e, below); });
      if (k < floorK) k = floorK;  // the fit itself misses by half a step (a --ctrl model)
      note = "zfp tolerance " + tolerancePhrase(k) +
             ", the default of integer samples: the largest (from " +
             numberText(kIntegerDefaultTolerance) +
             " up) whose decoded model rounds back to every sample it was fitted to";
      const std::int64_t cap = grid.inputBytes;
      if (!countsGiven && cap > 0 && coded.bytes(k) > cap) {
        const int raised = smallestPassing(k, hi, [&](int e) { return coded.bytes(e) <= cap; });
        if (raised <= hi) {
          k = raised;
          note = "zfp tolerance " + tolerancePhrase(k) +
                 ": raised further to keep the model within the input's " + std::to_string(cap) +
                 " bytes (--coding lossless or --coding-tolerance for more)";
        }
      }
    } else {
      const double range = std::max(fit.valueMax() - fit.valueMin(), 1e-30);
      k = static_cast<int>(std::floor(std::log2(kFloatDefaultRelativeTolerance * range)));
      note = "zfp tolerance " + tolerancePhrase(k) + " (the default: 1e-5 of the value range)";
    }
  }
  Coded c = coded.take(k);
  seconds();
  return finish(std::move(c), report, note);
}

Model encodeToBudget(const StructuredGrid& grid, const StructuredFitOptions& fit,
                     const CodingOptions& options, bool countsGiven, FitReport* report) {
  const auto start = std::chrono::steady_clock::now();
  const ModelBudget& budget = options.budget;
  if (budget.kind == BudgetKind::kNone) throw Error("encodeToBudget needs a budget");
  if (!(std::isfinite(budget.value) && budget.value > 0.0))
    throw Error("the budget must be a positive number");
  const ControlCoder coder = resolvedCoder(options);
  if (coder == ControlCoder::kZfp && options.tolerance > 0.0)
    throw Error("a budget chooses the zfp tolerance: give one or the other");
  const double samples = static_cast<double>(grid.sampleCount());
  const std::int64_t byteCap =
      budget.kind == BudgetKind::kBitsPerSample
          ? static_cast<std::int64_t>(std::floor(budget.value * samples / 8.0))
          : 0;

  // Candidate control grids: the given one, or a share of the samples on every axis.
  std::vector<Index3> counts;
  const Index3 given = resolveControlCounts(grid, fit);
  if (countsGiven) {
    counts.push_back(given);
  } else {
    for (double share : {1.0, 0.8, 0.65, 0.5, 0.4, 0.32, 0.25}) {
      Index3 n{};
      // Below the sample count, multiples of 4: ZFP codes 4^3 blocks, and a partial block at
      // the end of an axis costs nearly as much as a full one (measured: 33^3 control points
      // took as many bytes as 41^3).
      for (int a = 0; a < 3; ++a) {
        const double want = share * static_cast<double>(grid.dims[a]);
        const std::int64_t count = share == 1.0 ? grid.dims[a] : 4 * std::llround(want / 4.0);
        n[a] = std::clamp<std::int64_t>(count, fit.degree[a] + 1, grid.dims[a]);
      }
      if (counts.empty() || n != counts.back()) counts.push_back(n);
    }
  }

  std::optional<Coded> best;
  double bestFitRms = 0.0;
  std::string tried;
  double range = 0.0, targetRms = 0.0;
  for (size_t i = 0; i < counts.size(); ++i) {
    StructuredFitOptions f = fit;
    f.controlCounts = counts[i];
    if (fit.progress)
      fit.progress(static_cast<double>(i) / static_cast<double>(counts.size()),
                   "candidate " + std::to_string(i + 1) + " of " + std::to_string(counts.size()));
    StructuredFitOptions quiet = f;
    quiet.progress = nullptr;
    const Model model = fitStructured(grid, quiet);
    range = model.valueMax() - model.valueMin();
    if (budget.kind == BudgetKind::kPsnr)
      targetRms = range > 0.0 ? range / std::pow(10.0, budget.value / 20.0) : 0.0;
    else if (budget.kind == BudgetKind::kRmsError)
      targetRms = budget.value;
    const double fitRms = model.provenance().rmsError;
    // Without zfp the candidate is the fit itself, measured already.
    std::optional<Coder> zfp;
    if (coder == ControlCoder::kZfp) zfp.emplace(model, grid);
    const Measured uncoded{{model.provenance().maxError, model.provenance().rmsError},
                           coder == ControlCoder::kZfp ? 0 : codedSize(model, coder)};
    auto bytesAt = [&](int x) { return zfp ? zfp->bytes(x) : uncoded.controlBytes; };
    auto errorsAt = [&](int x) -> const SampleErrors& {
      return zfp ? zfp->errors(x) : uncoded.errors;
    };
    const auto [lo, hi] = zfp ? exponentRange(model) : std::pair<int, int>{0, 0};
    std::optional<int> k;
    if (budget.kind == BudgetKind::kBitsPerSample) {
      const int e = smallestPassing(lo, hi, [&](int x) { return bytesAt(x) <= byteCap; });
      if (e <= hi) k = e;
    } else if (fitRms <= targetRms) {
      const int e = largestPassing(lo, hi, [&](int x) { return errorsAt(x).rms <= targetRms; });
      if (e >= lo) k = e;
    }
    std::ostringstream line;
    line << counts[i][0] << "x" << counts[i][1] << "x" << counts[i][2] << ": ";
    if (!k) {
      line << (budget.kind == BudgetKind::kBitsPerSample
                   ? "over the budget at any tolerance"
                   : "the fit alone misses the target (" +
                         numberText(psnrOf(range, fitRms), "%.1f") + " dB)");
      tried += "  " + line.str() + "\n";
      // Fewer control points fit worse still: once a candidate met the error target, the
      // first that cannot ends the search.
      if (best && budget.kind != BudgetKind::kBitsPerSample) break;
      continue;
    }
    const Measured c{errorsAt(*k), bytesAt(*k)};
    line << numberText(8.0 * static_cast<double>(c.controlBytes) / samples, "%.3f")
         << " bits/sample, " << numberText(psnrOf(range, c.errors.rms), "%.2f") << " dB"
         << (coder == ControlCoder::kZfp ? ", tolerance " + tolerancePhrase(*k) : std::string());
    tried += "  " + line.str() + "\n";
    const bool better =
        !best || (budget.kind == BudgetKind::kBitsPerSample ? c.errors.rms < best->errors.rms
                                                            : c.controlBytes < best->controlBytes);
    // Every candidate is tried: neither the error at a byte budget nor the bytes at an error
    // target is unimodal in the control count (coarser grids are smoother to code).
    if (better) {
      best.reset();
      if (zfp) {
        best = zfp->take(*k);
      } else {
        Model own = model;
        own.setControlCoding({coder, 0.0});
        best = Coded{std::move(own), c.errors, c.controlBytes, 0};
      }
      bestFitRms = fitRms;
    }
  }
  if (!best) {
    std::ostringstream m;
    m << "no model of " << grid.source << " meets ";
    if (budget.kind == BudgetKind::kBitsPerSample)
      m << "--bits-per-sample " << budget.value;
    else if (budget.kind == BudgetKind::kPsnr)
      m << "--psnr " << budget.value << " dB";
    else
      m << "--rms-error " << budget.value;
    m << ":\n" << tried;
    if (budget.kind != BudgetKind::kBitsPerSample)
      m << "(an interpolating fit of every sample reaches the most; a higher degree or "
           "--coding lossless may help)";
    else
      m << "(raise the budget, or give fewer control points with --ctrl)";
    throw Error(m.str());
  }
  std::ostringstream note;
  note << (budget.kind == BudgetKind::kBitsPerSample ? "the most accurate of the candidates within "
                                                     : "the smallest of the candidates that meets ")
       << (budget.kind == BudgetKind::kBitsPerSample ? numberText(budget.value) + " bits/sample"
           : budget.kind == BudgetKind::kPsnr        ? numberText(budget.value) + " dB PSNR"
                                              : "an RMS error of " + numberText(budget.value))
       << " (fit alone: " << numberText(psnrOf(range, bestFitRms), "%.2f") << " dB); candidates:\n"
       << tried;
  if (report) {
    report->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report->rounds = 0;
  }
  if (fit.progress) fit.progress(1.0, "done");
  return finish(std::move(*best), report, note.str());
}

}  // namespace mfadvr
