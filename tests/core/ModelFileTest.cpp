#include "core/model/ModelFile.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <random>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

Model smallModel() {
  StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:9x8x7");
  StructuredFitOptions o;
  o.degree = {3, 2, 2};
  o.controlCounts = {6, 5, 4};
  return encodeStructured(g, o);
}

std::vector<std::uint8_t> bytesOf(const std::string& s) {
  return {s.begin(), s.end()};
}

void fixChecksum(std::vector<std::uint8_t>& b) {
  const std::uint32_t c =
      static_cast<std::uint32_t>(crc32(crc32(0, Z_NULL, 0), b.data(), b.size() - 4));
  std::memcpy(b.data() + b.size() - 4, &c, 4);
}

std::string errorOf(const std::vector<std::uint8_t>& b) {
  try {
    parseModel(b, "test.mfa");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ModelFile, RoundTripIsBitExact) {
  const Model m = smallModel();
  const std::string bytes = serializeModel(m);
  EXPECT_EQ(static_cast<std::int64_t>(bytes.size()), modelFileSize(m));
  const Model r = parseModel(bytesOf(bytes));
  EXPECT_EQ(serializeModel(r), bytes);
  EXPECT_EQ(r.spline().controlPoints(), m.spline().controlPoints());
  for (int a = 0; a < 3; ++a) EXPECT_EQ(r.spline().knots(a), m.spline().knots(a));
  EXPECT_EQ(r.domain().min, m.domain().min);
  EXPECT_EQ(r.domain().max, m.domain().max);
  EXPECT_EQ(r.valueMin(), m.valueMin());
  EXPECT_EQ(r.valueMax(), m.valueMax());
  EXPECT_EQ(r.provenance().source, m.provenance().source);
  EXPECT_EQ(r.provenance().maxError, m.provenance().maxError);
  EXPECT_EQ(r.provenance().sampleDims, m.provenance().sampleDims);
  // Size is essentially the control points: header and knots are small.
  EXPECT_LT(bytes.size(), m.spline().controlPoints().size() * 4 + 2048);
}

TEST(ModelFile, NonUniformKnotsRoundTrip) {
  const Model m0 = smallModel();
  Model m(m0.spline().withInsertedKnot(1, 0.31), m0.domain(), m0.valueMin(), m0.valueMax());
  const Model r = parseModel(bytesOf(serializeModel(m)));
  EXPECT_EQ(r.spline().knots(1), m.spline().knots(1));
  EXPECT_FALSE(r.spline().knots(1).isUniform());
}

TEST(ModelFile, SaveAndLoadAtomically) {
  const auto dir = test::scratchDir();
  const Model m = smallModel();
  saveModel(m, dir / "a.mfa");
  saveModel(m, dir / "a.mfa");  // overwrite
  const Model r = loadModel(dir / "a.mfa");
  EXPECT_EQ(serializeModel(r), serializeModel(m));
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(e.path().filename(), "a.mfa");
  }
  EXPECT_EQ(files, 1);
  EXPECT_THROW(saveModel(m, dir / "no-such-dir" / "b.mfa"), Error);
  EXPECT_THROW(loadModel(dir / "missing.mfa"), Error);
  EXPECT_THROW(loadModel(dir), Error);
}

TEST(ModelFile, EveryTruncationIsAnError) {
  const auto full = bytesOf(serializeModel(smallModel()));
  for (size_t n = 0; n < full.size(); ++n) {
    const std::vector<std::uint8_t> cut(full.begin(), full.begin() + n);
    EXPECT_NE(errorOf(cut), "") << "prefix of " << n << " bytes parsed";
  }
  auto longer = full;
  longer.push_back(0);
  EXPECT_NE(errorOf(longer).find("trailing"), std::string::npos);
}

TEST(ModelFile, EverySingleByteCorruptionIsAnError) {
  const auto full = bytesOf(serializeModel(smallModel()));
  for (size_t i = 0; i < full.size(); ++i) {
    auto b = full;
    b[i] ^= 0x5a;
    EXPECT_NE(errorOf(b), "") << "flip at byte " << i << " went unnoticed";
  }
}

TEST(ModelFile, ClearMessages) {
  const auto full = bytesOf(serializeModel(smallModel()));
  EXPECT_NE(errorOf(bytesOf("hello, world: not a model at all")).find("not an .mfa model"),
            std::string::npos);
  EXPECT_NE(errorOf({}).find("not an .mfa model"), std::string::npos);
  auto v2 = full;
  v2[10] = 2;
  EXPECT_NE(errorOf(v2).find("version 2 is not supported"), std::string::npos);
  auto crc = full;
  crc[crc.size() - 10] ^= 1;  // a control point byte
  EXPECT_NE(errorOf(crc).find("checksum"), std::string::npos);
  auto shortFile = full;
  shortFile.resize(full.size() - 100);
  EXPECT_NE(errorOf(shortFile).find("truncated"), std::string::npos);
}

// Rewrites the JSON header (keeping the checksum valid) so that validation past the checksum is
// exercised: absurd sizes must not allocate, bad values must be rejected.
std::vector<std::uint8_t> withHeader(const std::vector<std::uint8_t>& full, const std::string& from,
                                     const std::string& to) {
  std::uint32_t hlen;
  std::memcpy(&hlen, full.data() + 14, 4);
  std::string header(full.begin() + 18, full.begin() + 18 + hlen);
  const size_t at = header.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  header.replace(at, from.size(), to);
  const std::uint32_t n = static_cast<std::uint32_t>(header.size());
  std::string text(full.begin(), full.begin() + 14);
  text.append(reinterpret_cast<const char*>(&n), 4);
  text += header;
  text.append(full.begin() + 18 + hlen, full.end());
  std::vector<std::uint8_t> b = bytesOf(text);
  fixChecksum(b);
  return b;
}

TEST(ModelFile, SemanticValidationBehindValidChecksum) {
  const auto full = bytesOf(serializeModel(smallModel()));
  EXPECT_NO_THROW(parseModel(withHeader(full, "\"degree\"", "\"degree\"")));
  EXPECT_NE(errorOf(withHeader(full, "\"control_counts\":[6,5,4]",
                               "\"control_counts\":[1000000,1000000,1000000]")),
            "");
  EXPECT_NE(errorOf(withHeader(full, "\"control_counts\":[6,5,4]", "\"control_counts\":[6,5]")),
            "");
  EXPECT_NE(errorOf(withHeader(full, "\"degree\":[3,2,2]", "\"degree\":[9,2,2]")), "");
  EXPECT_NE(errorOf(withHeader(full, "\"degree\":[3,2,2]", "\"degree\":[-1,2,2]")), "");
  EXPECT_NE(errorOf(withHeader(full, "\"degree\":[3,2,2]", "\"degree\":\"three\"")), "");
  // Non-integer numbers where integers belong (a float this large is not representable as int).
  EXPECT_NE(errorOf(withHeader(full, "\"degree\":[3,2,2]", "\"degree\":[5.5e26,2,2]")), "");
  EXPECT_NE(errorOf(withHeader(full, "\"control_counts\":[6,5,4]", "\"control_counts\":[6,5,4.0]")),
            "");
  EXPECT_NE(errorOf(withHeader(full, "\"input_bytes\":", "\"input_bytes\":1e300,\"x\":")), "");
  EXPECT_NE(errorOf(withHeader(full, "\"domain_max\":[1.0", "\"domain_max\":[-5.0")), "");
  EXPECT_NE(errorOf(withHeader(full, "mfadvr-model", "something-else")), "");

  // A NaN control point and broken knots behind a valid checksum.
  auto nan = full;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.data() + nan.size() - 8, &q, 4);
  fixChecksum(nan);
  EXPECT_NE(errorOf(nan).find("NaN"), std::string::npos);
  std::uint32_t hlen;
  std::memcpy(&hlen, full.data() + 14, 4);
  auto knots = full;
  const double k = 0.9;  // second knot of x: breaks clamping
  std::memcpy(knots.data() + 18 + hlen + 8, &k, 8);
  fixChecksum(knots);
  EXPECT_NE(errorOf(knots).find("knots"), std::string::npos);
}

// A deterministic mini-fuzz: random multi-byte edits with the checksum repaired, so that the
// parser's deeper checks see damaged content. Every input must parse or raise Error. (The
// libFuzzer target fuzz/fuzz_model_file.cpp explores further.)
TEST(ModelFile, RandomCorruptionNeverCrashes) {
  const auto full = bytesOf(serializeModel(smallModel()));
  std::mt19937 rng(2024);
  int errors = 0;
  for (int t = 0; t < 3000; ++t) {
    auto b = full;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const size_t at = rng() % b.size();
      switch (rng() % 3) {
        case 0:
          b[at] = static_cast<std::uint8_t>(rng());
          break;
        case 1:
          b.erase(b.begin() + static_cast<long>(at));
          break;
        default:
          b.insert(b.begin() + static_cast<long>(at), static_cast<std::uint8_t>(rng()));
      }
    }
    if (b.size() > 4 && rng() % 2) fixChecksum(b);
    try {
      const Model m = parseModel(b);
      (void)m.value(Vec3d::Zero());
    } catch (const Error&) {
      ++errors;
    }
  }
  EXPECT_GT(errors, 2000);
}

}  // namespace
}  // namespace mfadvr
