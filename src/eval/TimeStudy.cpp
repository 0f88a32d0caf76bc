// `mfadvr eval time`: one 4-D model of a time series against interpolating its steps in time
// (docs/time-varying.md). The built-in orbiting-blobs, sampled at 8, 16 and 32 steps over one
// orbit: at the times halfway between steps (where no step was stored) the 4-D model, the linear
// interpolation of the two neighbouring steps (ParaView's Temporal Interpolator) and the nearest
// step are compared with the analytic field, at the grid's samples (value PSNR: every method is
// exact in space there, so only time differs) and in images (each instant encoded into the same
// interpolating 3-D model and rendered with one ray caster and camera). Size: the zfp-coded 4-D
// model against per-step zfp-coded 3-D models and ZFP's 4-D fixed-accuracy mode on the samples,
// over a range of tolerances.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "core/analytic/BuiltinSeries.h"
#include "core/encode/Encoder.h"
#include "core/encode/FitReport.h"
#include "core/encode/TimeSeriesEncoder.h"
#include "core/image/Montage.h"
#include "core/model/ControlCoding.h"
#include "core/model/ModelFile.h"
#include "core/model/ZfpArray.h"
#include "eval/CsvTable.h"
#include "eval/EvalRendering.h"
#include "eval/Experiment.h"

namespace mfadvr::eval {
namespace {

std::vector<double> evenTimes(int steps) {
  std::vector<double> t(static_cast<size_t>(steps));
  for (int s = 0; s < steps; ++s) t[static_cast<size_t>(s)] = static_cast<double>(s) / (steps - 1);
  return t;
}

struct SquaredErrors {
  double sum = 0.0;
  std::int64_t count = 0;
  void add(const std::vector<float>& a, const std::vector<float>& truth) {
    for (size_t i = 0; i < a.size(); ++i) {
      const double e = static_cast<double>(a[i]) - truth[i];
      sum += e * e;
    }
    count += static_cast<std::int64_t>(a.size());
  }
  void add(const std::vector<double>& a, const std::vector<float>& truth) {
    for (size_t i = 0; i < a.size(); ++i) {
      const double e = a[i] - truth[i];
      sum += e * e;
    }
    count += static_cast<std::int64_t>(a.size());
  }
  double psnr(double range) const {
    return psnrOf(range, std::sqrt(sum / static_cast<double>(std::max<std::int64_t>(count, 1))));
  }
};

}  // namespace

ExperimentReport runTimeStudy(const EvalContext& ctx) {
  ExperimentReport report;
  const bool quick = ctx.quick();
  const std::int64_t n = quick ? 24 : 48;
  const Index3 dims{n, n, n};
  const std::vector<int> stepCounts = quick ? std::vector<int>{8, 16} : std::vector<int>{8, 16, 32};
  const std::shared_ptr<const BuiltinSeriesFunction> f = makeBuiltinSeries("orbiting-blobs");
  std::ostringstream md;
  md << "The built-in `orbiting-blobs` (three Gaussian blobs circling the z axis once over t in "
        "[0, 1]; a blob moves 0.2 between two of 16 steps, its half width at half maximum is "
        "0.24) on "
     << n
     << "^3 samples, encoded as one 4-D model (cubic in space and time, interpolating "
        "every sample of every step). At the times halfway between steps, against the "
        "analytic field at the grid's samples: the 4-D model, the linear interpolation of "
        "the two neighbouring steps (ParaView's Temporal Interpolator) and the nearest step "
        "(value PSNR over the series' value range).\n\n";

  CsvTable values({"steps", "displacement_per_step", "psnr_4d", "psnr_linear", "psnr_nearest",
                   "gain_over_linear_db", "encode_seconds", "peak_bytes_per_sample"});
  for (int steps : stepCounts) {
    ctx.log("time: " + std::to_string(steps) + " steps: encoding");
    const BuiltinVolumeSeries series(f, dims, evenTimes(steps));
    FitReport fit;
    const TimeVaryingModel model =
        encodeTimeSeries(series, EncodeOptions(), TimeSeriesOptions(), &fit);
    const double range = fit.valueMax - fit.valueMin;
    SquaredErrors fourD, linear, nearest;
    StructuredGrid previous = series.load(0);
    for (int s = 0; s + 1 < steps; ++s) {
      const StructuredGrid next = series.load(s + 1);
      const double t = 0.5 * (series.time(s) + series.time(s + 1));
      const StructuredGrid truth = series.sampleAt(t);
      fourD.add(splineOnGrid(model.at(t).spline(), dims), truth.values);
      std::vector<float> lerp(previous.values.size());
      for (size_t i = 0; i < lerp.size(); ++i)
        lerp[i] = 0.5f * (previous.values[i] + next.values[i]);
      linear.add(lerp, truth.values);
      nearest.add(previous.values, truth.values);
      previous = next;
    }
    // A blob's centre moves 2 pi 0.5 / (steps - 1) along its orbit (and bobs) per step.
    const double displacement = 2.0 * 3.14159265358979 * std::hypot(0.5, 0.3) / (steps - 1);
    values.addRow({std::to_string(steps), csvNumber(displacement, 3),
                   csvNumber(fourD.psnr(range), 4), csvNumber(linear.psnr(range), 4),
                   csvNumber(nearest.psnr(range), 4),
                   csvNumber(fourD.psnr(range) - linear.psnr(range), 3), csvNumber(fit.seconds, 3),
                   csvNumber(static_cast<double>(4 * model.controlPoints().size() +
                                                 4 * dims[0] * dims[1] * dims[2]) /
                                 static_cast<double>(steps * dims[0] * dims[1] * dims[2]),
                             3)});
  }
  values.write(ctx.path("time/halfway_values.csv").string());
  report.files.push_back("time/halfway_values.csv");
  md << values.toMarkdown({"steps", "displacement_per_step", "psnr_4d", "psnr_linear",
                           "psnr_nearest", "gain_over_linear_db"},
                          {"steps", "blob moves per step", "4-D model dB", "linear dB",
                           "nearest dB", "4-D over linear dB"})
     << "\n";

  // Images at the instant halfway between steps 3 and 4 of the 16-step series.
  {
    const int steps = 16;
    const BuiltinVolumeSeries series(f, dims, evenTimes(steps));
    ctx.log("time: images");
    const TimeVaryingModel model = encodeTimeSeries(series, EncodeOptions(), TimeSeriesOptions());
    const double t = 0.5 * (series.time(3) + series.time(4));
    const StructuredGrid a = series.load(3), b = series.load(4);
    StructuredGrid lerp = a;
    for (size_t i = 0; i < lerp.values.size(); ++i)
      lerp.values[i] = 0.5f * (a.values[i] + b.values[i]);
    const Model instant = model.at(t);
    const Model linearModel = encodeStructured(lerp, EncodeOptions());
    const Model nearestModel = encodeStructured(a, EncodeOptions());
    const auto truthFunction = builtinAtTime(f, t, dims);
    const int size = quick ? 128 : 384;
    RenderSettings s = sceneSettings(size, size, a.boxMin(), a.boxMax(), 30.0, 25.0, "step:0.5",
                                     "white", model.first().valueMin(), model.first().valueMax(),
                                     a.spacing, 0.5, ctx.threads());
    s.shade = true;
    SceneData scene;
    scene.truth = truthFunction.get();
    scene.differenceStep = a.spacing;
    MethodSpec truthSpec;
    truthSpec.method = ReconstructionMethod::Truth;
    const Image8 truth = renderOurs(scene, truthSpec, s).image;
    MethodSpec mfa;
    mfa.method = ReconstructionMethod::Mfa;
    CsvTable images({"method", "image_psnr", "image_ssim"});
    std::vector<Image8> row = {truth};
    for (const auto& [name, m] : {std::pair<std::string, const Model*>{"4d", &instant},
                                  {"linear", &linearModel},
                                  {"nearest", &nearestModel}}) {
      SceneData sc = scene;
      sc.model = m;
      const Image8 img = renderOurs(sc, mfa, s).image;
      const ImageComparison c = compareImages(truth, img);
      images.addRow({name, csvNumber(c.psnr, 4), csvNumber(c.ssim, 4)});
      report.files.push_back(ctx.writeImage("time/halfway_" + name + ".png", img));
      row.push_back(img);
    }
    report.files.push_back(ctx.writeImage("time/halfway_truth.png", truth));
    report.files.push_back(ctx.writeImage("time/halfway_montage.png", montageHorizontal(row)));
    images.write(ctx.path("time/halfway_images.csv").string());
    report.files.push_back("time/halfway_images.csv");
    md << "Rendered at t = " << fixed(t, 4)
       << " (halfway between steps 3 and 4 of 16), shaded, the isosurface-like step transfer "
          "function at half the range; each instant encoded into the same interpolating cubic "
          "3-D model and rendered by the same ray caster, against the analytic field "
          "(`time/halfway_montage.png`: truth, 4-D model, linear, nearest):\n\n"
       << images.toMarkdown({"method", "image_psnr", "image_ssim"},
                            {"method", "image PSNR dB", "SSIM"})
       << "\n";
  }

  // Size: coded 4-D models vs coded 3-D models per step vs ZFP 4-D on the samples, on the
  // finest series (consecutive steps most alike).
  {
    const int steps = stepCounts.back();
    const BuiltinVolumeSeries series(f, dims, evenTimes(steps));
    ctx.log("time: sizes, " + std::to_string(steps) + " steps");
    std::vector<float> all;
    std::vector<StructuredGrid> grids;
    for (int st = 0; st < steps; ++st) {
      grids.push_back(series.load(st));
      all.insert(all.end(), grids.back().values.begin(), grids.back().values.end());
    }
    const auto [lo, hi] = std::minmax_element(all.begin(), all.end());
    const double range = static_cast<double>(*hi) - *lo;
    const double samples = static_cast<double>(all.size());
    struct Point {
      double bits, psnr;
    };
    std::map<std::string, std::vector<Point>> curves;
    CsvTable sizes({"method", "tolerance", "bytes", "bits_per_sample", "psnr_steps"});
    auto add = [&](const std::string& method, double tol, std::int64_t bytes, double psnr) {
      const double bits = 8.0 * static_cast<double>(bytes) / samples;
      sizes.addRow({method, csvNumber(tol, 3), std::to_string(bytes), csvNumber(bits, 4),
                    csvNumber(psnr, 4)});
      curves[method].push_back({bits, psnr});
    };
    const std::vector<int> timeCounts = {steps, steps / 2};
    for (double tol : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3}) {
      EncodeOptions coded;
      coded.coding.coder = ControlCoder::kZfp;
      coded.coding.tolerance = tol;
      for (int nt : timeCounts) {
        TimeSeriesOptions time;
        time.controlCount = nt;
        FitReport r4;
        encodeTimeSeries(series, coded, time, &r4);
        add("4d-model-" + std::to_string(nt), tol, r4.modelBytes, r4.psnr());
      }
      std::int64_t bytes3 = 0;
      SquaredErrors e3;
      for (const StructuredGrid& g : grids) {
        FitReport r3;
        const Model m3 = encodeStructured(g, coded, &r3);
        bytes3 += r3.modelBytes;
        e3.add(splineOnGrid(m3.spline(), dims), g.values);
      }
      add("3d-models", tol, bytes3, e3.psnr(range));
      const ZfpRoundTrip z = zfpRoundTrip(all, dims, {ZfpSettings::Mode::kAccuracy, tol}, steps);
      SquaredErrors ez;
      ez.add(z.decoded, all);
      add("zfp-4d", tol, static_cast<std::int64_t>(z.stream.size()), ez.psnr(range));
    }
    sizes.write(ctx.path("time/sizes.csv").string());
    report.files.push_back("time/sizes.csv");
    // Bits per sample of a method's curve at a PSNR inside it (linear in PSNR between points).
    auto bitsAt = [&](const std::string& method, double psnr) -> double {
      std::vector<Point> c = curves[method];
      std::sort(c.begin(), c.end(), [](const Point& a, const Point& b) { return a.psnr < b.psnr; });
      for (size_t i = 0; i + 1 < c.size(); ++i)
        if (psnr >= c[i].psnr && psnr <= c[i + 1].psnr) {
          const double w = (psnr - c[i].psnr) / (c[i + 1].psnr - c[i].psnr);
          return c[i].bits + w * (c[i + 1].bits - c[i].bits);
        }
      return std::nan("");
    };
    CsvTable equal({"model", "psnr", "bits_4d", "bits_3d_models", "ratio_to_3d", "bits_zfp_4d",
                    "ratio_to_zfp"});
    for (int nt : timeCounts) {
      const std::string name = "4d-model-" + std::to_string(nt);
      for (const Point& p : curves[name]) {
        const double b3 = bitsAt("3d-models", p.psnr), bz = bitsAt("zfp-4d", p.psnr);
        equal.addRow({name, csvNumber(p.psnr, 4), csvNumber(p.bits, 4), csvNumber(b3, 4),
                      csvNumber(p.bits / b3, 3), csvNumber(bz, 4), csvNumber(p.bits / bz, 3)});
      }
    }
    equal.write(ctx.path("time/equal_psnr.csv").string());
    report.files.push_back("time/equal_psnr.csv");
    md << "Size of a " << steps << "-step series (" << steps << " x " << n << "^3 float samples), "
       << "coded at each zfp tolerance: the 4-D model with as many time control points as steps "
          "(`4d-model-"
       << steps << "`) and with half as many (`4d-model-" << steps / 2
       << "`), each one 4-D zfp array; one interpolating 3-D model per step, each its own 3-D "
          "zfp array; ZFP's fixed-accuracy mode on the samples as one 4-D array. PSNR over every "
          "sample of every step (`time/sizes.csv`). At equal PSNR (the other methods' bits per "
          "sample interpolated linearly in PSNR between their points; empty outside their "
          "range):\n\n"
       << equal.toMarkdown(
              {"model", "psnr", "bits_4d", "bits_3d_models", "ratio_to_3d", "bits_zfp_4d",
               "ratio_to_zfp"},
              {"4-D model", "PSNR dB", "bits/sample", "3-D models", "ratio", "ZFP 4-D", "ratio"})
       << "\n";
  }
  report.markdown = md.str();
  return report;
}

}  // namespace mfadvr::eval
