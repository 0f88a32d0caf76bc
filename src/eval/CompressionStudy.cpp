// Compact models (beyond the paper, which names compression as future work): rate-distortion of
// coded MFA models against ZFP and downsampling at equal bytes (docs/compression.md).
//
// Per volume and rate B (bits per input sample): the MFA coded to the budget (`encode
// --bits-per-sample B`); an uncoded least-squares MFA with as many float32 control points as the
// coded model's bytes hold; ZFP fixed-rate at the coded model's rate and ZFP fixed-accuracy with
// the smallest tolerance whose stream fits its bytes, both on the samples; the volume resampled
// (cubic) to as many samples of its own type as those bytes hold. Every method is measured at
// every input sample (volume PSNR over the value range) and rendered through the same ray caster
// with the same transfer function in data units: grids (ZFP's decoded samples, the downsampled
// grid) through their interpolating cubic model, the reference through the full data's.
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRTAnalyticSource.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/CodingChoice.h"
#include "core/encode/Encoder.h"
#include "core/model/ModelFile.h"
#include "core/model/ZfpArray.h"
#include "core/util/Error.h"
#include "eval/CsvTable.h"
#include "eval/EvalRendering.h"
#include "eval/Experiment.h"
#include "io/VolumeLoader.h"

namespace mfadvr::eval {
namespace {

struct StudyVolume {
  std::string name;
  StructuredGrid grid;
};

// VTK's Wavelet source (vtkRTAnalyticSource with its defaults) on n^3 samples: the smooth test
// field every VTK user knows.
StructuredGrid waveletGrid(int n) {
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(0, n - 1, 0, n - 1, 0, n - 1);
  source->Update();
  vtkDataArray* values = source->GetOutput()->GetPointData()->GetScalars();
  StructuredGrid g;
  g.dims = {n, n, n};
  g.spacing = Vec3d::Ones();
  g.origin = Vec3d::Zero();
  g.source = "vtkRTAnalyticSource";
  g.fieldName = "RTData";
  g.sampleType = "float32";
  g.values.resize(static_cast<size_t>(n) * n * n);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i) g.values[i] = values->GetTuple1(i);
  g.inputBytes = static_cast<std::int64_t>(g.values.size()) * 4;
  return g;
}

int bytesPerSample(const std::string& type) {
  if (type == "uint8" || type == "int8") return 1;
  if (type == "uint16" || type == "int16") return 2;
  if (type == "float64" || type == "int64" || type == "uint64") return 8;
  return 4;
}

std::pair<double, double> valueRangeOf(const StructuredGrid& g) {
  const auto [lo, hi] = std::minmax_element(g.values.begin(), g.values.end());
  return {*lo, *hi};
}

double volumePsnr(const StructuredGrid& ref, std::span<const double> values) {
  double sumSq = 0.0;
  for (size_t i = 0; i < values.size(); ++i) {
    const double d = values[i] - ref.values[i];
    sumSq += d * d;
  }
  const auto [lo, hi] = valueRangeOf(ref);
  return psnrOf(hi - lo, std::sqrt(sumSq / static_cast<double>(values.size())));
}

// The grid `like` with other values, or another sample count over the same box.
StructuredGrid gridLike(const StructuredGrid& like, const Index3& dims,
                        std::vector<double> values) {
  StructuredGrid g = like;
  g.dims = dims;
  for (int a = 0; a < 3; ++a)
    g.spacing[a] =
        like.spacing[a] * static_cast<double>(like.dims[a] - 1) / static_cast<double>(dims[a] - 1);
  g.values.assign(values.begin(), values.end());
  return g;
}

Model interpolatingModel(const StructuredGrid& g) {
  return encodeStructured(g, EncodeOptions{});
}

struct Result {
  std::string method;
  std::int64_t bytes = 0;
  double volumePsnr = 0.0;
  std::int64_t memoryBytes = 0;  // what the renderer holds: control points or a float grid
  Image8 image;
};

std::string label(const std::string& method) {
  static const std::map<std::string, std::string> names = {
      {"mfa-coded", "MFA, coded to the budget"},
      {"mfa-ls-float32", "MFA least squares, float32"},
      {"zfp-rate", "ZFP fixed-rate"},
      {"zfp-accuracy", "ZFP fixed-accuracy"},
      {"downsampled-cubic", "downsampled + cubic"}};
  return names.at(method);
}

}  // namespace

ExperimentReport runCompressionStudy(const EvalContext& ctx) {
  const bool quick = ctx.quick();
  const int image = quick ? 96 : 256;
  const std::vector<double> rates =
      quick ? std::vector<double>{0.5, 1, 2} : std::vector<double>{0.25, 0.5, 1, 2, 4, 8};
  ExperimentReport report;
  std::vector<StudyVolume> volumes;
  const int ml = quick ? 32 : 64;
  volumes.push_back({"marschner-lobb " + std::to_string(ml) + "^3",
                     sampleBuiltinSpec("builtin:marschner-lobb:" + std::to_string(ml))});
  volumes.back().grid.sampleType = "float32";  // stored as float32 like the other float fields
  volumes.back().grid.inputBytes = volumes.back().grid.sampleCount() * 4;
  if (!quick) volumes.push_back({"wavelet 128^3", waveletGrid(128)});
  std::vector<std::string> files = {"fuel_64x64x64_uint8.raw", "nucleon_41x41x41_uint8.raw"};
  if (!quick)
    files = {"fuel_64x64x64_uint8.raw", "neghip_64x64x64_uint8.raw", "nucleon_41x41x41_uint8.raw",
             "bonsai.nrrd"};
  std::vector<std::string> missing;
  for (const auto& f : files) {
    const auto path = ctx.dataFile(f);
    if (path.empty()) {
      missing.push_back(f);
      continue;
    }
    volumes.push_back({f, loadStructuredVolume(path.string(), {})});
  }
  for (const auto& v : ctx.options().volumes) {
    try {
      volumes.push_back({v, loadStructuredVolume(v, {})});
    } catch (const std::exception& e) {
      report.skipInput(v, e.what());
    }
  }

  CsvTable table({"volume", "rate", "method", "bits_per_sample", "volume_psnr", "image_psnr",
                  "image_ssim", "memory_bytes"});
  std::string& md = report.markdown;
  md += "Settings: rates " +
        [&] {
          std::string s;
          for (double r : rates) s += (s.empty() ? "" : ", ") + csvNumber(r, 3);
          return s;
        }() +
        " bits per input sample; images " + std::to_string(image) + "x" + std::to_string(image) +
        ", shaded, ramp opacity over the full data's value range (data units, the same for "
        "every method), compared with the full data's interpolating model rendered the same "
        "way. Volume PSNR: value range over the RMS error at every input sample. Memory: what "
        "the renderer holds (control points, or the decoded float grid).\n\n";
  if (!missing.empty()) md += ctx.missingDataNote(missing) + "\n\n";

  int mfaAheadOfAccuracy = 0, mfaAheadOfRate = 0, mfaAheadOfDown = 0, points = 0;
  for (const StudyVolume& v : volumes) {
    const StructuredGrid& g = v.grid;
    const auto [vmin, vmax] = valueRangeOf(g);
    const double samples = static_cast<double>(g.sampleCount());
    RenderSettings s = sceneSettings(image, image, g.boxMin(), g.boxMax(), 30.0, 25.0, "ramp",
                                     "viridis", vmin, vmax, g.spacing, 0.5, ctx.threads());
    s.shade = true;
    ctx.log("compression: " + v.name + ": reference");
    const Model full = interpolatingModel(g);
    auto render = [&](const Model& m) {
      SceneData scene;
      scene.model = &m;
      MethodSpec spec;
      spec.method = ReconstructionMethod::Mfa;
      return renderOurs(scene, spec, s).image;
    };
    const Image8 reference = render(full);
    const std::string stem = "compression/" + [&] {
      std::string n;
      for (char c : v.name) n += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return n;
    }();
    report.files.push_back(ctx.writeImage(stem + "_reference.png", reference));
    const std::vector<float> samplesF(g.values.begin(), g.values.end());
    md += "### " + v.name +
          "\n\n| rate | method | bits/sample | volume PSNR | image PSNR | image "
          "SSIM | memory |\n|---|---|---|---|---|---|---|\n";
    for (double rate : rates) {
      ctx.log("compression: " + v.name + " at " + csvNumber(rate, 3) + " bits/sample");
      std::vector<Result> results;
      // MFA coded to the budget.
      EncodeOptions budget;
      budget.coding.budget = {BudgetKind::kBitsPerSample, rate};
      Model coded;
      try {
        coded = encodeStructured(g, budget);
      } catch (const Error&) {
        md += "| " + csvNumber(rate, 3) + " | all | no MFA model within the budget | | | | |\n";
        continue;
      }
      const std::int64_t bytes = modelFileSize(coded);
      results.push_back({"mfa-coded", bytes, volumePsnr(g, splineOnGrid(coded.spline(), g.dims)),
                         static_cast<std::int64_t>(coded.spline().controlPoints().size()) * 4,
                         render(coded)});
      // Uncoded least squares in the same bytes.
      {
        EncodeOptions ls;
        const double share = std::min(1.0, static_cast<double>(bytes) / 4.0 / samples);
        for (int a = 0; a < 3; ++a)
          ls.controlCounts[a] = std::clamp<std::int64_t>(
              std::llround(static_cast<double>(g.dims[a]) * std::cbrt(share)), 4, g.dims[a]);
        ls.coding.coder = ControlCoder::kFloat32;
        const Model m = encodeStructured(g, ls);
        results.push_back(
            {"mfa-ls-float32", modelFileSize(m), volumePsnr(g, splineOnGrid(m.spline(), g.dims)),
             static_cast<std::int64_t>(m.spline().controlPoints().size()) * 4, render(m)});
      }
      // ZFP on the samples, decoded and rendered through their interpolating model.
      auto zfpResult = [&](const std::string& method, const std::string& stream,
                           const ZfpSettings& z) {
        const std::vector<float> back =
            zfpDecompress(std::span<const std::uint8_t>(
                              reinterpret_cast<const std::uint8_t*>(stream.data()), stream.size()),
                          g.dims, z);
        const std::vector<double> values(back.begin(), back.end());
        const Model m = interpolatingModel(gridLike(g, g.dims, values));
        results.push_back({method, static_cast<std::int64_t>(stream.size()), volumePsnr(g, values),
                           static_cast<std::int64_t>(samples) * 4, render(m)});
      };
      const double fileRate = 8.0 * static_cast<double>(bytes) / samples;
      {
        const ZfpSettings z{ZfpSettings::Mode::kRate, fileRate};
        zfpResult("zfp-rate", zfpCompress(samplesF, g.dims, z), z);
      }
      {
        // The smallest power-of-two tolerance whose stream fits the coded model's bytes.
        const double range = std::max(vmax - vmin, 1e-30);
        std::string best;
        ZfpSettings bestSettings;
        for (int k = -30; k <= 10 && best.empty(); ++k) {
          const ZfpSettings z{ZfpSettings::Mode::kAccuracy, range * std::ldexp(1.0, k)};
          std::string stream = zfpCompress(samplesF, g.dims, z);
          if (static_cast<std::int64_t>(stream.size()) <= bytes) {
            best = std::move(stream);
            bestSettings = z;
          }
        }
        if (!best.empty()) zfpResult("zfp-accuracy", best, bestSettings);
      }
      // Downsampled: as many samples of the input's type as the bytes hold, cubic both ways.
      {
        const double share =
            std::min(1.0, static_cast<double>(bytes) / bytesPerSample(g.sampleType) / samples);
        Index3 small{};
        for (int a = 0; a < 3; ++a)
          small[a] = std::clamp<std::int64_t>(
              std::llround(static_cast<double>(g.dims[a]) * std::cbrt(share)), 4, g.dims[a]);
        std::vector<double> values = splineOnGrid(full.spline(), small);
        if (isIntegerSampleType(g.sampleType))
          for (double& x : values) x = std::clamp(std::round(x), vmin, vmax);
        const std::int64_t count = small[0] * small[1] * small[2];
        const Model m = interpolatingModel(gridLike(g, small, std::move(values)));
        results.push_back({"downsampled-cubic", count * bytesPerSample(g.sampleType),
                           volumePsnr(g, splineOnGrid(m.spline(), g.dims)), count * 4, render(m)});
      }
      double mfa = 0.0;
      std::map<std::string, double> psnrs;
      for (const Result& r : results) {
        const ImageComparison c = compareImages(reference, r.image);
        const double bits = 8.0 * static_cast<double>(r.bytes) / samples;
        psnrs[r.method] = r.volumePsnr;
        if (r.method == "mfa-coded") mfa = r.volumePsnr;
        table.addRow({v.name, csvNumber(rate, 3), r.method, csvNumber(bits),
                      csvNumber(r.volumePsnr), csvNumber(c.psnr), csvNumber(c.ssim),
                      std::to_string(r.memoryBytes)});
        md += "| " + csvNumber(rate, 3) + " | " + label(r.method) + " | " + fixed(bits, 3) + " | " +
              fixed(r.volumePsnr, 2) + " | " + fixed(c.psnr, 2) + " | " + fixed(c.ssim, 4) + " | " +
              csvNumber(static_cast<double>(r.memoryBytes) / 1e6, 3) + " MB |\n";
        if (rate == 1.0)
          report.files.push_back(ctx.writeImage(stem + "_" + r.method + "_1bps.png", r.image));
      }
      ++points;
      mfaAheadOfRate += mfa >= psnrs["zfp-rate"];
      mfaAheadOfDown += mfa >= psnrs["downsampled-cubic"];
      mfaAheadOfAccuracy += !psnrs.count("zfp-accuracy") || mfa >= psnrs["zfp-accuracy"];
    }
    md += "\n";
  }
  table.write(ctx.path("compression_rd.csv").string());
  report.files.push_back("compression_rd.csv");
  md += "Over " + std::to_string(points) +
        " volume-rate pairs, the coded MFA's volume PSNR is at "
        "least ZFP fixed-rate's in " +
        std::to_string(mfaAheadOfRate) + ", downsampling's in " + std::to_string(mfaAheadOfDown) +
        " and ZFP fixed-accuracy's in " + std::to_string(mfaAheadOfAccuracy) +
        " (counting the rates where fixed-accuracy cannot make a stream that small).\n\n";
  return report;
}

}  // namespace mfadvr::eval
