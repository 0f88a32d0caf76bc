// MFA parameter study on rendering quality (paper Fig. 10, section 4.2.3): Marschner-Lobb on a
// 256^3 grid (the paper's size) encoded with control counts from an eighth of the samples to all
// of them and degrees 1 to 4, each model rendered in Table 2's scene (value and gradient from the
// model) and compared with the truth.
#include <algorithm>
#include <map>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/Encoder.h"
#include "eval/CsvTable.h"
#include "eval/EvalRendering.h"
#include "eval/Experiment.h"

namespace mfadvr::eval {

ExperimentReport runParameterQuality(const EvalContext& ctx) {
  const int n = ctx.quick() ? 64 : 256;
  const int image = ctx.quick() ? 128 : 384;
  const std::vector<int> ctrls = {n / 8, n / 4, n / 2, 3 * n / 4, n};
  const std::vector<int> degrees = {1, 2, 3, 4};
  const auto ml = makeBuiltin("marschner-lobb");
  const std::string gridName =
      std::to_string(n) + "x" + std::to_string(n) + "x" + std::to_string(n);
  ctx.log("parameter study (quality): sampling marschner-lobb on " + gridName);
  const StructuredGrid grid = sampleBuiltin(*ml, {n, n, n});
  RenderSettings s = sceneSettings(image, image, grid.boxMin(), grid.boxMax(), 30.0, 25.0,
                                   "step:0.5", "white", 0.0, 1.0, grid.spacing, 0.5, ctx.threads());
  s.sampleDistance = 0.25 * 2.0 / 63.0;  // Table 2's step
  s.shade = true;
  SceneData base;
  base.truth = ml.get();
  MethodSpec truthSpec;
  truthSpec.method = ReconstructionMethod::Truth;
  const Image8 truth = renderOurs(base, truthSpec, s).image;
  ctx.writeImage("params/truth.png", truth);

  CsvTable table(
      {"grid", "degree", "ctrl", "mse", "psnr", "ssim", "encode_seconds", "render_seconds"});
  std::map<std::pair<int, int>, double> psnr;  // (degree, ctrl)
  for (int p : degrees)
    for (int c : ctrls) {
      if (c < p + 1) continue;
      ctx.log("parameter study (quality): degree " + std::to_string(p) + ", " + std::to_string(c) +
              "^3 control points");
      EncodeOptions fit;
      fit.degree = {p, p, p};
      fit.controlCounts = {c, c, c};
      FitReport fitReport;
      const Model model = encodeStructured(grid, fit, &fitReport);
      SceneData scene;
      scene.model = &model;
      MethodSpec spec;
      spec.method = ReconstructionMethod::Mfa;
      const TimedImage r = renderOurs(scene, spec, s);
      ctx.writeImage("params/p" + std::to_string(p) + "_n" + std::to_string(c) + ".png", r.image);
      const ImageComparison m = compareImages(truth, r.image);
      psnr[{p, c}] = m.psnr;
      table.addRow({gridName, std::to_string(p), std::to_string(c), csvNumber(m.mse),
                    csvNumber(m.psnr), csvNumber(m.ssim), csvNumber(fitReport.seconds),
                    csvNumber(r.seconds)});
    }
  table.write(ctx.path("fig10_param_quality.csv").string());

  ExperimentReport report;
  report.files = {"fig10_param_quality.csv"};
  std::string& md = report.markdown;
  md += "Settings: `marschner-lobb` sampled on " + gridName +
        ", encoded at degree p = 1..4 with N/8 ... N control points per axis (N = " +
        std::to_string(n) +
        "); each model in "
        "Table 2's scene (" +
        std::to_string(image) + "x" + std::to_string(image) + ", step " +
        csvNumber(s.sampleDistance, 4) + ") against the truth.\n\n";
  md += "PSNR (dB), rows degree, columns control points per axis:\n\n";
  md +=
      degreeByControlsTable(degrees, ctrls,
                            [&](int p, int c) {
                              return psnr.count({p, c}) ? fixed(psnr[{p, c}], 2) : std::string("-");
                            }) +
      "\n";
  auto at = [&](int p, int c) { return psnr.count({p, c}) ? psnr[{p, c}] : -1e300; };
  md += "Compared with the paper:\n\n";
  {
    int falling = 0;
    for (int p : degrees) falling += at(p, ctrls.back()) > at(p, ctrls.front());
    md += paperBullet(falling == int(degrees.size()),
                      "Fewer control points give lower quality: PSNR with " +
                          std::to_string(ctrls.front()) + "^3 control points is below that with " +
                          std::to_string(ctrls.back()) + "^3 for " + std::to_string(falling) +
                          " of " + std::to_string(degrees.size()) + " degrees.");
  }
  {
    int linearWorse = 0;
    for (int c : ctrls) linearWorse += at(1, c) < std::max(at(2, c), at(3, c));
    md += paperBullet(linearWorse == int(ctrls.size()),
                      "Degree 1 is suboptimal: below the better of degrees 2 and 3 at " +
                          std::to_string(linearWorse) + " of " + std::to_string(ctrls.size()) +
                          " control counts (a degree-1 model is trilinear interpolation of its "
                          "control points).");
  }
  {
    double best = -1e300;
    for (const auto& [key, v] : psnr) best = std::max(best, v);
    const double halfBest = std::max(at(2, n / 2), at(3, n / 2));
    md += paperBullet(
        halfBest >= best - 1.0,
        "Half the samples per axis with degree 2 or 3 (the paper's recommendation) "
        "gives " +
            fixed(halfBest, 2) + " dB, against the study's best " + fixed(best, 2) + " dB" +
            (halfBest >= best - 1.0 ? ": within 1 dB, so it works well here too."
                                    : ": more than 1 dB short; at this grid the function's ripples "
                                      "need more control points than half the samples."));
  }
  {
    const bool runge = at(4, n) < at(3, n);
    md += paperBullet(runge,
                      "At n = samples, degree 4 (" + fixed(at(4, n), 2) + " dB) " +
                          (runge ? "falls below" : "does not fall below") + " degree 3 (" +
                          fixed(at(3, n), 2) + " dB)" +
                          (runge ? ", the paper's Runge-like overfitting at the boundary."
                                 : ": the boundary oscillation of the paper's Fig. 14 does not "
                                   "show in this scene at this grid."));
  }
  md += "\nImages: `params/pP_nN.png` and `params/truth.png`.\n";
  return report;
}

}  // namespace mfadvr::eval
