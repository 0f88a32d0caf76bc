// Control-point coding (ControlCoding.h), coded model files, and the encoder's coding choices
// and budgets (CodingChoice.h), judged on the decoded model.
#include "core/model/ControlCoding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/decode/GridDecoder.h"
#include "core/encode/CodingChoice.h"
#include "core/encode/Encoder.h"
#include "core/model/ModelFile.h"
#include "core/model/ZfpArray.h"
#include "core/util/Crc32.h"

namespace mfadvr {
namespace {

std::vector<float> smoothGrid(const Index3& d) {
  std::vector<float> v;
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        v.push_back(static_cast<float>(100.0 * std::sin(0.3 * x) * std::cos(0.2 * y) + z));
  return v;
}

std::span<const std::uint8_t> bytesOf(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Marschner-Lobb quantized to 0..255: an 8-bit scan.
StructuredGrid byteGrid(int n) {
  StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:" + std::to_string(n));
  for (float& v : g.values) v = std::round(255.0f * v);
  g.sampleType = "uint8";
  g.inputBytes = g.sampleCount();
  return g;
}

double maxDifference(std::span<const float> a, std::span<const float> b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(double(a[i]) - b[i]));
  return worst;
}

TEST(ControlCoding, LosslessIsBitExact) {
  const Index3 d{7, 5, 3};
  std::vector<float> v = smoothGrid(d);
  v[3] = -0.0f;
  v[4] = std::numeric_limits<float>::denorm_min();
  v[5] = 3.4e38f;
  const std::string coded = encodeControlPoints(v, d, {ControlCoder::kLossless, 0});
  const std::vector<float> back = decodeControlPoints(bytesOf(coded), d, {ControlCoder::kLossless});
  ASSERT_EQ(back.size(), v.size());
  EXPECT_EQ(std::memcmp(back.data(), v.data(), v.size() * 4), 0);
}

TEST(ControlCoding, ZfpStaysWithinTheToleranceAndShrinksWithIt) {
  const Index3 d{33, 20, 17};
  const std::vector<float> v = smoothGrid(d);
  size_t previous = std::numeric_limits<size_t>::max();
  for (double tol : {1e-4, 1e-2, 1.0, 16.0}) {
    const ControlCoding c{ControlCoder::kZfp, tol};
    const std::string coded = encodeControlPoints(v, d, c);
    const auto back = decodeControlPoints(bytesOf(coded), d, c);
    EXPECT_LE(maxDifference(back, v), tol) << tol;
    EXPECT_LT(coded.size(), previous) << tol;
    EXPECT_LE(static_cast<std::int64_t>(coded.size()), maxCodedControlBytes(d, c));
    previous = coded.size();
  }
  EXPECT_THROW(encodeControlPoints(v, d, {ControlCoder::kZfp, 0.0}), Error);
  EXPECT_THROW(encodeControlPoints(v, d, {ControlCoder::kZfp, NAN}), Error);
}

TEST(ControlCoding, DamagedPayloadsAreErrorsOrValuesNeverCrashes) {
  const Index3 d{9, 8, 7};
  const std::vector<float> v = smoothGrid(d);
  std::mt19937 rng(11);
  for (ControlCoding c :
       {ControlCoding{ControlCoder::kLossless, 0}, ControlCoding{ControlCoder::kZfp, 0.01}}) {
    const std::string coded = encodeControlPoints(v, d, c);
    for (size_t cut = 0; cut < coded.size(); cut += 7) {
      std::string shorter = coded.substr(0, cut);
      try {
        decodeControlPoints(bytesOf(shorter), d, c);
      } catch (const Error&) {
      }
    }
    for (int trial = 0; trial < 300; ++trial) {
      std::string bad = coded;
      for (int k = 0; k < 1 + trial % 4; ++k)
        bad[rng() % bad.size()] ^= static_cast<char>(1 + rng() % 255);
      try {
        const auto out = decodeControlPoints(bytesOf(bad), d, c);
        EXPECT_EQ(out.size(), v.size());
      } catch (const Error&) {
      }
    }
    // Longer than the coding can produce: refused before decoding.
    const std::string huge(static_cast<size_t>(maxCodedControlBytes(d, c)) + 1, '\0');
    EXPECT_THROW(decodeControlPoints(bytesOf(huge), d, c), Error);
  }
  EXPECT_THROW(parseControlCoder("gzip"), Error);
}

TEST(ZfpArray, FixedRateTakesItsBitsAndDecodesDamagedStreamsSafely) {
  const Index3 d{16, 12, 8};
  const std::vector<float> v = smoothGrid(d);
  const ZfpSettings rate{ZfpSettings::Mode::kRate, 4.0};
  const std::string stream = zfpCompress(v, d, rate);
  EXPECT_EQ(stream.size(), v.size() * 4 / 8);  // 4 bits per value, whole 4^3 blocks
  const std::vector<float> back = zfpDecompress(bytesOf(stream), d, rate);
  EXPECT_LT(maxDifference(back, v), 20.0);
  EXPECT_GT(maxDifference(back, v), 0.0);  // lossy at 4 bits per value
  std::mt19937 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    std::string bad = stream.substr(0, rng() % (stream.size() + 1));
    if (!bad.empty()) bad[rng() % bad.size()] ^= 0x5a;
    try {
      EXPECT_EQ(zfpDecompress(bytesOf(bad), d, rate).size(), v.size());
    } catch (const Error&) {
    }
  }
  EXPECT_THROW(zfpCompress(v, d, {ZfpSettings::Mode::kRate, 0.0}), Error);
  EXPECT_THROW(zfpCompress(std::span<const float>(v).first(10), d, rate), Error);
}

// The encoder's round trip gives the stream zfpCompress writes and the values zfpDecompress
// reads back from it, bit for bit, in both modes and for uneven sizes.
TEST(ZfpArray, RoundTripIsCompressThenDecompress) {
  for (const Index3 d : {Index3{16, 12, 8}, Index3{13, 7, 5}}) {
    const std::vector<float> v = smoothGrid(d);
    for (const ZfpSettings z : {ZfpSettings{ZfpSettings::Mode::kAccuracy, 0.25},
                                ZfpSettings{ZfpSettings::Mode::kAccuracy, 1e-4},
                                ZfpSettings{ZfpSettings::Mode::kRate, 6.0}}) {
      const ZfpRoundTrip r = zfpRoundTrip(v, d, z);
      EXPECT_EQ(r.stream, zfpCompress(v, d, z));
      EXPECT_EQ(r.decoded, zfpDecompress(bytesOf(r.stream), d, z));
    }
  }
}

Model fittedModel() {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:20x18x16");
  return fitStructured(g, {});
}

TEST(ControlCoding, CodedModelFilesRoundTripExactly) {
  const Model fit = fittedModel();
  for (ControlCoding c :
       {ControlCoding{ControlCoder::kFloat32, 0}, ControlCoding{ControlCoder::kLossless, 0},
        ControlCoding{ControlCoder::kZfp, 1e-3}}) {
    const Model coded = codeControlPoints(fit, c);
    if (c.coder != ControlCoder::kZfp)
      EXPECT_EQ(test::values(coded.spline().controlPoints()),
                test::values(fit.spline().controlPoints()));
    else
      EXPECT_LE(maxDifference(coded.spline().controlPoints(), fit.spline().controlPoints()), 1e-3);
    const std::string file = serializeModel(coded);
    EXPECT_EQ(static_cast<std::int64_t>(file.size()), modelFileSize(coded));
    const Model back = parseModel(bytesOf(file));
    EXPECT_EQ(back.controlCoding().coder, c.coder);
    EXPECT_EQ(test::values(back.spline().controlPoints()),
              test::values(coded.spline().controlPoints()));
    EXPECT_EQ(serializeModel(back), file);  // lossy bytes are kept, not coded again
  }
  const std::string lossless = serializeModel(codeControlPoints(fit, {ControlCoder::kLossless, 0}));
  EXPECT_LT(lossless.size(), serializeModel(fit).size());
  // The knots come back from their rule bit for bit.
  const Model back = parseModel(bytesOf(lossless));
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(back.spline().knots(a).knots(), fit.spline().knots(a).knots());
}

// A version-2 file: float32 control points and no "control_points" entry.
TEST(ControlCoding, VersionTwoFilesStillLoad) {
  Model fit = fittedModel();
  fit.provenance().sampleDims = {0, 0, 0};  // no knot rule: every knot stored, as in version 2
  std::string file = serializeModel(fit);
  std::uint32_t hlen;
  std::memcpy(&hlen, file.data() + 14, 4);
  std::string header = file.substr(18, hlen);
  const size_t at = header.find("\"control_points\":{");
  ASSERT_NE(at, std::string::npos);
  const size_t end = header.find('}', at);
  header.erase(at, end - at + 2);  // the entry and the comma after it
  const size_t rules = header.find("\"knots\":[");
  ASSERT_NE(rules, std::string::npos);
  header.erase(rules, header.find(']', rules) - rules + 2);
  const std::uint32_t n = static_cast<std::uint32_t>(header.size());
  std::string v2 = file.substr(0, 10);
  const std::uint32_t two = 2;
  v2.append(reinterpret_cast<const char*>(&two), 4);
  v2.append(reinterpret_cast<const char*>(&n), 4);
  v2 += header;
  v2.append(file, 18 + hlen, std::string::npos);
  const std::uint32_t crc =
      crc32Of(reinterpret_cast<const std::uint8_t*>(v2.data()), v2.size() - 4);
  std::memcpy(v2.data() + v2.size() - 4, &crc, 4);
  std::uint32_t version = 0;
  const Model m = parseModel(bytesOf(v2), "v2.mfa", &version);
  EXPECT_EQ(version, 2u);
  EXPECT_EQ(m.controlCoding().coder, ControlCoder::kFloat32);
  EXPECT_EQ(test::values(m.spline().controlPoints()), test::values(fit.spline().controlPoints()));
}

TEST(ControlCoding, DamagedCodedModelFilesAreErrors) {
  const Model coded = codeControlPoints(fittedModel(), {ControlCoder::kZfp, 1e-3});
  const std::string file = serializeModel(coded);
  for (size_t cut = 0; cut < file.size(); cut += 13)
    EXPECT_THROW(parseModel(bytesOf(file.substr(0, cut))), Error) << cut;
  // Any flipped byte: the checksum catches it.
  for (size_t i = 0; i < file.size(); i += 11) {
    std::string bad = file;
    bad[i] ^= 0x20;
    EXPECT_THROW(parseModel(bytesOf(bad)), Error) << i;
  }
}

TEST(CodingChoice, IntegerScansRoundBackToTheirSamples) {
  const StructuredGrid g = byteGrid(24);
  FitReport r;
  const Model fit = fitStructured(g, {}, &r);
  CodingOptions o;
  o.coder = ControlCoder::kZfp;
  // countsGiven: the model is not held to the input's size, so the rounding bound decides.
  const Model m = codeFittedModel(fit, g, o, 0.0, true, &r);
  EXPECT_EQ(r.coding, "zfp");
  EXPECT_GE(r.codingTolerance, kIntegerDefaultTolerance);
  // The stated errors are measured on the decoded model.
  const SampleErrors e = errorsOnGrid(m.spline(), g);
  EXPECT_DOUBLE_EQ(r.maxError, e.max);
  EXPECT_LT(e.max, kIntegerRoundingBound);
  const std::vector<double> values = splineOnGrid(m.spline(), g.dims);
  for (size_t i = 0; i < values.size(); ++i) ASSERT_EQ(std::round(values[i]), g.values[i]) << i;

  // By default the model stays within the input's bytes: this rough 24^3 field needs a larger
  // tolerance for that, and the report says so.
  FitReport capped;
  const Model small = codeFittedModel(fit, g, o, 0.0, false, &capped);
  EXPECT_LE(static_cast<std::int64_t>(small.codedControlPoints()->size()), g.inputBytes);
  EXPECT_GT(capped.codingTolerance, r.codingTolerance);
  EXPECT_NE(capped.codingNote.find("input's"), std::string::npos) << capped.codingNote;
}

TEST(CodingChoice, BudgetsAreMetOnTheDecodedModel) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:32");
  const double n = static_cast<double>(g.sampleCount());
  StructuredFitOptions fit;
  for (double bits : {0.5, 2.0}) {
    CodingOptions o;
    o.budget = {BudgetKind::kBitsPerSample, bits};
    FitReport r;
    const Model m = encodeToBudget(g, fit, o, false, &r);
    ASSERT_NE(m.codedControlPoints(), nullptr);
    EXPECT_LE(8.0 * static_cast<double>(m.codedControlPoints()->size()) / n, bits);
    EXPECT_NEAR(errorsOnGrid(m.spline(), g).rms, r.rmsError, 1e-12);
  }
  for (double psnr : {40.0, 80.0}) {
    CodingOptions o;
    o.budget = {BudgetKind::kPsnr, psnr};
    FitReport r;
    const Model m = encodeToBudget(g, fit, o, false, &r);
    const SampleErrors e = errorsOnGrid(m.spline(), g);
    EXPECT_GE(psnrOf(m.valueMax() - m.valueMin(), e.rms), psnr);
    EXPECT_DOUBLE_EQ(r.rmsError, e.rms);
  }
  CodingOptions rms;
  rms.budget = {BudgetKind::kRmsError, 1e-3};
  EXPECT_LE(errorsOnGrid(encodeToBudget(g, fit, rms, false, nullptr).spline(), g).rms, 1e-3);
  // A higher PSNR costs more bytes.
  CodingOptions low, high;
  low.budget = {BudgetKind::kPsnr, 40};
  high.budget = {BudgetKind::kPsnr, 80};
  EXPECT_LT(modelFileSize(encodeToBudget(g, fit, low, false, nullptr)),
            modelFileSize(encodeToBudget(g, fit, high, false, nullptr)));
  CodingOptions impossible;
  impossible.budget = {BudgetKind::kPsnr, 400};
  test::expectError([&] { encodeToBudget(g, fit, impossible, false, nullptr); },
                    {"no model", "--psnr 400"});
}

TEST(CodingChoice, MaxErrorIsKeptWithZfpCoding) {
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:33");
  EncodeOptions o;
  o.adaptive = AdaptiveOptions{};
  o.adaptive->maxRelativeError = 5e-3;
  o.coding.coder = ControlCoder::kZfp;
  FitReport r;
  const Model m = encodeStructured(g, o, &r);
  EXPECT_TRUE(r.reachedTarget);
  EXPECT_EQ(r.coding, "zfp");
  const double range = m.valueMax() - m.valueMin();
  EXPECT_LE(errorsOnGrid(m.spline(), g).max, 5e-3 * range);
}

TEST(GridDecoder, SlabsAgreeWithTheWholeGrid) {
  const Model m = fittedModel();
  const DecodeGrid grid = decodeGridWithSamples(m, {13, 11, 29});
  const std::vector<double> whole = splineOnGrid(m.spline(), grid.dims);
  std::vector<double> slabs;
  std::int64_t expectZ = 0;
  decodeBySlabs(m, grid, 13 * 11 * 4, [&](std::int64_t z0, std::int64_t z1, auto values) {
    EXPECT_EQ(z0, expectZ);
    expectZ = z1;
    slabs.insert(slabs.end(), values.begin(), values.end());
  });
  EXPECT_EQ(expectZ, 29);
  ASSERT_EQ(slabs.size(), whole.size());
  for (size_t i = 0; i < whole.size(); ++i) ASSERT_NEAR(slabs[i], whole[i], 1e-9) << i;
  // At the samples of the fitted grid, decoding gives the model's own values.
  const DecodeGrid own = defaultDecodeGrid(m);
  EXPECT_EQ(own.dims, (Index3{20, 18, 16}));
  EXPECT_NEAR(whole[13 * 11 * 28 + 13 * 10 + 12],
              m.value(grid.origin + Vec3d(12, 10, 28).cwiseProduct(grid.spacing)), 1e-5);
  EXPECT_THROW(decodeGridWithSamples(m, {1, 5, 5}), Error);
}

}  // namespace
}  // namespace mfadvr
