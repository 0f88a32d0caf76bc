// Noise reduction (beyond the paper, which names it as future work of the MFA): smoothing fits of
// noisy and quantized samples against the analytic truth of the clean function
// (docs/denoise.md).
//
// Marschner-Lobb and the CT head phantom are sampled on n^3 grids, then quantized to 8 or 12
// bits over their range, or given Gaussian noise of 1, 3 or 10 % of the range (fixed seeds).
// Every method renders the same scene through the same ray caster: the grid filters (nearest,
// trilinear, tricubic, Catmull-Rom, prefiltered B-spline) on the degraded samples; MFA models
// fitted to them (interpolating, least squares with 5/8 as many control points, `--smooth auto`,
// and every lambda of a sweep, the best of which is reported). Images are compared with the
// truth's, rendered from the clean function's value and gradient (paper Table 2), and in the
// gradient-only test (paper Table 1: value from the truth, gradient from the method). Real scans
// from the data folder are rendered with and without smoothing, and integer ones dequantized (no
// truth there), whole and zoomed. The quantization rows against the truth are
// QuantizationStudy.cpp's.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <random>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/CodingChoice.h"
#include "core/encode/Encoder.h"
#include "core/image/BitmapFont.h"
#include "core/image/Montage.h"
#include "eval/CsvTable.h"
#include "eval/EvalRendering.h"
#include "eval/Experiment.h"
#include "eval/QuantizationStudy.h"
#include "io/VolumeLoader.h"

namespace mfadvr::eval {
namespace {

struct Degradation {
  std::string name;
  int bits = 0;        // quantization to 2^bits levels over the clean range (0: none)
  double noise = 0.0;  // Gaussian noise, standard deviation as a fraction of the range
  std::string label() const {
    return bits > 0 ? std::to_string(bits) + "-bit quantization"
                    : fixed(100.0 * noise, 0) + "% Gaussian noise";
  }
};

StructuredGrid degraded(const StructuredGrid& clean, const Degradation& d, double vmin, double vmax,
                        unsigned seed) {
  StructuredGrid g = clean;
  const double range = vmax - vmin;
  if (d.bits > 0) {
    const double levels = std::ldexp(1.0, d.bits) - 1.0;
    for (float& v : g.values)
      v = static_cast<float>(vmin + std::round((v - vmin) / range * levels) * (range / levels));
  }
  if (d.noise > 0.0) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n(0.0, d.noise * range);
    for (float& v : g.values) v = static_cast<float>(v + n(rng));
  }
  g.source += " (" + d.name + ")";
  return g;
}

struct Subject {
  std::string function;
  std::string opacity;  // transfer-function preset over the clean range
  std::string isoNote;
};

struct MethodResult {
  std::string name;
  double lambda = -1.0;  // MFA fits: the smoothing weight (0: none); others -1
  ImageComparison full, gradientOnly;
  double samplePsnr = 0.0;  // the reconstruction at the samples against the clean samples
  Image8 image;
};

std::string lambdaText(double lambda) {
  if (lambda < 0.0) return "";
  if (lambda == 0.0) return "0";
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", lambda);
  return b;
}

}  // namespace

ExperimentReport runDenoiseStudy(const EvalContext& ctx) {
  const bool quick = ctx.quick();
  const int image = quick ? 128 : 400;
  const std::vector<int> sizes = quick ? std::vector<int>{41} : std::vector<int>{41, 64, 128};
  std::vector<Degradation> degradations = {
      {"q8", 8, 0.0}, {"q12", 12, 0.0}, {"n1", 0, 0.01}, {"n3", 0, 0.03}, {"n10", 0, 0.10}};
  if (quick) degradations = {{"q8", 8, 0.0}, {"n3", 0, 0.03}};
  std::vector<double> sweep;
  for (double e = quick ? -3.0 : -4.0; e <= (quick ? 1.0 : 2.0) + 1e-9; e += quick ? 1.0 : 0.5)
    sweep.push_back(std::pow(10.0, e));
  const std::vector<Subject> subjects = {
      {"marschner-lobb", "step:0.5", "opacity step at 0.5 of the range (the isovalue 0.5)"},
      {"ct-head", "step:0.6", "opacity step at 0.6 of the range (200 HU: vessels and skull)"}};
  using RM = ReconstructionMethod;
  const std::vector<RM> filters = {RM::Nearest, RM::Trilinear, RM::Tricubic, RM::CatmullRom,
                                   RM::BSpline};
  // One step for every grid, fine enough for the 128^3 samples: equal truth images.
  const double step = 0.5 * 2.0 / 127.0;

  ExperimentReport report;
  std::string& md = report.markdown;
  md += "Settings: " + std::to_string(image) + "x" + std::to_string(image) +
        " images, perspective framed on [-1,1]^3, azimuth 30, elevation 25, constant white, "
        "shading on (headlight; ambient 0.3, diffuse 0.7, specular 0.2, power 10), step " +
        csvNumber(step, 4) + ". Marschner-Lobb: " + subjects[0].isoNote +
        "; ct-head: " + subjects[1].isoNote +
        ". Degradations of the samples: quantization to 2^b levels over the clean range, "
        "Gaussian noise with a standard deviation of a fraction of the range (fixed seeds). "
        "MFA: degree 3; `mfa` as many control points as samples (interpolating), `mfa-lsq` 5/8 "
        "as many per axis, `mfa-auto` `--smooth auto`, `mfa-best` the best lambda of the sweep "
        "{";
  for (size_t i = 0; i < sweep.size(); ++i) md += (i ? ", " : "") + lambdaText(sweep[i]);
  md +=
      "} by image PSNR. PSNR/SSIM on 8-bit RGB against the truth (the clean function's value "
      "and gradient); `grad` columns: the gradient-only test (value from the truth). "
      "`samples dB`: the reconstruction at the sample points against the clean samples, over "
      "the range.\n\n";

  CsvTable table({"function", "grid", "degradation", "method", "lambda", "psnr", "ssim",
                  "gradient_psnr", "gradient_ssim", "samples_psnr", "image"});
  struct GoalRow {
    std::string subject, grid, degradation;
    std::map<std::string, MethodResult> r;
  };
  std::vector<GoalRow> goals;
  std::vector<std::vector<Image8>> montageRows;
  const std::vector<std::string> montageColumns = {"trilinear", "catmull-rom", "bspline", "mfa",
                                                   "mfa-lsq",   "mfa-auto",    "mfa-best"};
  unsigned seed = 1;
  for (const Subject& subject : subjects) {
    const auto f = makeBuiltin(subject.function);
    for (int n : sizes) {
      const std::string gridName =
          std::to_string(n) + "x" + std::to_string(n) + "x" + std::to_string(n);
      const StructuredGrid clean = sampleBuiltin(*f, {n, n, n});
      const auto [lo, hi] = std::minmax_element(clean.values.begin(), clean.values.end());
      const double vmin = *lo, vmax = *hi, range = vmax - vmin;
      RenderSettings s =
          sceneSettings(image, image, clean.boxMin(), clean.boxMax(), 30.0, 25.0, subject.opacity,
                        "white", vmin, vmax, clean.spacing, 0.5, ctx.threads());
      s.sampleDistance = step;
      s.shade = true;
      SceneData truthScene;
      truthScene.truth = f.get();
      truthScene.grid = &clean;
      truthScene.differenceStep = clean.spacing;
      MethodSpec truthSpec;
      truthSpec.method = ReconstructionMethod::Truth;
      ctx.log("denoise: " + subject.function + " " + gridName + ": truth");
      const Image8 truth = renderOurs(truthScene, truthSpec, s).image;
      const std::string prefix = "denoise/" + subject.function + "_" + std::to_string(n);
      ctx.writeImage(prefix + "_truth.png", truth);

      for (const Degradation& d : degradations) {
        ctx.log("denoise: " + subject.function + " " + gridName + ", " + d.name + ": fitting");
        const StructuredGrid grid = degraded(clean, d, vmin, vmax, seed++);
        double degradedSq = 0.0;
        for (size_t i = 0; i < grid.values.size(); ++i)
          degradedSq += (grid.values[i] - clean.values[i]) * (grid.values[i] - clean.values[i]);
        const double degradedPsnr =
            psnrOf(range, std::sqrt(degradedSq / static_cast<double>(grid.values.size())));
        SceneData scene = truthScene;
        scene.grid = &grid;

        auto render = [&](const std::string& name, const MethodSpec& spec, const Model* model,
                          double lambda, bool gradientTest) {
          MethodResult m;
          m.name = name;
          m.lambda = lambda;
          SceneData sc = scene;
          sc.model = model;
          const Image8 img = renderOurs(sc, spec, s).image;
          m.full = compareImages(truth, img);
          m.image = img;
          if (gradientTest) {
            MethodSpec g;
            g.method = ReconstructionMethod::Truth;
            g.gradientFrom = spec.method;
            m.gradientOnly = compareImages(truth, renderOurs(sc, g, s).image);
          }
          if (model) {
            const SampleErrors e = errorsOnGrid(model->spline(), clean);
            m.samplePsnr = psnrOf(range, e.rms);
          } else {
            m.samplePsnr = degradedPsnr;  // the filters all pass through the samples
          }
          return m;
        };
        auto fit = [&](Index3 counts, std::optional<double> lambda, bool automatic,
                       FitReport* r = nullptr) {
          EncodeOptions o;
          o.controlCounts = counts;
          o.smoothing = lambda;
          o.autoSmoothing = automatic;
          return encodeStructured(grid, o, r);
        };
        const std::int64_t lsq = std::max<std::int64_t>(4, std::llround(0.625 * n));
        const Model interpolating = fit({n, n, n}, std::nullopt, false);
        const Model fewer = fit({lsq, lsq, lsq}, std::nullopt, false);
        FitReport autoReport;
        const Model automatic = fit({n, n, n}, std::nullopt, true, &autoReport);

        GoalRow row{subject.function, gridName, d.name, {}};
        ctx.log("denoise: " + subject.function + " " + gridName + ", " + d.name + ": rendering");
        for (const RM method : filters) {
          MethodSpec spec;
          spec.method = method;
          row.r[methodName(method)] = render(methodName(method), spec, nullptr, -1.0, true);
        }
        MethodSpec mfa;
        mfa.method = ReconstructionMethod::Mfa;
        row.r["mfa"] = render("mfa", mfa, &interpolating, 0.0, true);
        row.r["mfa-lsq"] = render("mfa-lsq", mfa, &fewer, 0.0, true);
        row.r["mfa-auto"] = render("mfa-auto", mfa, &automatic, autoReport.smoothing, true);
        MethodResult best;
        best.full.psnr = -1.0;
        std::vector<MethodResult> swept;
        for (double lambda : sweep) {
          const Model m = fit({n, n, n}, lambda, false);
          MethodResult r = render("sweep", mfa, &m, lambda, false);
          if (r.full.psnr > best.full.psnr) {
            best = r;
            best.gradientOnly = render("sweep", mfa, &m, lambda, true).gradientOnly;
          }
          swept.push_back(std::move(r));
        }
        best.name = "mfa-best";
        row.r["mfa-best"] = best;

        auto addRow = [&](const MethodResult& m) {
          const std::string path =
              m.name == "sweep"
                  ? std::string()
                  : ctx.writeImage(prefix + "_" + d.name + "_" + m.name + ".png", m.image);
          table.addRow({subject.function, gridName, d.name, m.name, lambdaText(m.lambda),
                        csvNumber(m.full.psnr), csvNumber(m.full.ssim),
                        m.name == "sweep" ? "" : csvNumber(m.gradientOnly.psnr),
                        m.name == "sweep" ? "" : csvNumber(m.gradientOnly.ssim),
                        csvNumber(m.samplePsnr), path});
        };
        for (const RM method : filters) addRow(row.r[methodName(method)]);
        for (const char* name : {"mfa", "mfa-lsq", "mfa-auto", "mfa-best"}) addRow(row.r[name]);
        for (const MethodResult& r : swept) addRow(r);

        if (n == (quick ? 41 : 64)) {
          std::vector<Image8> cells{withCaption(truth, {"truth", d.label()}, 2)};
          for (const std::string& c : montageColumns) {
            const MethodResult& m = row.r[c];
            std::string caption = c;
            if (m.lambda > 0.0) caption += " l=" + lambdaText(m.lambda);
            cells.push_back(withCaption(m.image, {caption, fixed(m.full.psnr, 2) + " dB"}, 2));
          }
          montageRows.push_back(std::move(cells));
        }
        for (auto& [name, m] : row.r) m.image = Image8();
        goals.push_back(std::move(row));
      }
      if (!montageRows.empty() && n == (quick ? 41 : 64)) {
        report.files.push_back(ctx.writeImage("denoise/" + subject.function + "_montage.png",
                                              montageGrid(montageRows)));
        montageRows.clear();
      }
    }
  }
  table.write(ctx.path("denoise.csv").string());
  report.files.push_back("denoise.csv");

  // Tables: image PSNR (value and gradient from the method) per configuration.
  const std::vector<std::string> columns = {"nearest",     "trilinear", "tricubic",
                                            "catmull-rom", "bspline",   "mfa",
                                            "mfa-lsq",     "mfa-auto",  "mfa-best"};
  for (const Subject& subject : subjects) {
    md += "**" + subject.function +
          "**, image PSNR (dB) against the truth; gradient-only test "
          "in brackets for trilinear and the MFA models\n\n| grid | samples |";
    for (const auto& c : columns) md += " " + c + " |";
    md += " auto lambda |\n|---|---|";
    for (size_t i = 0; i <= columns.size(); ++i) md += "---|";
    md += "\n";
    for (const GoalRow& g : goals) {
      if (g.subject != subject.function) continue;
      md += "| " + g.grid + " | " + g.degradation + " |";
      for (const auto& c : columns) {
        const MethodResult& m = g.r.at(c);
        md += " " + fixed(m.full.psnr, 2);
        if (c == "trilinear" || c.rfind("mfa", 0) == 0)
          md += " (" + fixed(m.gradientOnly.psnr, 1) + ")";
        md += " |";
      }
      md += " " + lambdaText(g.r.at("mfa-auto").lambda) + " |\n";
    }
    md += "\n";
  }

  // The goals of docs/denoise.md, judged on every configuration they name.
  int noisyRows = 0, noisyTri = 0, noisyInterp = 0, quantRows = 0, quantOk = 0, nearBest = 0;
  double worstGap = 0.0;
  for (const GoalRow& g : goals) {
    const double a = g.r.at("mfa-auto").full.psnr;
    if (g.degradation == "n3") {
      ++noisyRows;
      noisyTri += a >= g.r.at("trilinear").full.psnr + 3.0;
      noisyInterp += a >= g.r.at("mfa").full.psnr + 3.0;
    }
    if (g.degradation == "q8") {
      ++quantRows;
      quantOk += a >= g.r.at("mfa").full.psnr - 0.05;
    }
    const double gap = g.r.at("mfa-best").full.psnr - a;
    nearBest += gap <= 0.5;
    worstGap = std::max(worstGap, gap);
  }
  md += "Goals (docs/denoise.md):\n\n";
  md += "- 3% noise, `--smooth auto` at least 3 dB above trilinear: " + std::to_string(noisyTri) +
        " of " + std::to_string(noisyRows) +
        " configurations; above the interpolating model: " + std::to_string(noisyInterp) + " of " +
        std::to_string(noisyRows) + ".\n";
  md += "- 8-bit quantization, no worse than the interpolating model (within 0.05 dB): " +
        std::to_string(quantOk) + " of " + std::to_string(quantRows) + ".\n";
  md += "- Within 0.5 dB of the sweep's best lambda: " + std::to_string(nearBest) + " of " +
        std::to_string(goals.size()) + " configurations (largest gap " + fixed(worstGap, 2) +
        " dB).\n\n";

  appendQuantizationStudy(ctx, report);

  // Real scans: no truth; the pictures with and without smoothing, whole and zoomed.
  md += "### Real scans\n\n";
  std::vector<std::string> scans = {"neghip_64x64x64_uint8.raw"};
  if (!quick) {
    scans.push_back("fuel_64x64x64_uint8.raw");
    scans.push_back("bonsai.nrrd");
  }
  std::vector<std::string> missing;
  std::vector<std::filesystem::path> scanPaths;
  for (const std::string& name : scans) {
    const auto path = ctx.dataFile(name);
    if (path.empty())
      missing.push_back(name);
    else
      scanPaths.push_back(path);
  }
  for (const auto& v : ctx.options().volumes) scanPaths.emplace_back(v);
  for (const auto& path : scanPaths) {
    const std::string name = path.filename().string();
    StructuredGrid grid;
    try {
      grid = loadStructuredVolume(path.string());
    } catch (const std::exception& e) {
      report.skipInput(path.string(), e.what());
      continue;
    }
    ctx.log("denoise: " + name + ": fitting");
    EncodeOptions o;
    if (isIntegerSampleType(grid.sampleType)) o.coding.coder = ControlCoder::kZfp;  // as encode
    // Wall time of each encode (the report's fit time leaves out the dequantize iterations).
    double seconds[3] = {0.0, 0.0, 0.0};
    auto timed = [&](int k, const EncodeOptions& options, FitReport* fit) {
      const double start = ctx.elapsedSeconds();
      Model m = encodeStructured(grid, options, fit);
      seconds[k] = ctx.elapsedSeconds() - start;
      return m;
    };
    FitReport plainReport;
    const Model interpolating = timed(0, o, &plainReport);
    o.autoSmoothing = true;
    FitReport r;
    const Model smooth = timed(1, o, &r);
    std::optional<Model> dequantized;
    FitReport dr;
    if (isIntegerSampleType(grid.sampleType)) {
      EncodeOptions d = o;
      d.autoSmoothing = false;
      d.dequantizeStep = 0.0;
      ctx.log("denoise: " + name + ": --dequantize");
      dequantized = timed(2, d, &dr);
    }
    const auto [lo, hi] = std::minmax_element(grid.values.begin(), grid.values.end());
    RenderSettings s =
        sceneSettings(image, image, grid.boxMin(), grid.boxMax(), 30.0, 20.0, "step:0.25", "white",
                      *lo, std::max<double>(*hi, *lo + 1e-12), grid.spacing, 0.5, ctx.threads());
    s.shade = true;
    SceneData scene;
    scene.grid = &grid;
    // Whole, and zoomed 3x on the centre (the terraces of a surface show there).
    std::vector<std::vector<Image8>> rowsOfCells;
    ctx.log("denoise: " + name + ": rendering");
    for (const double zoom : {1.0, 3.0}) {
      RenderSettings z = s;
      z.camera.zoom(zoom);
      std::vector<Image8> cells;
      MethodSpec tri;
      tri.method = ReconstructionMethod::Trilinear;
      const std::string zoomText = zoom > 1.0 ? "zoom 3" : "";
      cells.push_back(withCaption(renderOurs(scene, tri, z).image, {"trilinear", zoomText}, 2));
      MethodSpec mfa;
      mfa.method = ReconstructionMethod::Mfa;
      scene.model = &interpolating;
      cells.push_back(
          withCaption(renderOurs(scene, mfa, z).image, {"mfa (interpolating)", zoomText}, 2));
      scene.model = &smooth;
      cells.push_back(withCaption(renderOurs(scene, mfa, z).image,
                                  {"mfa --smooth auto", "lambda " + lambdaText(r.smoothing)}, 2));
      if (dequantized) {
        scene.model = &*dequantized;
        cells.push_back(
            withCaption(renderOurs(scene, mfa, z).image, {"mfa --dequantize", zoomText}, 2));
      }
      rowsOfCells.push_back(std::move(cells));
    }
    const std::string stem = std::filesystem::path(name).stem().string();
    report.files.push_back(
        ctx.writeImage("denoise/scan_" + stem + ".png", montageGrid(rowsOfCells)));
    md += "- `" + name + "`: " + r.smoothingNote + "; `denoise/scan_" + stem +
          ".png` (trilinear, interpolating MFA, smoothed MFA" +
          std::string(dequantized ? ", dequantized MFA" : "") +
          "; opacity step at 0.25 of the range, shaded; below: zoomed 3x). Bits/sample: "
          "interpolating " +
          fixed(plainReport.bitsPerSample(), 2) + ", smoothed " + fixed(r.bitsPerSample(), 2);
    if (dequantized)
      md += ", dequantized " + fixed(dr.bitsPerSample(), 2) + " (" +
            std::to_string(dr.dequantizeIterations) + " iterations" +
            (dr.dequantizeConverged ? "" : ", not converged") + ", max |model - sample| " +
            fixed(dr.maxError, 3) + ")";
    md += "; encode " + fixed(seconds[0], 2) + " s / " + fixed(seconds[1], 2) + " s" +
          (dequantized ? " / " + fixed(seconds[2], 2) + " s" : std::string()) + ".\n";
  }
  md += ctx.missingDataNote(missing);
  md +=
      "\nImages: `denoise/FUNCTION_N_DEGRADATION_METHOD.png`, montages "
      "`denoise/FUNCTION_montage.png` (" +
      std::string(quick ? "41" : "64") +
      "^3; columns: truth, then trilinear, catmull-rom, bspline, mfa, mfa-lsq, mfa-auto, "
      "mfa-best; one row per degradation).\n";
  return report;
}

}  // namespace mfadvr::eval
