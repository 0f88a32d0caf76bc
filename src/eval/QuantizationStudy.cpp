// Quantized samples against the clean truth (docs/denoise.md, "Quantized samples"): the terraces
// of 6-, 8- and 10-bit quantization, and what each reconstruction makes of them.
//
// Each analytic field is sampled on an n^3 grid, scaled to the levels 0 .. 2^b - 1 over its range
// and rounded to integers, as a scan stores it (uint8 or uint16, so that the MFA models are coded
// with zfp within half a level, as `mfadvr encode` codes integer scans). The truth is the field
// scaled the same way. Methods: trilinear and tricubic on the quantized samples; MFA models
// fitted to them: interpolating, `--smooth auto`, `--dequantize`. Measured: the image against the
// truth's (shaded, opacity step at an isovalue), the value at random points between the samples,
// the angle between the method's gradient and the truth's on the truth's isosurface (terraces are
// gradient errors), and for the models the largest |model - sample| in levels (<= 0.5: rounds
// back to every sample), bits per sample and encode time.
#include "eval/QuantizationStudy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/CodingChoice.h"
#include "core/encode/Encoder.h"
#include "core/image/BitmapFont.h"
#include "core/image/Montage.h"
#include "core/render/ReconstructionMethod.h"
#include "eval/CsvTable.h"
#include "eval/EvalRendering.h"

namespace mfadvr::eval {
namespace {

// a (F - vmin): the field in quantization levels.
class ScaledFunction final : public BuiltinFunction {
 public:
  ScaledFunction(const BuiltinFunction& f, double scale, double offset)
      : f_(f), scale_(scale), offset_(offset) {}
  std::string name() const override { return f_.name(); }
  Index3 defaultDims() const override { return f_.defaultDims(); }
  double value(const Vec3d& x) const override { return scale_ * (f_.value(x) - offset_); }
  double valueGradient(const Vec3d& x, Vec3d& g) const override {
    const double v = f_.valueGradient(x, g);
    g *= scale_;
    return scale_ * (v - offset_);
  }

 private:
  const BuiltinFunction& f_;
  double scale_, offset_;
};

struct Subject {
  std::string function;
  std::string kind;  // "smooth", "scan-like" or "oscillating": which goal it is judged by
  // The isovalue of the opacity step and of the gradient measurement: a fraction of the clean
  // range, or (isoValue set) a value of the field.
  double isoFraction = 0.5;
  std::optional<double> isoValue;
  std::string isoNote;
  // The soft part of the isosurface, measured on its own (empty: none).
  std::function<bool(const Vec3d&)> soft;
};

// Points on the truth's isosurface: where the field crosses `iso` along the edges of a lattice of
// m^3 points (cell centres of [-1,1]^3 cut into m cells per axis), each located by bisection; at
// most `cap` of them, evenly strided.
std::vector<Vec3d> isosurfacePoints(const BuiltinFunction& f, double iso, int m, size_t cap) {
  const double h = 2.0 / m;
  auto at = [&](int i) { return -1.0 + (i + 0.5) * h; };
  std::vector<double> v(static_cast<size_t>(m) * m * m);
  tbb::parallel_for(0, m, [&](int k) {
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        v[(static_cast<size_t>(k) * m + j) * m + i] = f.value(Vec3d(at(i), at(j), at(k))) - iso;
  });
  std::vector<Vec3d> points;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const double a = v[(static_cast<size_t>(k) * m + j) * m + i];
        const Vec3d p(at(i), at(j), at(k));
        const int next[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (int axis = 0; axis < 3; ++axis) {
          const auto [ni, nj, nk] = next[axis];
          if (ni >= m || nj >= m || nk >= m) continue;
          const double b = v[(static_cast<size_t>(nk) * m + nj) * m + ni];
          if ((a < 0.0) == (b < 0.0)) continue;
          double lo = 0.0, hi = h;  // along the axis from p; the sign of a at lo
          for (int it = 0; it < 40; ++it) {
            const double mid = 0.5 * (lo + hi);
            Vec3d q = p;
            q[axis] += mid;
            ((f.value(q) - iso < 0.0) == (a < 0.0) ? lo : hi) = mid;
          }
          Vec3d q = p;
          q[axis] += 0.5 * (lo + hi);
          points.push_back(q);
        }
      }
  if (points.size() > cap) {
    std::vector<Vec3d> kept;
    const double stride = static_cast<double>(points.size()) / static_cast<double>(cap);
    for (size_t t = 0; t < cap; ++t) kept.push_back(points[static_cast<size_t>(t * stride)]);
    points = std::move(kept);
  }
  return points;
}

// Mean angle (degrees) between each gradient and the truth's; a zero gradient counts as 90.
double meanAngle(const std::vector<ValueGradient>& got, const std::vector<Vec3d>& truth,
                 const std::vector<bool>* keep = nullptr) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    if (keep && !(*keep)[i]) continue;
    const Vec3d g = got[i].gradient.cast<double>();
    const double d = g.norm() * truth[i].norm();
    const double c = d > 0.0 ? std::clamp(g.dot(truth[i]) / d, -1.0, 1.0) : 0.0;
    sum += std::acos(c) * 180.0 / std::numbers::pi;
    ++n;
  }
  return n ? sum / static_cast<double>(n) : std::nan("");
}

struct Result {
  ImageComparison image;
  double valuePsnr = 0.0, angle = 0.0, softAngle = std::nan("");
  // Models only (NaN for the filters).
  double maxSampleError = std::nan(""), bitsPerSample = std::nan(""), seconds = std::nan("");
  double lambda = std::nan("");
  int iterations = 0;
  Image8 picture;
};

const std::vector<std::string> kMethods = {"trilinear", "tricubic", "mfa", "mfa-auto",
                                           "mfa-dequantize"};

std::string orDash(double v, int decimals) {
  return std::isfinite(v) ? fixed(v, decimals) : std::string("-");
}

}  // namespace

void appendQuantizationStudy(const EvalContext& ctx, ExperimentReport& report) {
  const bool quick = ctx.quick();
  const int image = quick ? 128 : 400;
  const int n = quick ? 33 : 64;
  const std::vector<int> bitDepths = quick ? std::vector<int>{8} : std::vector<int>{6, 8, 10};
  std::vector<Subject> subjects = {
      {"gaussian-beam", "smooth", 0.5, std::nullopt, "opacity step at 0.5 of the range", {}},
      {"marschner-lobb", "oscillating", 0.5, std::nullopt, "opacity step at 0.5", {}},
      {"ct-head", "scan-like", 0.6, std::nullopt, "opacity step at 200 HU (vessels, skull)", {}},
      {"soft-and-sharp", "scan-like", 0.0, 38.0,
       "opacity step at the value 38 (the soft blob and the sharp ball); soft: the blob's half, "
       "x > 0.1",
       [](const Vec3d& x) { return x[0] > 0.1; }}};
  if (quick) subjects = {subjects.back()};
  const std::string gridName = std::to_string(n) + "^3";

  std::string& md = report.markdown;
  md += "\n### Quantized samples\n\nSettings: each field sampled on " + gridName +
        " points, scaled to the levels 0 .. 2^b - 1 over its range and rounded (stored as uint8 "
        "or uint16, the models zfp-coded as `mfadvr encode` codes integer scans); the truth is the "
        "field scaled the same way. " +
        std::to_string(image) + "x" + std::to_string(image) +
        " images, shaded, azimuth 30, elevation 25. `value dB`: PSNR over the levels at 100,000 "
        "random points; `angle`: mean angle (degrees) between the method's gradient and the "
        "truth's at points of the truth's isosurface; `max/step`: the largest |model - sample| "
        "in levels (<= 0.5: the model rounds back to every sample).\n\n";

  CsvTable table({"function", "grid", "bits", "method", "psnr", "ssim", "value_psnr", "angle_deg",
                  "soft_angle_deg", "max_sample_error_levels", "bits_per_sample", "encode_seconds",
                  "lambda", "dequantize_iterations", "image"});
  struct Row {
    std::string subject, kind;
    int bits = 0;
    std::map<std::string, Result> r;
  };
  std::vector<Row> rows;

  for (const Subject& subject : subjects) {
    const auto f = makeBuiltin(subject.function);
    const StructuredGrid clean = sampleBuiltin(*f, {n, n, n});
    const auto [lo, hi] = std::minmax_element(clean.values.begin(), clean.values.end());
    const double vmin = *lo, vmax = *hi;
    const double isoFraction =
        subject.isoValue ? (*subject.isoValue - vmin) / (vmax - vmin) : subject.isoFraction;
    std::vector<std::vector<Image8>> montage;
    for (int bits : bitDepths) {
      const double levels = std::ldexp(1.0, bits) - 1.0;
      const ScaledFunction truthFn(*f, levels / (vmax - vmin), vmin);
      StructuredGrid grid = clean;
      for (float& v : grid.values)
        v = static_cast<float>(std::round(levels * (v - vmin) / (vmax - vmin)));
      grid.sampleType = bits <= 8 ? "uint8" : "uint16";
      grid.source = "builtin:" + subject.function + ":" + std::to_string(n) + " at " +
                    std::to_string(bits) + " bits";
      const std::string label =
          subject.function + " " + gridName + ", " + std::to_string(bits) + " bits";

      RenderSettings s = sceneSettings(image, image, clean.boxMin(), clean.boxMax(), 30.0, 25.0,
                                       "step:" + csvNumber(isoFraction, 6), "white", 0.0, levels,
                                       clean.spacing, 0.5, ctx.threads());
      s.shade = true;
      SceneData scene;
      scene.truth = &truthFn;
      scene.grid = &grid;
      scene.differenceStep = clean.spacing;
      MethodSpec truthSpec;
      truthSpec.method = ReconstructionMethod::Truth;
      ctx.log("denoise: quantized " + label + ": truth");
      const Image8 truth = renderOurs(scene, truthSpec, s).image;

      // The measurement points: random ones for the value, isosurface ones for the gradient.
      std::mt19937_64 rng(17);
      std::uniform_real_distribution<double> uni(-1.0, 1.0);
      std::vector<Vec3d> random(100000);
      for (Vec3d& p : random) p = Vec3d(uni(rng), uni(rng), uni(rng));
      std::vector<double> randomTruth(random.size());
      for (size_t i = 0; i < random.size(); ++i) randomTruth[i] = truthFn.value(random[i]);
      const double iso = isoFraction * levels;
      const std::vector<Vec3d> surface = isosurfacePoints(truthFn, iso, 2 * n, 60000);
      std::vector<Vec3d> surfaceGradient(surface.size());
      std::vector<bool> soft(surface.size(), false);
      for (size_t i = 0; i < surface.size(); ++i) {
        truthFn.valueGradient(surface[i], surfaceGradient[i]);
        soft[i] = subject.soft && subject.soft(surface[i]);
      }

      Row row{subject.function, subject.kind, bits, {}};
      auto measure = [&](const std::string& name, ReconstructionMethod method, const Model* model,
                         const FitReport* fit, double seconds) {
        Result r;
        SceneData sc = scene;
        sc.model = model;
        MethodSpec spec;
        spec.method = method;
        ctx.log("denoise: quantized " + label + ": " + name);
        r.picture = renderOurs(sc, spec, s).image;
        r.image = compareImages(truth, r.picture);
        const auto values = sampleMethod(sc, method, random);
        double sq = 0.0;
        for (size_t i = 0; i < random.size(); ++i)
          sq += (values[i].value - randomTruth[i]) * (values[i].value - randomTruth[i]);
        r.valuePsnr = psnrOf(levels, std::sqrt(sq / static_cast<double>(random.size())));
        const auto gradients = sampleMethod(sc, method, surface);
        r.angle = meanAngle(gradients, surfaceGradient);
        if (subject.soft) r.softAngle = meanAngle(gradients, surfaceGradient, &soft);
        if (fit) {
          r.maxSampleError = fit->maxError;
          r.bitsPerSample = fit->bitsPerSample();
          r.seconds = seconds;
          r.lambda = fit->dequantizeStep > 0.0 ? fit->dequantizeLambda : fit->smoothing;
          r.iterations = fit->dequantizeIterations;
        }
        row.r[name] = std::move(r);
      };
      measure("trilinear", ReconstructionMethod::Trilinear, nullptr, nullptr, 0.0);
      measure("tricubic", ReconstructionMethod::Tricubic, nullptr, nullptr, 0.0);
      auto fitAndMeasure = [&](const std::string& name, EncodeOptions o) {
        o.coding.coder = ControlCoder::kZfp;  // as `mfadvr encode` codes integer samples
        ctx.log("denoise: quantized " + label + ": fitting " + name);
        FitReport fit;
        const auto start = std::chrono::steady_clock::now();
        const Model model = encodeStructured(grid, o, &fit);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        measure(name, ReconstructionMethod::Mfa, &model, &fit, seconds);
      };
      fitAndMeasure("mfa", EncodeOptions{});
      EncodeOptions automatic;
      automatic.autoSmoothing = true;
      fitAndMeasure("mfa-auto", automatic);
      EncodeOptions dequantized;
      dequantized.dequantizeStep = 0.0;  // 1: the samples are integers
      fitAndMeasure("mfa-dequantize", dequantized);

      const std::string prefix = "denoise/quantized_" + subject.function + "_" + std::to_string(n) +
                                 "_" + std::to_string(bits);
      ctx.writeImage(prefix + "_truth.png", truth);
      std::vector<Image8> cells{withCaption(truth, {"truth", std::to_string(bits) + " bits"}, 2)};
      for (const std::string& name : kMethods) {
        Result& r = row.r.at(name);
        const std::string path = ctx.writeImage(prefix + "_" + name + ".png", r.picture);
        table.addRow({subject.function, gridName, std::to_string(bits), name,
                      csvNumber(r.image.psnr), csvNumber(r.image.ssim), csvNumber(r.valuePsnr),
                      csvNumber(r.angle), std::isfinite(r.softAngle) ? csvNumber(r.softAngle) : "",
                      std::isfinite(r.maxSampleError) ? csvNumber(r.maxSampleError) : "",
                      std::isfinite(r.bitsPerSample) ? csvNumber(r.bitsPerSample) : "",
                      std::isfinite(r.seconds) ? csvNumber(r.seconds) : "",
                      std::isfinite(r.lambda) ? csvNumber(r.lambda) : "",
                      name == "mfa-dequantize" ? std::to_string(r.iterations) : "", path});
        cells.push_back(withCaption(r.picture, {name, fixed(r.image.psnr, 2) + " dB"}, 2));
        r.picture = Image8();
      }
      montage.push_back(std::move(cells));
      rows.push_back(std::move(row));
    }
    report.files.push_back(ctx.writeImage("denoise/quantized_" + subject.function + "_montage.png",
                                          montageGrid(montage)));
  }
  table.write(ctx.path("denoise_quantized.csv").string());
  report.files.push_back("denoise_quantized.csv");

  for (const Subject& subject : subjects) {
    md += "**" + subject.function + "** " + gridName + " (" + subject.isoNote +
          "): image PSNR (dB) / value PSNR (dB) / mean gradient angle (degrees" +
          (subject.soft ? "; soft part in brackets" : "") +
          "); models: max |model - sample| in levels, bits/sample, encode seconds\n\n"
          "| bits | method | image | SSIM | value | angle | max/step | bits/sample | encode | "
          "lambda (iterations) |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& row : rows) {
      if (row.subject != subject.function) continue;
      for (const std::string& name : kMethods) {
        const Result& r = row.r.at(name);
        std::string angle = fixed(r.angle, 2);
        if (std::isfinite(r.softAngle)) angle += " (" + fixed(r.softAngle, 2) + ")";
        std::string lambda = std::isfinite(r.lambda) ? csvNumber(r.lambda, 3) : "-";
        if (name == "mfa-dequantize") lambda += " (" + std::to_string(r.iterations) + ")";
        md += "| " + std::to_string(row.bits) + " | " + name + " | " + fixed(r.image.psnr, 2) +
              " | " + fixed(r.image.ssim, 3) + " | " + fixed(r.valuePsnr, 2) + " | " + angle +
              " | " + orDash(r.maxSampleError, 3) + " | " + orDash(r.bitsPerSample, 2) + " | " +
              orDash(r.seconds, 2) + " | " + lambda + " |\n";
      }
    }
    md += "\n";
  }

  // The goals of issue 70 (docs/denoise.md), at 8 bits.
  int smooth = 0, smoothMet = 0, scan = 0, scanMet = 0, softRows = 0, softMet = 0, roundsBack = 0,
      models = 0, smaller = 0;
  for (const Row& row : rows) {
    const Result& d = row.r.at("mfa-dequantize");
    const Result& i = row.r.at("mfa");
    const Result& a = row.r.at("mfa-auto");
    models += 1;
    roundsBack += d.maxSampleError <= 0.5;
    smaller += d.bitsPerSample <= i.bitsPerSample;
    if (row.bits != 8) continue;
    if (row.kind == "smooth") {
      ++smooth;
      smoothMet += d.image.psnr >= i.image.psnr + 3.0 && d.image.psnr >= a.image.psnr + 1.0;
    } else if (row.kind == "scan-like") {
      ++scan;
      scanMet += d.image.psnr >= i.image.psnr + 1.0 && d.image.psnr >= a.image.psnr + 1.0;
      if (std::isfinite(d.softAngle)) {
        ++softRows;
        softMet += d.softAngle <= 0.7 * i.softAngle;
      }
    }
  }
  md += "Goals of `--dequantize` (docs/denoise.md), at 8 bits:\n\n";
  if (smooth)
    md +=
        "- smooth fields, image >= 3 dB above the interpolating model and >= 1 dB above "
        "`--smooth auto`: " +
        std::to_string(smoothMet) + " of " + std::to_string(smooth) + ".\n";
  if (scan)
    md += "- scan-like fields, image >= 1 dB above both: " + std::to_string(scanMet) + " of " +
          std::to_string(scan) + ".\n";
  if (softRows)
    md += "- mean gradient angle on the soft surfaces <= 0.7x the interpolating model's: " +
          std::to_string(softMet) + " of " + std::to_string(softRows) + ".\n";
  md += "- every bit depth: rounds back to every sample (max/step <= 0.5) in " +
        std::to_string(roundsBack) + " of " + std::to_string(models) +
        " configurations; codes no larger than the interpolating model in " +
        std::to_string(smaller) + " of " + std::to_string(models) + ".\n\n";
  md +=
      "Images: `denoise/quantized_FUNCTION_N_BITS_METHOD.png`, montages "
      "`denoise/quantized_FUNCTION_montage.png` (one row per bit depth).\n\n";
}

}  // namespace mfadvr::eval
