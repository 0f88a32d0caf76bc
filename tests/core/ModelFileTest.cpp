#include "core/model/ModelFile.h"

#include "core/model/ControlCoding.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <memory>
#include <optional>
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
  return fitStructured(g, o);
}

// smallModel with a 5 x 6 x 7 point-coverage mask (210 nodes: the last byte has padding bits)
// and scattered-input provenance.
Model maskedModel() {
  Model m = smallModel();
  std::mt19937 rng(5);
  std::vector<std::uint8_t> nodes(5 * 6 * 7);
  for (auto& n : nodes) n = rng() % 3 != 0;
  m.setMask(DomainMask(MaskKind::PointCoverage, {5, 6, 7}, nodes));
  m.provenance().inputPoints = 12345;
  m.provenance().fieldAssociation = "cell data averaged to points";
  return m;
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

std::string headerOf(const std::string& file) {
  std::uint32_t hlen;
  std::memcpy(&hlen, file.data() + 14, 4);
  return file.substr(18, hlen);
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

// The compressed mask section of a masked model file: the last `bytes` bytes before the CRC,
// `bytes` as the header's mask.bytes says.
size_t maskSectionBytes(const std::vector<std::uint8_t>& file) {
  const std::string text(file.begin(), file.end());
  const std::string header = headerOf(text);
  const size_t at = header.find("\"mask\":{\"bytes\":");
  EXPECT_NE(at, std::string::npos) << header;
  return std::stoul(header.substr(at + 16));
}

// The packed (uncompressed) mask bits of a masked model file.
std::vector<std::uint8_t> packedMaskBits(const std::vector<std::uint8_t>& file, size_t packed) {
  const size_t bytes = maskSectionBytes(file);
  std::vector<std::uint8_t> out(packed);
  uLongf size = packed;
  EXPECT_EQ(uncompress(out.data(), &size, file.data() + file.size() - 4 - bytes, bytes), Z_OK);
  EXPECT_EQ(size, packed);
  return out;
}

// The file with its mask section replaced by `section` (header byte count and CRC updated).
std::vector<std::uint8_t> withMaskSection(const std::vector<std::uint8_t>& file,
                                          const std::vector<std::uint8_t>& section) {
  const size_t bytes = maskSectionBytes(file);
  std::vector<std::uint8_t> b(file.begin(), file.end() - 4 - static_cast<long>(bytes));
  b.insert(b.end(), section.begin(), section.end());
  b.insert(b.end(), 4, 0);
  return withHeader(b, "\"mask\":{\"bytes\":" + std::to_string(bytes),
                    "\"mask\":{\"bytes\":" + std::to_string(section.size()));
}

std::vector<std::uint8_t> compressed(const std::vector<std::uint8_t>& packed) {
  uLongf size = compressBound(packed.size());
  std::vector<std::uint8_t> out(size);
  EXPECT_EQ(compress(out.data(), &size, packed.data(), packed.size()), Z_OK);
  out.resize(size);
  return out;
}

TEST(ModelFile, RoundTripIsBitExact) {
  const Model m = smallModel();
  const std::string bytes = serializeModel(m);
  EXPECT_EQ(static_cast<std::int64_t>(bytes.size()), modelFileSize(m));
  const Model r = parseModel(bytesOf(bytes));
  EXPECT_EQ(serializeModel(r), bytes);
  EXPECT_EQ(test::values(r.spline().controlPoints()), test::values(m.spline().controlPoints()));
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

// Files pad their header so that the control points start at a multiple of 16 bytes; given the
// bytes' owner, the parser then uses float32 control points where they lie, and the model keeps
// the bytes alive. Unaligned bytes and coded control points are copied, as without an owner.
TEST(ModelFile, Float32ControlPointsAreUsedInPlace) {
  const Model m = smallModel();
  for (const Model& model :
       {m, Model(m.spline().withInsertedKnot(1, 0.31), m.domain(), m.valueMin(), m.valueMax())}) {
    auto bytes = std::make_shared<std::vector<std::uint8_t>>(bytesOf(serializeModel(model)));
    const std::uint8_t* begin = bytes->data();
    const std::uint8_t* end = begin + bytes->size();
    const size_t controlBytes = model.spline().controlPoints().size() * 4;
    const auto* start = reinterpret_cast<const std::uint8_t*>(
        parseModel(*bytes, "m", nullptr, bytes).spline().controlPoints().data());
    EXPECT_EQ((start - begin) % 16, 0);
    EXPECT_EQ(start + controlBytes + 4, end);  // then only the CRC (no mask)
    EXPECT_TRUE(summarizeModelHead(*bytes, bytes->size(), "m").readInPlace);
    // The model outlives every other holder of the bytes (ASan would see a freed read).
    std::weak_ptr<std::vector<std::uint8_t>> watch = bytes;
    std::optional<Model> kept;
    const std::span<const std::uint8_t> view(*bytes);
    kept.emplace(parseModel(view, "m", nullptr, std::move(bytes)));
    EXPECT_FALSE(watch.expired());
    EXPECT_EQ(test::values(kept->spline().controlPoints()),
              test::values(model.spline().controlPoints()));
    EXPECT_EQ(serializeModel(*kept), serializeModel(model));
    kept.reset();
    EXPECT_TRUE(watch.expired());
    // Without an owner, or misaligned by a byte: a copy of its own.
    const auto whole = bytesOf(serializeModel(model));
    std::vector<std::uint8_t> shifted(whole.size() + 1);
    std::memcpy(shifted.data() + 1, whole.data(), whole.size());
    auto owner = std::make_shared<std::vector<std::uint8_t>>(shifted);
    const std::span<const std::uint8_t> odd = std::span<const std::uint8_t>(*owner).subspan(1);
    const Model copied = parseModel(odd, "m", nullptr, owner);
    const auto* at = reinterpret_cast<const std::uint8_t*>(copied.spline().controlPoints().data());
    EXPECT_TRUE(at < owner->data() || at >= owner->data() + owner->size());
    EXPECT_EQ(test::values(copied.spline().controlPoints()),
              test::values(model.spline().controlPoints()));
  }
  // zfp-coded control points are decoded into an array of the model's own.
  auto zfp = std::make_shared<std::vector<std::uint8_t>>(
      bytesOf(serializeModel(codeControlPoints(m, {ControlCoder::kZfp, 1e-3}))));
  const auto* at = reinterpret_cast<const std::uint8_t*>(
      parseModel(*zfp, "m", nullptr, zfp).spline().controlPoints().data());
  EXPECT_TRUE(at < zfp->data() || at >= zfp->data() + zfp->size());
  EXPECT_FALSE(summarizeModelHead(*zfp, zfp->size(), "m").readInPlace);
}

TEST(ModelFile, EveryTruncationIsAnError) {
  for (const Model& m : {smallModel(), maskedModel()}) {
    const auto full = bytesOf(serializeModel(m));
    for (size_t n = 0; n < full.size(); ++n) {
      const std::vector<std::uint8_t> cut(full.begin(), full.begin() + n);
      EXPECT_NE(errorOf(cut), "") << "prefix of " << n << " bytes parsed";
    }
    auto longer = full;
    longer.push_back(0);
    EXPECT_NE(errorOf(longer).find("trailing"), std::string::npos);
  }
}

TEST(ModelFile, EverySingleByteCorruptionIsAnError) {
  for (const Model& m : {smallModel(), maskedModel()}) {
    const auto full = bytesOf(serializeModel(m));
    for (size_t i = 0; i < full.size(); ++i) {
      auto b = full;
      b[i] ^= 0x5a;
      EXPECT_NE(errorOf(b), "") << "flip at byte " << i << " went unnoticed";
    }
  }
}

TEST(ModelFile, MaskRoundTripIsBitExact) {
  const Model m = maskedModel();
  const std::string bytes = serializeModel(m);
  EXPECT_EQ(static_cast<std::int64_t>(bytes.size()), modelFileSize(m));
  std::uint32_t version = 0;
  const Model r = parseModel(bytesOf(bytes), "m.mfa", &version);
  EXPECT_EQ(version, kModelFormatVersion);
  EXPECT_EQ(version, 3u);
  EXPECT_EQ(r.mask().kind(), MaskKind::PointCoverage);
  EXPECT_EQ(r.mask().dims(), (Index3{5, 6, 7}));
  EXPECT_EQ(r.mask().nodes(), m.mask().nodes());
  EXPECT_EQ(test::values(r.spline().controlPoints()), test::values(m.spline().controlPoints()));
  EXPECT_EQ(r.provenance().inputPoints, 12345);
  EXPECT_EQ(r.provenance().fieldAssociation, "cell data averaged to points");
  EXPECT_EQ(serializeModel(r), bytes);
  EXPECT_NE(headerOf(bytes).find("\"dims\":[5,6,7],\"kind\":\"point-coverage\"}"),
            std::string::npos)
      << headerOf(bytes);

  // The packing: node n is bit n % 8 of mask byte n / 8, x fastest; 27 bytes, zlib-compressed.
  const auto bits = packedMaskBits(bytesOf(bytes), 27);
  for (size_t n = 0; n < 210; ++n)
    EXPECT_EQ((bits[n / 8] >> (n % 8)) & 1, m.mask().nodes()[n]) << n;

  // Every node set, and a mask kind of its own; a mask whose node count is a multiple of 8.
  Model full = smallModel();
  full.setMask(DomainMask(MaskKind::MeshOccupancy, {2, 4, 3}, std::vector<std::uint8_t>(24, 1)));
  const Model rf = parseModel(bytesOf(serializeModel(full)));
  EXPECT_EQ(rf.mask().kind(), MaskKind::MeshOccupancy);
  EXPECT_EQ(rf.mask().nodes(), full.mask().nodes());
  EXPECT_EQ(static_cast<std::int64_t>(serializeModel(full).size()), modelFileSize(full));

  // No mask: no mask key, no mask bytes.
  const std::string plain = serializeModel(smallModel());
  EXPECT_EQ(headerOf(plain).find("\"mask\""), std::string::npos);
  EXPECT_TRUE(parseModel(bytesOf(plain)).mask().empty());
}

template <class T>
void appendRaw(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

// A version-1 file written by hand from the layout in docs/model-format.md: trilinear
// (degree 1, 2 control points per axis) over [0,2] x [0,1] x [0,1], P(i,j,k) = i + 2j + 4k.
std::vector<std::uint8_t> versionOneFile(const std::string& extraHeader = "",
                                         const std::string& extraBytes = "") {
  const std::string header =
      "{\"format\":\"mfadvr-model\",\"degree\":[1,1,1],\"control_counts\":[2,2,2],"
      "\"domain_min\":[0.0,0.0,0.0],\"domain_max\":[2.0,1.0,1.0],\"value_range\":[0.0,7.0],"
      "\"provenance\":{\"source\":\"by hand\",\"field\":\"f\",\"sample_type\":\"float32\","
      "\"sample_dims\":[2,2,2],\"input_bytes\":32,\"encoder\":\"structured-least-squares\","
      "\"created\":\"2026-01-01T00:00:00Z\",\"tool_version\":\"0.1.0\",\"fit_seconds\":0.0,"
      "\"max_error\":0.0,\"rms_error\":0.0}" +
      extraHeader + "}";
  std::string out("MFADVR\r\n\x1a\n", 10);
  appendRaw(out, std::uint32_t{1});
  appendRaw(out, static_cast<std::uint32_t>(header.size()));
  out += header;
  for (int a = 0; a < 3; ++a)
    for (double k : {0.0, 0.0, 1.0, 1.0}) appendRaw(out, k);
  for (int n = 0; n < 8; ++n) appendRaw(out, static_cast<float>(n));
  out += extraBytes;
  appendRaw(out, std::uint32_t{0});
  std::vector<std::uint8_t> b = bytesOf(out);
  fixChecksum(b);
  return b;
}

TEST(ModelFile, VersionOneFilesStillLoad) {
  std::uint32_t version = 0;
  const Model m = parseModel(versionOneFile(), "v1.mfa", &version);
  EXPECT_EQ(version, 1u);
  EXPECT_TRUE(m.mask().empty());
  EXPECT_TRUE(m.inside(Vec3d(1, 0.5, 0.5)));
  EXPECT_EQ(m.provenance().source, "by hand");
  EXPECT_EQ(m.provenance().inputPoints, 0);
  EXPECT_EQ(m.provenance().fieldAssociation, "");
  EXPECT_EQ(m.spline().degrees(), (Degree3{1, 1, 1}));
  // Trilinear: value = u + 2v + 4w with u = x / 2.
  EXPECT_NEAR(m.value(Vec3d(1.0, 0.25, 0.5)), 0.5 + 0.5 + 2.0, 1e-6);
  EXPECT_NEAR(m.value(Vec3d(2.0, 1.0, 1.0)), 7.0, 1e-6);
  // Written back, it becomes version 3 with the same content.
  const auto again = bytesOf(serializeModel(m));
  EXPECT_EQ(again[10], 3);
  EXPECT_EQ(test::values(parseModel(again).spline().controlPoints()),
            test::values(m.spline().controlPoints()));

  // A "mask" key means nothing to version 1 (unknown keys are ignored): no mask section is read.
  const auto withKey = versionOneFile(",\"mask\":{\"kind\":\"mesh-occupancy\",\"dims\":[2,2,2]}");
  EXPECT_TRUE(parseModel(withKey).mask().empty());
  EXPECT_NE(errorOf(versionOneFile(",\"mask\":{\"kind\":\"mesh-occupancy\",\"dims\":[2,2,2]}",
                                   std::string(1, '\xff')))
                .find("trailing"),
            std::string::npos);
}

TEST(ModelFile, DamagedMaskSectionsAreErrors) {
  const auto full = bytesOf(serializeModel(maskedModel()));
  const std::string bytes = "\"bytes\":" + std::to_string(maskSectionBytes(full));
  const std::string kMask = "\"mask\":{" + bytes + ",\"dims\":[5,6,7],\"kind\":\"point-coverage\"}";
  EXPECT_NO_THROW(parseModel(withHeader(full, kMask, kMask)));
  auto maskWith = [&](const std::string& replacement) {
    return errorOf(withHeader(full, kMask, "\"mask\":" + replacement));
  };
  auto withBytes = [&](const std::string& rest) { return "{" + bytes + "," + rest + "}"; };
  EXPECT_NE(maskWith(withBytes("\"dims\":[5,6,7],\"kind\":\"voxels\"")).find("unknown mask kind"),
            std::string::npos);
  EXPECT_NE(maskWith(withBytes("\"dims\":[5,6,7],\"kind\":3")), "");
  EXPECT_NE(maskWith(withBytes("\"dims\":[5,6,7]")), "");
  EXPECT_NE(maskWith(withBytes("\"kind\":\"point-coverage\"")), "");
  EXPECT_NE(maskWith("\"point-coverage\""), "");
  EXPECT_NE(maskWith("null"), "");
  EXPECT_NE(maskWith(withBytes("\"dims\":[5,6],\"kind\":\"point-coverage\"")), "");
  EXPECT_NE(maskWith(withBytes("\"dims\":[5,6,7.5],\"kind\":\"point-coverage\"")), "");
  EXPECT_NE(maskWith(withBytes("\"dims\":[1,6,7],\"kind\":\"point-coverage\"")).find("mask"),
            std::string::npos);
  EXPECT_NE(maskWith(withBytes("\"dims\":[5,6,4097],\"kind\":\"point-coverage\"")).find("mask"),
            std::string::npos);
  // Within the per-axis limit but 2^36 nodes: refused before any size arithmetic or allocation.
  EXPECT_NE(
      maskWith(withBytes("\"dims\":[4096,4096,4096],\"kind\":\"point-coverage\"")).find("mask"),
      std::string::npos);
  EXPECT_NE(maskWith(withBytes("\"dims\":[-5,6,7],\"kind\":\"point-coverage\"")), "");
  EXPECT_NE(maskWith(withBytes("\"dims\":[9223372036854775807,2,2],\"kind\":\"point-coverage\"")),
            "");
  // The compressed byte count: missing, not an integer, zero, or beyond zlib's bound.
  EXPECT_NE(maskWith("{\"dims\":[5,6,7],\"kind\":\"point-coverage\"}").find("byte count"),
            std::string::npos);
  EXPECT_NE(maskWith("{\"bytes\":\"9\",\"dims\":[5,6,7],\"kind\":\"point-coverage\"}"), "");
  EXPECT_NE(
      maskWith("{\"bytes\":0,\"dims\":[5,6,7],\"kind\":\"point-coverage\"}").find("byte count"),
      std::string::npos);
  EXPECT_NE(maskWith("{\"bytes\":100000,\"dims\":[5,6,7],\"kind\":\"point-coverage\"}")
                .find("byte count"),
            std::string::npos);
  // Dims that do not match the stream: 5 x 6 x 8 needs 30 packed bytes, 5 x 6 x 6 needs 23;
  // the stream holds 27.
  EXPECT_NE(maskWith(withBytes("\"dims\":[5,6,8],\"kind\":\"point-coverage\"")).find("corrupt"),
            std::string::npos);
  EXPECT_NE(maskWith(withBytes("\"dims\":[5,6,6],\"kind\":\"point-coverage\"")).find("corrupt"),
            std::string::npos);

  const std::vector<std::uint8_t> bits = packedMaskBits(full, 27);
  EXPECT_NO_THROW(parseModel(withMaskSection(full, compressed(bits))));
  // Padding bits (210 nodes: the top 6 bits of the last packed byte) must be zero.
  for (int bit = 2; bit < 8; ++bit) {
    auto padded = bits;
    padded.back() = static_cast<std::uint8_t>(padded.back() | (1u << bit));
    EXPECT_NE(errorOf(withMaskSection(full, compressed(padded))).find("padding"), std::string::npos)
        << bit;
  }
  // A flipped node bit is a different, valid mask.
  auto flippedBits = bits;
  flippedBits[3] ^= 1;
  const Model r = parseModel(withMaskSection(full, compressed(flippedBits)));
  EXPECT_NE(r.mask().nodes(), maskedModel().mask().nodes());
  // A stream that is not zlib, or ends early, behind a valid checksum and byte count.
  EXPECT_NE(errorOf(withMaskSection(full, std::vector<std::uint8_t>(20, 0x55))).find("corrupt"),
            std::string::npos);
  auto shortStream = compressed(bits);
  shortStream.resize(shortStream.size() - 3);
  EXPECT_NE(errorOf(withMaskSection(full, shortStream)).find("corrupt"), std::string::npos);
  // A mask section cut short (the checksum repaired) or missing altogether.
  auto cut = full;
  cut.erase(cut.end() - 6);
  fixChecksum(cut);
  EXPECT_NE(errorOf(cut).find("truncated"), std::string::npos);
  auto none = full;
  none.erase(none.end() - 4 - static_cast<long>(maskSectionBytes(full)), none.end() - 4);
  fixChecksum(none);
  EXPECT_NE(errorOf(none).find("truncated"), std::string::npos);
}

TEST(ModelFile, ClearMessages) {
  const auto full = bytesOf(serializeModel(smallModel()));
  EXPECT_NE(errorOf(bytesOf("hello, world: not a model at all")).find("not an .mfa model"),
            std::string::npos);
  EXPECT_NE(errorOf({}).find("not an .mfa model"), std::string::npos);
  auto v2 = full;
  v2[10] = 5;
  EXPECT_NE(errorOf(v2).find("version 5 is not supported"), std::string::npos);
  v2[10] = 0;
  EXPECT_NE(errorOf(v2).find("version 0 is not supported"), std::string::npos);
  auto crc = full;
  crc[crc.size() - 10] ^= 1;  // a control point byte
  EXPECT_NE(errorOf(crc).find("checksum"), std::string::npos);
  auto shortFile = full;
  shortFile.resize(full.size() - 100);
  EXPECT_NE(errorOf(shortFile).find("truncated"), std::string::npos);
}

TEST(ModelFile, SummaryReadsTheHeaderAlone) {
  const Model m = smallModel();
  const auto whole = bytesOf(serializeModel(m));
  for (const Model& model : {m, codeControlPoints(m, {ControlCoder::kZfp, 1e-3})}) {
    const auto bytes = bytesOf(serializeModel(model));
    // The prefix and the header are enough (the knots and control points follow them).
    const size_t headBytes = 18 + bytes[14] + (bytes[15] << 8);
    const auto s = summarizeModelHead(std::span(bytes).first(headBytes), bytes.size(), "m");
    EXPECT_EQ(s.degree, (Degree3{3, 2, 2}));
    EXPECT_EQ(s.controlCounts, (Index3{6, 5, 4}));
    EXPECT_EQ(s.coder, model.controlCoding().coder);
    EXPECT_EQ(s.fileBytes, bytes.size());
    EXPECT_THROW(summarizeModelHead(std::span(bytes).first(headBytes - 1), bytes.size(), "m"),
                 Error);
  }
  const auto path = test::scratchDir() / "summary.mfa";
  saveModel(m, path);
  EXPECT_EQ(summarizeModelFile(path, 0, whole.size()).controlCounts, (Index3{6, 5, 4}));
  EXPECT_THROW(summarizeModelHead(bytesOf("not a model at all, but long enough"), 40, "m"), Error);
  // A header that names impossible counts is an Error, as when the model is loaded.
  std::string text(reinterpret_cast<const char*>(whole.data()), whole.size());
  const size_t at = text.find("\"control_counts\":[6,5,4]");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 24, "\"control_counts\":[6,5,1]");
  EXPECT_THROW(summarizeModelHead(bytesOf(text), text.size(), "m"), Error);
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
  EXPECT_NE(errorOf(withHeader(full, "\"input_points\":0", "\"input_points\":0.5")), "");
  EXPECT_NE(errorOf(withHeader(full, "\"domain_max\":[1.0", "\"domain_max\":[-5.0")), "");
  EXPECT_NE(errorOf(withHeader(full, "mfadvr-model", "something-else")), "");

  // A NaN control point and broken knots behind a valid checksum.
  auto nan = full;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.data() + nan.size() - 8, &q, 4);
  fixChecksum(nan);
  EXPECT_NE(errorOf(nan).find("NaN"), std::string::npos);
  // Knots are stored as float64 only where no rule gives them: a model without its sample grid.
  Model noRule = smallModel();
  noRule.provenance().sampleDims = {0, 0, 0};
  const auto storedKnots = bytesOf(serializeModel(noRule));
  EXPECT_NE(headerOf(serializeModel(noRule)).find("\"rule\":\"stored\""), std::string::npos);
  std::uint32_t hlen;
  std::memcpy(&hlen, storedKnots.data() + 14, 4);
  auto knots = storedKnots;
  const double k = 0.9;  // second knot of x: breaks clamping
  std::memcpy(knots.data() + 18 + hlen + 8, &k, 8);
  fixChecksum(knots);
  EXPECT_NE(errorOf(knots).find("knots"), std::string::npos);

  // Knot rules: the placement for the recorded samples, checked before use.
  const std::string rule = "{\"rule\":\"samples\",\"samples\":9}";
  EXPECT_NE(headerOf(serializeModel(smallModel())).find(rule), std::string::npos);
  EXPECT_NE(errorOf(withHeader(full, rule, "{\"rule\":\"samples\",\"samples\":5}"))
                .find("fewer samples than control points"),
            std::string::npos);
  EXPECT_NE(errorOf(withHeader(full, rule, "{\"rule\":\"spline\"}")).find("unknown knot rule"),
            std::string::npos);
  EXPECT_NE(errorOf(withHeader(full, rule, "{\"rule\":\"samples\",\"samples\":1e99}")), "");
  EXPECT_NE(errorOf(withHeader(full, rule, "{\"rule\":\"samples\"}")), "");
  EXPECT_NE(errorOf(withHeader(full, rule, "7")), "");
  // A rule where the knots were stored leaves bytes over: a size error, never a misread.
  EXPECT_NE(errorOf(withHeader(full, rule, "{\"rule\":\"stored\"}")).find("truncated"),
            std::string::npos);
}

// A deterministic mini-fuzz: random multi-byte edits with the checksum repaired, so that the
// parser's deeper checks see damaged content. Every input must parse or raise Error. (The
// libFuzzer target fuzz/fuzz_model_file.cpp explores further.)
TEST(ModelFile, RandomCorruptionNeverCrashes) {
  const auto plain = bytesOf(serializeModel(smallModel()));
  const auto masked = bytesOf(serializeModel(maskedModel()));
  std::mt19937 rng(2024);
  int errors = 0;
  for (int t = 0; t < 3000; ++t) {
    const auto& full = t % 2 ? masked : plain;
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
      (void)m.inside(Vec3d::Zero());
    } catch (const Error&) {
      ++errors;
    }
  }
  EXPECT_GT(errors, 2000);
}

}  // namespace
}  // namespace mfadvr
