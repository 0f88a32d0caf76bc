#include "core/model/TimeVaryingModel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/analytic/BuiltinSeries.h"
#include "core/encode/StructuredEncoder.h"
#include "core/encode/TimeSeriesEncoder.h"
#include "core/model/ModelFile.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/RayCaster.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// A polynomial of degree 2 in x, y, z and 3 in t: a cubic-in-time model with spatial degree >= 2
// reproduces it from any samples that determine it.
class Polynomial final : public BuiltinSeriesFunction {
 public:
  std::string name() const override { return "polynomial"; }
  Index3 defaultDims() const override { return {10, 9, 8}; }
  int defaultSteps() const override { return 7; }
  double value(const Vec3d& p, double t, Vec3d* g, double* rate) const override {
    const double x = p[0], y = p[1], z = p[2];
    const double s = 0.5 + x * y - 0.3 * z * z + 0.2 * y;
    const double q = 1.0 + 0.5 * t - 0.8 * t * t + 0.6 * t * t * t;
    if (g) *g = Vec3d(y * q + 0.4 * t * x, (x + 0.2) * q, -0.6 * z * q);
    if (rate) *rate = s * (0.5 - 1.6 * t + 1.8 * t * t) + 0.2 * x * x;
    return s * q + 0.2 * t * x * x;
  }
};

// Steps at uneven times, on a 10 x 9 x 8 grid.
BuiltinVolumeSeries polynomialSeries(std::vector<double> times = {0.0, 0.1, 0.35, 0.4, 0.7, 0.85,
                                                                  1.0}) {
  return BuiltinVolumeSeries(std::make_shared<Polynomial>(), {10, 9, 8}, std::move(times));
}

EncodeOptions spatialOptions() {
  EncodeOptions o;
  o.degree = {3, 3, 3};
  o.controlCounts = {6, 5, 5};
  return o;
}

TEST(TimeVarying, APolynomialInSpaceAndTimeIsReproducedAtAnyTime) {
  const BuiltinVolumeSeries series = polynomialSeries();
  TimeSeriesOptions time;
  time.controlCount = 5;  // fewer than the 7 steps: a least-squares fit in time
  FitReport report;
  const TimeVaryingModel m = encodeTimeSeries(series, spatialOptions(), time, &report);
  ASSERT_TRUE(m.hasTime());
  EXPECT_EQ(m.timeAxis().controlCount(), 5);
  EXPECT_EQ(m.timeAxis().degree(), 3);
  EXPECT_EQ(report.timeSteps, 7);
  EXPECT_LT(report.maxError, 1e-4);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0), ut(0.0, 1.0);
  std::vector<Vec3d> points;
  std::vector<double> times;
  for (int i = 0; i < 400; ++i) {
    points.emplace_back(u(rng), u(rng), u(rng));
    times.push_back(ut(rng));
  }
  std::vector<float> values(points.size()), rates(points.size());
  std::vector<Vec3f> gradients(points.size());
  m.evaluate(points, times, values, gradients, rates);
  for (size_t i = 0; i < points.size(); ++i) {
    Vec3d g;
    double rate = 0.0;
    const double truth = series.function().value(points[i], times[i], &g, &rate);
    ASSERT_NEAR(values[i], truth, 2e-4) << "at t = " << times[i];
    ASSERT_NEAR(rates[i], rate, 5e-3);
    for (int a = 0; a < 3; ++a) ASSERT_NEAR(gradients[i][a], g[a], 2e-3);
  }
}

TEST(TimeVarying, TheContractionAgreesWithTheFourDimensionalEvaluation) {
  const TimeVaryingModel m =
      encodeTimeSeries(BuiltinVolumeSeries("builtin:orbiting-blobs:12x12x12x6"), EncodeOptions(),
                       TimeSeriesOptions());
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    const Model instant = m.at(t);
    std::vector<Vec3d> points;
    for (int i = 0; i < 100; ++i) points.emplace_back(u(rng), u(rng), u(rng));
    std::vector<double> times(points.size(), t);
    std::vector<float> direct(points.size());
    m.evaluate(points, times, direct);
    for (size_t i = 0; i < points.size(); ++i)
      ASSERT_NEAR(instant.value(points[i]), direct[i], 1e-5) << "t = " << t;
  }
  // The model interpolates the steps: at a step's time it gives that step's samples.
  const BuiltinVolumeSeries series("builtin:orbiting-blobs:12x12x12x6");
  const StructuredGrid step = series.load(2);
  const Model at = m.at(series.time(2));
  for (std::int64_t k = 0; k < 12; k += 5)
    for (std::int64_t j = 0; j < 12; j += 3)
      for (std::int64_t i = 0; i < 12; ++i)
        ASSERT_NEAR(at.value(step.position(i, j, k)), step.at(i, j, k), 1e-4);
}

TEST(TimeVarying, FilesKeepTheTimeAxisAndThreeDimensionalFilesAreUnchanged) {
  const TimeVaryingModel m =
      encodeTimeSeries(polynomialSeries(), spatialOptions(), TimeSeriesOptions());
  std::uint32_t version = 0;
  for (const ControlCoder coder :
       {ControlCoder::kFloat32, ControlCoder::kLossless, ControlCoder::kZfp}) {
    TimeVaryingModel coded = m;
    std::vector<float> expected(m.controlPoints().begin(), m.controlPoints().end());
    if (coder != ControlCoder::kFloat32) {
      ControlCoding c{coder, 1e-3};
      const std::string bytes =
          encodeControlPoints(m.controlPoints(), m.first().spline().counts(), c, m.slabCount());
      expected =
          decodeControlPoints({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()},
                              m.first().spline().counts(), c, m.slabCount());
      // A zfp round trip keeps the control points within the tolerance.
      for (size_t i = 0; i < expected.size(); ++i)
        ASSERT_NEAR(expected[i], m.controlPoints()[i], 1e-3);
      coded = TimeVaryingModel(m.first(), m.timeAxis(), expected);
      coded.setControlCoding(c, std::make_shared<const std::string>(bytes));
    }
    const std::string file = serializeModel(coded);
    const std::vector<std::uint8_t> bytes(file.begin(), file.end());
    const TimeVaryingModel back = parseTimeVaryingModel(bytes, "m.mfa", &version);
    EXPECT_EQ(version, kTimeModelFormatVersion);
    ASSERT_TRUE(back.hasTime());
    EXPECT_EQ(back.timeAxis().steps, m.timeAxis().steps);
    EXPECT_EQ(back.timeAxis().knots, m.timeAxis().knots);
    EXPECT_EQ(back.controlCoding().coder, coder);
    EXPECT_EQ(std::vector<float>(back.controlPoints().begin(), back.controlPoints().end()),
              expected);
    // Written again, the same bytes.
    EXPECT_EQ(serializeModel(back), file);
    EXPECT_EQ(modelFileSize(back), static_cast<std::int64_t>(file.size()));
    // A 3-D reader sees the first step.
    const Model first = parseModel(bytes, "m.mfa");
    EXPECT_NEAR(first.value(Vec3d(0.1, 0.2, 0.3)), back.at(0.0).value(Vec3d(0.1, 0.2, 0.3)), 1e-6);
  }
  // A 3-D model through the time-varying writer: the version-3 bytes of the 3-D writer.
  const Model plain = m.at(0.5);
  const std::string three = serializeModel(TimeVaryingModel(plain));
  EXPECT_EQ(three, serializeModel(plain));
  const std::vector<std::uint8_t> b3(three.begin(), three.end());
  const TimeVaryingModel back3 = parseTimeVaryingModel(b3, "p.mfa", &version);
  EXPECT_EQ(version, kModelFormatVersion);
  EXPECT_FALSE(back3.hasTime());
}

TEST(TimeVarying, DamagedFourDimensionalFilesAreClearErrors) {
  const TimeVaryingModel m =
      encodeTimeSeries(polynomialSeries(), spatialOptions(), TimeSeriesOptions());
  const std::string file = serializeModel(m);
  std::mt19937 rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> b(file.begin(), file.end());
    if (trial % 2 == 0)
      b.resize(rng() % b.size());
    else
      b[rng() % b.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    EXPECT_THROW(parseTimeVaryingModel(b, "bad.mfa"), Error);
  }
}

TEST(TimeVarying, BadSeriesAreClearErrors) {
  auto message = [](const BuiltinVolumeSeries& s, const TimeSeriesOptions& t = {}) {
    try {
      encodeTimeSeries(s, spatialOptions(), t);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(polynomialSeries({0.0, 0.5, 0.4, 1.0})).find("must increase"),
            std::string::npos);
  EXPECT_NE(message(polynomialSeries({0.0, 0.5, 0.4, 1.0})).find("step 2"), std::string::npos);
  EXPECT_NE(message(polynomialSeries({0.0})).find("at least two steps"), std::string::npos);
  TimeSeriesOptions tooMany;
  tooMany.controlCount = 9;
  EXPECT_NE(message(polynomialSeries(), tooMany).find("--time-ctrl"), std::string::npos);
  TimeSeriesOptions badDegree;
  badDegree.degree = 0;
  EXPECT_NE(message(polynomialSeries(), badDegree).find("--time-degree"), std::string::npos);
  // Few steps lower the degree, with a note.
  std::vector<std::string> notes;
  const TimeVaryingModel two = encodeTimeSeries(polynomialSeries({0.0, 1.0}), spatialOptions(),
                                                TimeSeriesOptions(), nullptr, &notes);
  EXPECT_EQ(two.timeAxis().degree(), 1);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("lowered"), std::string::npos);
}

// A series whose steps do not share one grid.
class ShiftingGrid final : public VolumeSeries {
 public:
  int size() const override { return 3; }
  double time(int s) const override { return s; }
  std::string stepName(int s) const override { return "frame" + std::to_string(s) + ".nrrd"; }
  StructuredGrid load(int s) const override {
    StructuredGrid g;
    g.dims = {6, 6, s == 2 ? 7 : 6};
    g.values.assign(static_cast<size_t>(g.sampleCount()), 1.0f);
    g.sampleType = "float32";
    return g;
  }
  std::string source() const override { return "frame%d.nrrd"; }
};

TEST(TimeVarying, AStepOnAnotherGridIsNamed) {
  EncodeOptions o;
  o.controlCounts = {4, 4, 4};
  try {
    encodeTimeSeries(ShiftingGrid(), o, TimeSeriesOptions());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("frame2.nrrd has another grid"), std::string::npos)
        << e.what();
  }
}

// The polynomial series scaled by `scale` and rounded, as an 8-bit scan's steps are, with the
// clean field kept for comparisons.
class QuantizedPolynomial final : public VolumeSeries {
 public:
  explicit QuantizedPolynomial(double scale) : clean_(polynomialSeries()), scale_(scale) {}
  int size() const override { return clean_.size(); }
  double time(int s) const override { return clean_.time(s); }
  std::string stepName(int s) const override { return clean_.stepName(s); }
  std::string source() const override { return "quantized polynomial"; }
  StructuredGrid load(int s) const override { return quantized(clean_.load(s)); }
  StructuredGrid truthAt(double t) const {
    StructuredGrid g = clean_.sampleAt(t);
    for (float& v : g.values) v = static_cast<float>(scale_ * v);
    return g;
  }

 private:
  StructuredGrid quantized(StructuredGrid g) const {
    for (float& v : g.values) v = static_cast<float>(std::round(scale_ * v));
    g.sampleType = "uint8";
    return g;
  }
  BuiltinVolumeSeries clean_;
  double scale_;
};

TEST(TimeVarying, DequantizedSeriesRoundBackToEverySampleAndComeCloserToTheCleanField) {
  const QuantizedPolynomial series(8.0);  // about 20 levels over the range: coarse terraces
  EncodeOptions o;
  o.degree = {3, 3, 3};
  o.coding.coder = ControlCoder::kZfp;  // as `mfadvr encode` codes integer samples
  TimeSeriesOptions time;
  FitReport plainReport, report;
  const TimeVaryingModel plain = encodeTimeSeries(series, o, time, &plainReport);
  o.dequantizeStep = 0.0;  // the default step of integer samples: 1
  const TimeVaryingModel smooth = encodeTimeSeries(series, o, time, &report);
  EXPECT_EQ(report.encoder, "time-series-dequantize");
  EXPECT_EQ(report.dequantizeStep, 1.0);
  EXPECT_GT(report.dequantizeIterations, 0);
  EXPECT_GT(report.dequantizeEdgeShare, 0.0);
  EXPECT_EQ(report.coding, "zfp");
  // Within half a step of every sample of every step, on the model as stored: rounding gives the
  // samples back.
  EXPECT_LT(report.maxError, 0.5);
  for (int s = 0; s < series.size(); ++s) {
    const StructuredGrid step = series.load(s);
    const Model at = smooth.at(series.time(s));
    for (std::int64_t k = 0; k < step.dims[2]; ++k)
      for (std::int64_t j = 0; j < step.dims[1]; ++j)
        for (std::int64_t i = 0; i < step.dims[0]; ++i)
          ASSERT_EQ(std::round(at.value(step.position(i, j, k))), step.at(i, j, k))
              << "step " << s << " at " << i << "," << j << "," << k;
  }
  // Closer to the clean field than the interpolating model, at the steps and between them.
  for (double t : {series.time(2), 0.5 * (series.time(2) + series.time(3))}) {
    const StructuredGrid truth = series.truthAt(t);
    const double plainRms = errorsOnGrid(plain.at(t).spline(), truth).rms;
    const double smoothRms = errorsOnGrid(smooth.at(t).spline(), truth).rms;
    EXPECT_LT(smoothRms, 0.8 * plainRms) << "t = " << t;
  }
  // Only a model that interpolates in time keeps the bound; float samples need their step.
  TimeSeriesOptions fewer;
  fewer.controlCount = 4;
  EXPECT_THROW(encodeTimeSeries(series, o, fewer), Error);
  EncodeOptions floats = spatialOptions();
  floats.dequantizeStep = 0.0;
  try {
    encodeTimeSeries(polynomialSeries(), floats, TimeSeriesOptions());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("give the step"), std::string::npos) << e.what();
  }
}

TEST(TimeVarying, AutomaticSmoothingIsTheFitWithTheLambdaChosenOnTheMiddleStep) {
  const BuiltinVolumeSeries series("builtin:orbiting-blobs:16x16x16x5");
  EncodeOptions o;
  o.controlCounts = {10, 10, 10};
  o.autoSmoothing = true;
  FitReport report;
  const TimeVaryingModel chosen = encodeTimeSeries(series, o, TimeSeriesOptions(), &report);
  EXPECT_NE(report.smoothingNote.find("the middle step"), std::string::npos)
      << report.smoothingNote;
  EXPECT_GT(report.smoothing, 0.0);
  o.autoSmoothing = false;
  o.smoothing = report.smoothing;
  const TimeVaryingModel given = encodeTimeSeries(series, o, TimeSeriesOptions());
  const auto a = chosen.controlPoints(), b = given.controlPoints();
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]);
  o.autoSmoothing = true;
  EXPECT_THROW(encodeTimeSeries(series, o, TimeSeriesOptions()), Error);  // both
}

TEST(TimeVarying, BudgetsChooseTheZfpToleranceOfTheFourDimensionalArray) {
  const BuiltinVolumeSeries series("builtin:orbiting-blobs:16x16x16x6");
  const double samples = 16.0 * 16 * 16 * 6;
  auto encode = [&](BudgetKind kind, double value, FitReport* r) {
    EncodeOptions o;
    o.coding.budget = {kind, value};
    return encodeTimeSeries(series, o, TimeSeriesOptions(), r);
  };
  FitReport small, large;
  const TimeVaryingModel a = encode(BudgetKind::kBitsPerSample, 3.0, &small);
  const TimeVaryingModel b = encode(BudgetKind::kBitsPerSample, 10.0, &large);
  EXPECT_EQ(small.coding, "zfp");
  auto bits = [&](const TimeVaryingModel& m) {
    EXPECT_NE(m.codedControlPoints(), nullptr);
    return m.codedControlPoints()
               ? 8.0 * static_cast<double>(m.codedControlPoints()->size()) / samples
               : 1e30;
  };
  EXPECT_LE(bits(a), 3.0);
  EXPECT_LE(bits(b), 10.0);
  EXPECT_GT(bits(b), 3.0);
  EXPECT_LT(large.rmsError, small.rmsError);
  FitReport psnr;
  encode(BudgetKind::kPsnr, 45.0, &psnr);
  EXPECT_GE(psnr.psnr(), 45.0);
  EXPECT_NE(psnr.codingNote.find("--psnr 45"), std::string::npos) << psnr.codingNote;
  FitReport rms;
  encode(BudgetKind::kRmsError, 1e-3, &rms);
  EXPECT_LE(rms.rmsError, 1e-3);
  // Out of reach, or a coder that has no tolerance: clear errors.
  try {
    encode(BudgetKind::kPsnr, 400.0, nullptr);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("before any coding"), std::string::npos) << e.what();
  }
  EXPECT_THROW(encode(BudgetKind::kBitsPerSample, 1e-6, nullptr), Error);
  EncodeOptions lossless;
  lossless.coding.coder = ControlCoder::kLossless;
  lossless.coding.budget = {BudgetKind::kPsnr, 40.0};
  EXPECT_THROW(encodeTimeSeries(series, lossless, TimeSeriesOptions()), Error);
}

TEST(TimeVarying, AnErrorBoundRefinesOneSetOfKnotsForEveryStep) {
  const BuiltinVolumeSeries series("builtin:orbiting-blobs:24x24x24x5");
  EncodeOptions o;
  o.adaptive = AdaptiveOptions();
  o.adaptive->maxRelativeError = 0.01;
  std::vector<int> rounds;
  o.adaptive->onRound = [&](const AdaptiveRound& r) { rounds.push_back(r.round); };
  o.coding.coder = ControlCoder::kZfp;  // the fit gets half the bound, zfp the room it leaves
  FitReport report;
  const TimeVaryingModel m = encodeTimeSeries(series, o, TimeSeriesOptions(), &report);
  EXPECT_TRUE(report.reachedTarget) << report.stopReason;
  EXPECT_GT(report.rounds, 1);
  EXPECT_EQ(rounds.size(), static_cast<size_t>(report.rounds));
  EXPECT_EQ(report.encoder, "time-series-least-squares-adaptive");
  EXPECT_LT(report.controlCounts[0] * report.controlCounts[1] * report.controlCounts[2],
            24 * 24 * 24);
  EXPECT_GT(report.codingTolerance, 0.0);
  // The bound holds at every sample of every step, on the model as stored.
  const double bound = 0.01 * (report.valueMax - report.valueMin);
  EXPECT_LE(report.maxError, bound);
  for (int s = 0; s < series.size(); ++s)
    EXPECT_LE(errorsOnGrid(m.at(series.time(s)).spline(), series.load(s)).max, bound) << s;
  // Only a model that interpolates in time keeps it.
  TimeSeriesOptions fewer;
  fewer.controlCount = 4;
  EXPECT_THROW(encodeTimeSeries(series, o, fewer), Error);
}

// The envelope of the slabs bounds every instant's control points; skip flags built from it
// serve every instant from one cache entry, and the images are those of no skipping.
TEST(TimeVarying, EnvelopeFlagsServeEveryInstantWithTheImagesOfNoSkipping) {
  const BuiltinVolumeSeries series("builtin:orbiting-blobs:20x20x20x8");
  EncodeOptions o;
  o.degree = {3, 3, 3};
  const TimeVaryingModel model = encodeTimeSeries(series, o, TimeSeriesOptions{});
  const auto envelope = model.controlEnvelope();
  ASSERT_TRUE(envelope);
  const auto lo = envelope->lower.controlPoints(), hi = envelope->upper.controlPoints();
  TransferFunction tf;
  tf.color = {{0.0, Vec3f(1, 1, 1)}, {1.0, Vec3f(1, 0.5f, 0)}};
  tf.space = TfSpace::Data;                                            // the blobs peak at 1
  tf.opacity = {{0.0, 0.0f}, {0.45, 0.0f}, {0.5, 0.6f}, {1.0, 0.6f}};  // a step at 0.45
  EmptySpaceCache cache;
  std::shared_ptr<const EmptySpaceFlags> first;
  std::int64_t skipped = 0;
  for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    SCOPED_TRACE(t);
    const Model instant = model.at(t);
    EXPECT_EQ(instant.controlEnvelope(), envelope.get());
    const auto c = instant.spline().controlPoints();
    for (size_t i = 0; i < c.size(); ++i) ASSERT_TRUE(lo[i] <= c[i] && c[i] <= hi[i]) << i;
    RenderSettings s;
    s.width = 48;
    s.height = 40;
    s.camera.resetToBounds(instant.domain().min, instant.domain().max);
    s.camera.azimuth(30);
    s.sampleDistance = 0.5 * instant.dataSpacing().minCoeff();
    s.transferFunction = tf;
    RenderStats cached, again, off;
    const Image a = renderVolume(ModelField(instant, &cache), s, &cached);
    // The first render of an instant: the envelope's flags, one object for every instant.
    const auto used = cache.current();
    if (!first) first = used;
    EXPECT_EQ(used, first);
    // Rendered again at the same time: its own flags, which skip at least as much.
    const Image d = renderVolume(ModelField(instant, &cache), s, &again);
    EXPECT_NE(cache.current(), first);
    EXPECT_LE(cache.current()->emptyCells, instant.spline().spanRanges()->cellCount());
    EXPECT_GE(cache.current()->emptyCells, first->emptyCells);
    s.skipEmptySpace = false;
    const Image b = renderVolume(ModelField(instant), s, &off);
    EXPECT_EQ(a.rgba, b.rgba);
    EXPECT_EQ(d.rgba, b.rgba);
    EXPECT_LE(again.samples, cached.samples);
    skipped += cached.skipped;
  }
  ASSERT_TRUE(first);
  EXPECT_GT(first->emptyCells, 0);
  EXPECT_GT(skipped, 0);  // the test has to exercise the skipping
  // A 3-D model (no time axis) carries no envelope.
  EXPECT_EQ(TimeVaryingModel(model.first()).controlEnvelope(), nullptr);
  EXPECT_EQ(Model(model.first().spline(), model.first().domain(), 0, 1).controlEnvelope(), nullptr);
}

}  // namespace
}  // namespace mfadvr
