#include "core/model/ModelFile.h"

#include <zlib.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "core/encode/KnotPlacement.h"
#include "core/model/ProvenanceJson.h"
#include "core/util/AtomicFile.h"
#include "core/util/ByteIo.h"
#include "core/util/Crc32.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the .mfa writer and reader assume a little-endian host");

constexpr char kMagic[10] = {'M', 'F', 'A', 'D', 'V', 'R', '\r', '\n', '\x1a', '\n'};
constexpr size_t kPrefixBytes = sizeof(kMagic) + 4 + 4;  // magic, version, header length
constexpr std::uint32_t kMaxHeaderBytes = 1u << 20;
constexpr std::int64_t kMaxControlPerAxis = 1 << 20;
constexpr std::int64_t kMaxRuleSamples = std::int64_t(1) << 40;

using nlohmann::json;

// nlohmann's number conversions cast floating values to integers unchecked (undefined for
// 1e30), so integer fields are read only when the JSON holds an integer.
std::int64_t integerOr(const json& j, const char* key, std::int64_t fallback) {
  const auto it = j.find(key);
  if (it == j.end()) return fallback;
  if (!it->is_number_integer())
    throw json::type_error::create(302, std::string(key) + " must be an integer", &j);
  return it->get<std::int64_t>();
}

Index3 integers3(const json& j, const char* key) {
  const json& a = j.at(key);
  if (!a.is_array() || a.size() != 3)
    throw json::type_error::create(302, std::string(key) + " must be an array of 3", &j);
  Index3 out{};
  for (int i = 0; i < 3; ++i) {
    if (!a[i].is_number_integer())
      throw json::type_error::create(302, std::string(key) + " must hold integers", &j);
    out[i] = a[i].get<std::int64_t>();
  }
  return out;
}

Provenance provenanceFromJson(const json& j) {
  Provenance p;
  p.source = j.value("source", "");
  p.field = j.value("field", "");
  p.sampleType = j.value("sample_type", "");
  p.sampleDims = j.contains("sample_dims") ? integers3(j, "sample_dims") : Index3{0, 0, 0};
  p.inputPoints = integerOr(j, "input_points", 0);
  p.fieldAssociation = j.value("field_association", "");
  p.inputBytes = integerOr(j, "input_bytes", 0);
  p.encoder = j.value("encoder", "");
  p.created = j.value("created", "");
  p.toolVersion = j.value("tool_version", "");
  p.fitSeconds = j.value("fit_seconds", 0.0);
  p.maxError = j.value("max_error", 0.0);
  p.rmsError = j.value("rms_error", 0.0);
  p.smoothing = j.value("smoothing", 0.0);
  if (!(p.smoothing >= 0.0) || !std::isfinite(p.smoothing)) p.smoothing = 0.0;
  return p;
}

// Mask nodes, 0/1 bytes, as bits: node i is bit i % 8 (least significant first) of byte i / 8.
std::int64_t maskBytes(const Index3& dims) {
  return (dims[0] * dims[1] * dims[2] + 7) / 8;
}

// `raw` as one zlib stream (what: named in the error).
std::string zlibCompressed(const std::string& raw, const char* what) {
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string out(size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()),
                Z_BEST_COMPRESSION) != Z_OK)
    throw Error(std::string("cannot compress the ") + what);
  out.resize(size);
  return out;
}

// The packed bits, zlib-compressed: masks are long runs of 0 and 1, and compress to a few
// percent of their packed size.
std::string compressedMask(const DomainMask& mask) {
  const auto& nodes = mask.nodes();
  std::string bits(static_cast<size_t>(maskBytes(mask.dims())), '\0');
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i]) bits[i / 8] = static_cast<char>(bits[i / 8] | (1u << (i % 8)));
  return zlibCompressed(bits, "domain mask");
}

// A boundary's vertices (float32 x, y, z each) then its triangles (uint32 indices),
// zlib-compressed.
std::int64_t boundaryRawBytes(std::int64_t vertices, std::int64_t triangles) {
  return 12 * vertices + 12 * triangles;
}

std::string compressedBoundary(const DomainBoundary* boundary) {
  if (!boundary) return {};
  std::string raw;
  raw.reserve(static_cast<size_t>(
      boundaryRawBytes(static_cast<std::int64_t>(boundary->vertices().size()),
                       static_cast<std::int64_t>(boundary->triangles().size()))));
  for (const Vec3f& v : boundary->vertices())
    for (int a = 0; a < 3; ++a) appendBytes(raw, v[a]);
  for (const BoundaryTriangle& t : boundary->triangles())
    for (std::uint32_t i : t) appendBytes(raw, i);
  return zlibCompressed(raw, "domain boundary");
}

// How a knot vector is stored (version 3): as a rule when the rule gives exactly these knots
// (the placement for N equally spaced samples, or clamped uniform), else as float64 values.
// A 64^3 model's knots are 1.6 KB of float64: at 0.25 bits per sample, a fifth of the file.
json knotRule(const KnotVector& kv, std::int64_t samples) {
  const int p = kv.degree(), n = kv.controlCount();
  if (samples >= n && samples >= 2 && knotsForSamples(p, n, samples).knots() == kv.knots())
    return {{"rule", "samples"}, {"samples", samples}};
  if (KnotVector::clampedUniform(p, n).knots() == kv.knots()) return {{"rule", "uniform"}};
  return {{"rule", "stored"}};
}

// What a model file holds: the spatial shape (knots, box, range, provenance, mask) of a model,
// an optional time axis, and every control point with its coding.
struct FileContent {
  const Model& shape;
  const TimeAxis* time = nullptr;  // null: a 3-D model (format version 3)
  std::span<const float> controls;
  ControlCoding coding;
  const std::string* coded = nullptr;  // the kept coded bytes, when there are some
  std::int64_t slabs() const { return time ? time->controlCount() : 1; }
};

FileContent contentOf(const Model& m) {
  return {m, nullptr, m.spline().controlPoints(), m.controlCoding(), m.codedControlPoints()};
}

FileContent contentOf(const TimeVaryingModel& m) {
  if (!m.hasTime()) return contentOf(m.first());
  return {m.first(), &m.timeAxis(), m.controlPoints(), m.controlCoding(), m.codedControlPoints()};
}

std::array<json, 3> knotRules(const Model& m) {
  std::array<json, 3> rules;
  for (int a = 0; a < 3; ++a)
    rules[a] = knotRule(m.spline().knots(a), m.provenance().sampleDims[a]);
  return rules;
}

bool stored(const json& rule) {
  return rule.at("rule") == "stored";
}

// The control-point section as the model's coding stores it: the bytes the model was read from or
// coded to when it holds them, the float array itself when uncoded (no copy), else coded now.
// `owned` keeps bytes coded here alive as long as the view is used.
std::string_view codedControls(const FileContent& c, std::shared_ptr<const std::string>& owned) {
  if (c.coded) return *c.coded;
  if (c.coding.coder == ControlCoder::kFloat32)
    return {reinterpret_cast<const char*>(c.controls.data()), c.controls.size() * sizeof(float)};
  owned = std::make_shared<const std::string>(
      encodeControlPoints(c.controls, c.shape.spline().counts(), c.coding, c.slabs()));
  return *owned;
}

// compressedMaskBytes, compressedBoundaryBytes: the sizes of the mask and boundary sections
// (ignored without them).
std::string headerText(const FileContent& content, const std::array<json, 3>& rules,
                       std::int64_t controlBytes, std::int64_t compressedMaskBytes,
                       std::int64_t compressedBoundaryBytes) {
  const Model& m = content.shape;
  const TensorBSpline& s = m.spline();
  const DomainBox& d = m.domain();
  json h = {{"format", "mfadvr-model"},
            {"degree", s.degrees()},
            {"control_counts", s.counts()},
            {"domain_min", {d.min[0], d.min[1], d.min[2]}},
            {"domain_max", {d.max[0], d.max[1], d.max[2]}},
            {"value_range", {m.valueMin(), m.valueMax()}},
            {"provenance", provenanceToJson(m.provenance())}};
  const ControlCoding& c = content.coding;
  h["control_points"] = {{"coding", controlCoderName(c.coder)}, {"bytes", controlBytes}};
  if (const TimeAxis* t = content.time)
    h["time"] = {{"degree", t->degree()},
                 {"control_count", t->controlCount()},
                 {"range", {t->begin, t->end}},
                 {"steps", t->steps}};
  h["knots"] = {rules[0], rules[1], rules[2]};
  if (c.coder == ControlCoder::kZfp) h["control_points"]["tolerance"] = c.tolerance;
  if (!m.mask().empty())
    h["mask"] = {{"kind", maskKindName(m.mask().kind())},
                 {"dims", m.mask().dims()},
                 {"bytes", compressedMaskBytes}};
  if (const DomainBoundary* b = m.boundary())
    h["boundary"] = {{"vertices", b->vertices().size()},
                     {"triangles", b->triangles().size()},
                     {"bytes", compressedBoundaryBytes}};
  return h.dump();
}

// Bytes of the knots a model file stores (the spatial ones without a rule, the time knots).
std::int64_t storedKnotBytes(const FileContent& c, const std::array<json, 3>& rules) {
  std::int64_t knots = 0;
  for (int a = 0; a < 3; ++a)
    if (stored(rules[a]))
      knots += static_cast<std::int64_t>(c.shape.spline().knots(a).knots().size());
  if (c.time) knots += static_cast<std::int64_t>(c.time->knots.knots().size());
  return 8 * knots;
}

// The header, padded with spaces (JSON allows them) so that the control points start at a
// multiple of kControlAlignment bytes: a reader can then use float32 control points where the
// file's bytes lie (parseModel with an owner), without a copy.
constexpr size_t kControlAlignment = 16;
std::string paddedHeader(std::string header, std::int64_t knotBytes) {
  const size_t start = kPrefixBytes + header.size() + static_cast<size_t>(knotBytes);
  header.append((kControlAlignment - start % kControlAlignment) % kControlAlignment, ' ');
  return header;
}

Error invalidModel(const std::string& name, const std::string& why) {
  return Error(name + ": not a valid .mfa model: " + why);
}

struct ModelPrefix {
  std::uint32_t version = 0;
  std::uint32_t headerBytes = 0;
};

// The magic bytes, version and header length of a model of fileBytes bytes starting at `b` (which
// holds at least its prefix when the file is long enough).
ModelPrefix checkedPrefix(std::span<const std::uint8_t> b, std::uint64_t fileBytes,
                          const std::string& name) {
  if (b.size() >= 8 && std::memcmp(b.data(), "MFADVRMB", 8) == 0)
    throw Error(name +
                ": is a multi-block model (mfadvr encode --blocks), not a single model; "
                "`mfadvr render` and `info` read it, and ParaView's MFA reader");
  if (b.size() < sizeof(kMagic) || std::memcmp(b.data(), kMagic, sizeof(kMagic)) != 0)
    throw Error(name + ": not an .mfa model file (wrong magic bytes)");
  if (b.size() < kPrefixBytes || fileBytes < kPrefixBytes + 4)
    throw invalidModel(name, "file is truncated");
  const auto version = readBytesAt<std::uint32_t>(b, sizeof(kMagic));
  if (version < kOldestModelFormatVersion || version > kTimeModelFormatVersion)
    throw Error(name + ": .mfa format version " + std::to_string(version) +
                " is not supported; this build reads versions " +
                std::to_string(kOldestModelFormatVersion) + " to " +
                std::to_string(kTimeModelFormatVersion));
  const auto headerBytes = readBytesAt<std::uint32_t>(b, sizeof(kMagic) + 4);
  if (headerBytes > kMaxHeaderBytes || kPrefixBytes + headerBytes + 4 > fileBytes)
    throw invalidModel(name,
                       "header length " + std::to_string(headerBytes) + " does not fit the file");
  return {version, headerBytes};
}

// Degrees and control counts as the reader accepts them.
void checkShape(const Degree3& p, const Index3& n, const std::string& name) {
  for (int a = 0; a < 3; ++a) {
    if (p[a] < 1 || p[a] > kMaxDegree)
      throw invalidModel(name, "degree outside 1.." + std::to_string(kMaxDegree));
    if (n[a] < p[a] + 1 || n[a] > kMaxControlPerAxis)
      throw invalidModel(name, "control count out of range");
  }
}

Degree3 degreesOf(const json& h) {
  const Index3 degree = integers3(h, "degree");
  Degree3 p{};
  for (int a = 0; a < 3; ++a)
    p[a] = degree[a] < 1 || degree[a] > kMaxDegree ? 0 : static_cast<int>(degree[a]);
  return p;
}

std::uint32_t crc(const std::uint8_t* data, size_t n) {
  return crc32Of(data, n);
}

Vec3d vec3(const json& j, const char* key) {
  const auto a = j.at(key).get<std::array<double, 3>>();
  return Vec3d(a[0], a[1], a[2]);
}

}  // namespace

namespace {

// A model file in its pieces: prefix, header and stored knots; the control points; the mask;
// then comes the CRC-32 of all three.
struct ModelFilePieces {
  std::string head;
  std::shared_ptr<const std::string> ownedControls;
  std::string_view controls;
  std::string mask;
  std::string boundary;
};

ModelFilePieces modelFilePieces(const FileContent& content) {
  const Model& model = content.shape;
  ModelFilePieces p;
  p.mask = model.mask().empty() ? std::string() : compressedMask(model.mask());
  p.boundary = compressedBoundary(model.boundary());
  p.controls = codedControls(content, p.ownedControls);
  const auto rules = knotRules(model);
  const std::string header =
      paddedHeader(headerText(content, rules, static_cast<std::int64_t>(p.controls.size()),
                              static_cast<std::int64_t>(p.mask.size()),
                              static_cast<std::int64_t>(p.boundary.size())),
                   storedKnotBytes(content, rules));
  std::string& out = p.head;
  out.append(kMagic, sizeof(kMagic));
  appendBytes(out, content.time ? kTimeModelFormatVersion : kModelFormatVersion);
  appendBytes(out, static_cast<std::uint32_t>(header.size()));
  out += header;
  for (int a = 0; a < 3; ++a)
    if (stored(rules[a]))
      for (double k : model.spline().knots(a).knots()) appendBytes(out, k);
  if (content.time)
    for (double k : content.time->knots.knots()) appendBytes(out, k);
  return p;
}

std::uint32_t crcOf(std::uint32_t crc, std::string_view bytes) {
  return crc32Continue(crc, reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

}  // namespace

namespace {

void serializeContent(const FileContent& content,
                      const std::function<std::uint8_t*(size_t)>& allocate) {
  const ModelFilePieces p = modelFilePieces(content);
  const size_t body = p.head.size() + p.controls.size() + p.mask.size() + p.boundary.size();
  std::uint8_t* out = allocate(body + 4);
  std::uint8_t* at = out;
  for (const std::string_view piece : {std::string_view(p.head), p.controls,
                                       std::string_view(p.mask), std::string_view(p.boundary)}) {
    std::memcpy(at, piece.data(), piece.size());
    at += piece.size();
  }
  const std::uint32_t sum = crc(out, body);
  std::memcpy(at, &sum, 4);  // little-endian (asserted above)
}

std::string serializedContent(const FileContent& content) {
  std::string out;
  serializeContent(content, [&out](size_t bytes) {
    out.resize(bytes);
    return reinterpret_cast<std::uint8_t*>(out.data());
  });
  return out;
}

std::int64_t fileSizeOf(const FileContent& content) {
  const Model& model = content.shape;
  const std::int64_t mask =
      model.mask().empty() ? 0 : static_cast<std::int64_t>(compressedMask(model.mask()).size());
  const auto boundary = static_cast<std::int64_t>(compressedBoundary(model.boundary()).size());
  const auto rules = knotRules(model);
  const std::int64_t knotBytes = storedKnotBytes(content, rules);
  std::shared_ptr<const std::string> owned;
  const auto ctrl = static_cast<std::int64_t>(codedControls(content, owned).size());
  return static_cast<std::int64_t>(
             kPrefixBytes +
             paddedHeader(headerText(content, rules, ctrl, mask, boundary), knotBytes).size()) +
         knotBytes + ctrl + mask + boundary + 4;
}

void saveContent(const FileContent& content, const std::filesystem::path& path) {
  // Piece by piece, so that the control points go to the file from where they are held: a large
  // model is not copied into one buffer first.
  const ModelFilePieces p = modelFilePieces(content);
  AtomicFileWriter out(path);
  std::uint32_t sum = 0;
  for (const std::string_view piece : {std::string_view(p.head), p.controls,
                                       std::string_view(p.mask), std::string_view(p.boundary)}) {
    out.write(piece);
    sum = crcOf(sum, piece);
  }
  std::string tail;
  appendBytes(tail, sum);
  out.write(tail);
  out.commit();
}

}  // namespace

void serializeModel(const Model& model, const std::function<std::uint8_t*(size_t)>& allocate) {
  serializeContent(contentOf(model), allocate);
}

std::string serializeModel(const Model& model) {
  return serializedContent(contentOf(model));
}

std::string serializeModel(const TimeVaryingModel& model) {
  return serializedContent(contentOf(model));
}

std::int64_t modelFileSize(const TimeVaryingModel& model) {
  return fileSizeOf(contentOf(model));
}

std::int64_t codedControlBytes(const Model& m) {
  if (const std::string* kept = m.codedControlPoints())
    return static_cast<std::int64_t>(kept->size());
  if (m.controlCoding().coder == ControlCoder::kFloat32)
    return 4 * static_cast<std::int64_t>(m.spline().controlPoints().size());
  std::shared_ptr<const std::string> owned;
  return static_cast<std::int64_t>(codedControls(contentOf(m), owned).size());
}

std::int64_t modelFileSize(const Model& model) {
  return fileSizeOf(contentOf(model));
}

TimeVaryingModel parseTimeVaryingModel(std::span<const std::uint8_t> b, const std::string& name,
                                       std::uint32_t* formatVersion,
                                       std::shared_ptr<const void> owner) {
  auto bad = [&](const std::string& why) { return invalidModel(name, why); };
  const auto [version, headerBytes] = checkedPrefix(b, b.size(), name);

  json h;
  Degree3 p{};
  Index3 n{};
  Vec3d lo, hi;
  std::array<double, 2> range{};
  Provenance prov;
  std::optional<MaskKind> maskKind;  // version 2 on; a version-1 file has no mask
  Index3 maskDims{0, 0, 0};
  std::int64_t storedMaskBytes = 0;  // compressed size
  // The exact boundary of a mesh (optional): counts and compressed size.
  std::int64_t boundaryVertices = 0, boundaryTriangles = 0, storedBoundaryBytes = 0;
  ControlCoding coding;  // version 3 on; before: float32
  std::int64_t storedControlBytes = -1;
  std::array<std::int64_t, 3> knotSamples{-1, -1, -1};  // version 3: -1 stored, 0 uniform, N
  // Version 4: the time axis (its knots are read from the knot section).
  std::optional<TimeAxis> time;
  int timeDegree = 0;
  std::int64_t timeCount = 0;
  try {
    h = json::parse(b.begin() + kPrefixBytes, b.begin() + kPrefixBytes + headerBytes);
    if (h.value("format", "") != "mfadvr-model") throw bad("header is not an mfadvr-model header");
    p = degreesOf(h);
    n = integers3(h, "control_counts");
    checkShape(p, n, name);
    lo = vec3(h, "domain_min");
    hi = vec3(h, "domain_max");
    range = h.at("value_range").get<std::array<double, 2>>();
    if (h.contains("provenance")) prov = provenanceFromJson(h.at("provenance"));
    if (version >= 3) {
      const json& c = h.at("control_points");
      if (!c.is_object()) throw bad("control_points must be an object");
      const json& name = c.at("coding");
      if (!name.is_string()) throw bad("control-point coding must be a string");
      try {
        coding.coder = parseControlCoder(name.get<std::string>());
      } catch (const Error& e) {
        throw bad(e.what());
      }
      storedControlBytes = integerOr(c, "bytes", -1);
      const json& rules = h.at("knots");
      if (!rules.is_array() || rules.size() != 3) throw bad("knots must be an array of 3 rules");
      for (int a = 0; a < 3; ++a) {
        const json& r = rules[a];
        if (!r.is_object() || !r.contains("rule") || !r.at("rule").is_string())
          throw bad("a knot rule must be an object with a \"rule\" string");
        const std::string rule = r.at("rule").get<std::string>();
        if (rule == "uniform")
          knotSamples[a] = 0;
        else if (rule == "samples")
          knotSamples[a] = integerOr(r, "samples", -1);
        else if (rule != "stored")
          throw bad("unknown knot rule '" + rule + "' (samples, uniform or stored)");
        if (rule == "samples" && (knotSamples[a] < 2 || knotSamples[a] > kMaxRuleSamples))
          throw bad("knot rule sample count out of range");
      }
      if (coding.coder == ControlCoder::kZfp) {
        const json& t = c.at("tolerance");
        if (!t.is_number()) throw bad("zfp tolerance must be a number");
        coding.tolerance = t.get<double>();
        if (!(std::isfinite(coding.tolerance) && coding.tolerance > 0.0))
          throw bad("zfp tolerance must be positive and finite");
      }
    }
    if (version >= 2 && h.contains("mask")) {
      const json& m = h.at("mask");
      if (!m.is_object()) throw bad("mask must be an object");
      const json& kind = m.at("kind");
      if (!kind.is_string()) throw bad("mask kind must be a string");
      try {
        maskKind = parseMaskKind(kind.get<std::string>());
      } catch (const Error& e) {
        throw bad(e.what());
      }
      maskDims = integers3(m, "dims");
      storedMaskBytes = integerOr(m, "bytes", -1);
    }
    if (version >= 3 && h.contains("boundary")) {
      const json& m = h.at("boundary");
      if (!m.is_object()) throw bad("boundary must be an object");
      boundaryVertices = integerOr(m, "vertices", -1);
      boundaryTriangles = integerOr(m, "triangles", -1);
      storedBoundaryBytes = integerOr(m, "bytes", -1);
      if (boundaryVertices < 3 || boundaryVertices > kMaxBoundaryElements ||
          boundaryTriangles < 1 || boundaryTriangles > kMaxBoundaryElements)
        throw bad("boundary vertex or triangle count is missing or out of range");
      if (storedBoundaryBytes < 1 ||
          storedBoundaryBytes > static_cast<std::int64_t>(compressBound(static_cast<uLong>(
                                    boundaryRawBytes(boundaryVertices, boundaryTriangles)))))
        throw bad("boundary byte count is missing or out of range");
      // zlib's deflate shrinks data at most about 1032 times: a small section cannot claim a
      // boundary of gigabytes.
      if (boundaryRawBytes(boundaryVertices, boundaryTriangles) > 1032 * storedBoundaryBytes)
        throw bad("boundary byte count is too small for its vertex and triangle counts");
    }
    if (version >= 4 && h.contains("time")) {
      const json& t = h.at("time");
      if (!t.is_object()) throw bad("time must be an object");
      const std::int64_t degree = integerOr(t, "degree", 0);
      timeCount = integerOr(t, "control_count", 0);
      if (degree < 1 || degree > kMaxDegree)
        throw bad("time degree outside 1.." + std::to_string(kMaxDegree));
      timeDegree = static_cast<int>(degree);
      if (timeCount < degree + 1 || timeCount > kMaxControlPerAxis)
        throw bad("time control count out of range");
      const json& steps = t.at("steps");
      if (!steps.is_array() || steps.size() < 2 ||
          steps.size() > static_cast<size_t>(kMaxControlPerAxis))
        throw bad("time steps must be an array of 2 to " + std::to_string(kMaxControlPerAxis) +
                  " times");
      time.emplace();
      for (const json& v : steps) {
        if (!v.is_number()) throw bad("a time step is not a number");
        time->steps.push_back(v.get<double>());
      }
      const auto r = t.at("range").get<std::array<double, 2>>();
      time->begin = r[0];
      time->end = r[1];
    }
  } catch (const json::exception& e) {
    throw bad(std::string("header is corrupt (") + e.what() + ")");
  }
  for (int a = 0; a < 3; ++a) {
    if (!(std::isfinite(lo[a]) && std::isfinite(hi[a]) && hi[a] > lo[a]))
      throw bad("domain box is empty or not finite");
  }
  if (!(std::isfinite(range[0]) && std::isfinite(range[1]) && range[0] <= range[1]))
    throw bad("value range is not finite");
  if (maskKind) {
    try {
      DomainMask::validateDims(maskDims);  // bounds the node count by 2^31
    } catch (const Error& e) {
      throw bad(std::string("mask: ") + e.what());
    }
  }
  const std::int64_t packedMaskBytes = maskKind ? maskBytes(maskDims) : 0;
  // zlib never grows data by more than 0.1% + 12 bytes (compressBound).
  if (maskKind && (storedMaskBytes < 1 ||
                   storedMaskBytes > static_cast<std::int64_t>(
                                         compressBound(static_cast<uLong>(packedMaskBytes)))))
    throw bad("mask byte count is missing or out of range");

  // Sizes: every factor is at most 2^20, so the products below cannot overflow int64.
  std::int64_t knotCount = 0;  // stored ones
  for (int a = 0; a < 3; ++a) {
    if (knotSamples[a] > 0 && knotSamples[a] < n[a])
      throw bad(std::string("knot rule of axis ") + "xyz"[a] +
                ": fewer samples than control points");
    if (knotSamples[a] < 0) knotCount += n[a] + p[a] + 1;
  }
  if (time) knotCount += timeCount + timeDegree + 1;
  const std::int64_t slabs = time ? timeCount : 1;
  const std::int64_t spatialCount = n[0] * n[1] * n[2];
  if (spatialCount > std::numeric_limits<std::int64_t>::max() / 8 / slabs)
    throw bad("too many control points");
  const std::int64_t ctrlCount = spatialCount * slabs;
  if (version < 3) storedControlBytes = 4 * ctrlCount;
  if (storedControlBytes < 1 || storedControlBytes > maxCodedControlBytes(n, coding, slabs))
    throw bad("control-point byte count is missing or out of range for " +
              std::to_string(ctrlCount) + " control points coded " +
              controlCoderName(coding.coder));
  const std::int64_t expected = static_cast<std::int64_t>(kPrefixBytes + headerBytes) +
                                8 * knotCount + storedControlBytes + storedMaskBytes +
                                storedBoundaryBytes + 4;
  if (static_cast<std::int64_t>(b.size()) != expected)
    throw bad("size is " + std::to_string(b.size()) + " bytes but the header describes " +
              std::to_string(expected) +
              (static_cast<std::int64_t>(b.size()) < expected ? " (file is truncated)"
                                                              : " (trailing bytes)"));
  const auto stored = readBytesAt<std::uint32_t>(b, b.size() - 4);
  if (crc(b.data(), b.size() - 4) != stored) throw bad("checksum mismatch (file is corrupted)");

  size_t offset = kPrefixBytes + headerBytes;
  std::array<KnotVector, 3> knots;
  for (int a = 0; a < 3; ++a) {
    const int na = static_cast<int>(n[a]);
    if (knotSamples[a] == 0) {
      knots[a] = KnotVector::clampedUniform(p[a], na);
      continue;
    }
    if (knotSamples[a] > 0) {
      knots[a] = knotsForSamples(p[a], na, knotSamples[a]);
      continue;
    }
    std::vector<double> k(static_cast<size_t>(n[a] + p[a] + 1));
    std::memcpy(k.data(), b.data() + offset, k.size() * sizeof(double));
    offset += k.size() * sizeof(double);
    try {
      knots[a] = KnotVector::fromKnots(p[a], std::move(k));
    } catch (const Error& e) {
      throw bad(std::string("knots of axis ") + "xyz"[a] + ": " + e.what());
    }
  }
  if (time) {
    std::vector<double> k(static_cast<size_t>(timeCount + timeDegree + 1));
    std::memcpy(k.data(), b.data() + offset, k.size() * sizeof(double));
    offset += k.size() * sizeof(double);
    try {
      time->knots = KnotVector::fromKnots(timeDegree, std::move(k));
      validateTimeAxis(*time);
    } catch (const Error& e) {
      throw bad(std::string("time axis: ") + e.what());
    }
  }
  const auto controlSection = b.subspan(offset, static_cast<size_t>(storedControlBytes));
  offset += controlSection.size();
  // float32 control points where the bytes lie, when their owner keeps them and they are
  // aligned (files written since the header was padded); else decoded into a new array.
  const bool inPlace =
      !time && owner && coding.coder == ControlCoder::kFloat32 &&
      storedControlBytes == 4 * ctrlCount &&
      reinterpret_cast<std::uintptr_t>(controlSection.data()) % alignof(float) == 0;
  std::vector<float> decoded;
  std::span<const float> ctrl;
  if (inPlace) {
    ctrl = {reinterpret_cast<const float*>(controlSection.data()), static_cast<size_t>(ctrlCount)};
  } else {
    try {
      decoded = decodeControlPoints(controlSection, n, coding, slabs);
    } catch (const Error& e) {
      throw bad(e.what());
    }
    ctrl = decoded;
  }
  for (float c : ctrl)
    if (!std::isfinite(c)) throw bad("a control point is NaN or infinite");
  // A time-varying model's spatial shape holds its first slab until the model is assembled.
  std::vector<float> slabs4d;
  if (time) {
    slabs4d = std::move(decoded);
    decoded.assign(slabs4d.begin(), slabs4d.begin() + spatialCount);
  }
  Model model(inPlace ? TensorBSpline(std::move(knots), std::move(owner), ctrl)
                      : TensorBSpline(std::move(knots), std::move(decoded)),
              DomainBox{lo, hi}, range[0], range[1], std::move(prov));
  if (maskKind) {
    std::vector<std::uint8_t> packed(static_cast<size_t>(packedMaskBytes));
    uLongf size = static_cast<uLongf>(packed.size());
    if (uncompress(packed.data(), &size, b.data() + offset, static_cast<uLong>(storedMaskBytes)) !=
            Z_OK ||
        size != packed.size())
      throw bad("mask data is corrupt or does not hold its " + std::to_string(maskDims[0]) + "x" +
                std::to_string(maskDims[1]) + "x" + std::to_string(maskDims[2]) + " nodes");
    const std::uint8_t* bits = packed.data();
    const std::int64_t count = maskDims[0] * maskDims[1] * maskDims[2];
    if (count % 8 != 0 && (bits[packedMaskBytes - 1] >> (count % 8)) != 0)
      throw bad("mask padding bits are not zero");
    std::vector<std::uint8_t> nodes(static_cast<size_t>(count));
    for (std::int64_t i = 0; i < count; ++i) nodes[i] = (bits[i / 8] >> (i % 8)) & 1u;
    model.setMask(DomainMask(*maskKind, maskDims, std::move(nodes)));
    offset += static_cast<size_t>(storedMaskBytes);
  }
  if (boundaryTriangles > 0) {
    std::vector<std::uint8_t> raw(
        static_cast<size_t>(boundaryRawBytes(boundaryVertices, boundaryTriangles)));
    uLongf size = static_cast<uLongf>(raw.size());
    if (uncompress(raw.data(), &size, b.data() + offset, static_cast<uLong>(storedBoundaryBytes)) !=
            Z_OK ||
        size != raw.size())
      throw bad("boundary data is corrupt or does not hold its " +
                std::to_string(boundaryVertices) + " vertices and " +
                std::to_string(boundaryTriangles) + " triangles");
    std::vector<Vec3f> vertices(static_cast<size_t>(boundaryVertices));
    for (size_t i = 0; i < vertices.size(); ++i) {
      float xyz[3];
      std::memcpy(xyz, raw.data() + 12 * i, 12);
      vertices[i] = Vec3f(xyz[0], xyz[1], xyz[2]);
    }
    std::vector<BoundaryTriangle> triangles(static_cast<size_t>(boundaryTriangles));
    std::memcpy(triangles.data(), raw.data() + 12 * vertices.size(), 12 * triangles.size());
    try {
      model.setBoundary(
          std::make_shared<const DomainBoundary>(std::move(vertices), std::move(triangles)));
    } catch (const Error& e) {
      throw bad(e.what());
    }
  }
  if (formatVersion) *formatVersion = version;
  TimeVaryingModel out = time ? TimeVaryingModel(model, std::move(*time), std::move(slabs4d))
                              : TimeVaryingModel(std::move(model));
  // Keep the coded bytes of lossy codings, so that writing the model again stores the same
  // bytes (coding decoded values again would move them once more).
  if (coding.coder == ControlCoder::kZfp)
    out.setControlCoding(
        coding, std::make_shared<const std::string>(
                    reinterpret_cast<const char*>(controlSection.data()), controlSection.size()));
  else
    out.setControlCoding(coding);
  return out;
}

Model parseModel(std::span<const std::uint8_t> b, const std::string& name,
                 std::uint32_t* formatVersion, std::shared_ptr<const void> owner) {
  return parseTimeVaryingModel(b, name, formatVersion, std::move(owner)).first();
}

void saveModel(const Model& model, const std::filesystem::path& path) {
  saveContent(contentOf(model), path);
}

void saveModel(const TimeVaryingModel& model, const std::filesystem::path& path) {
  saveContent(contentOf(model), path);
}

TimeVaryingModel loadTimeVaryingModel(const std::filesystem::path& path,
                                      std::uint32_t* formatVersion) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error("cannot read " + path.string() + ": is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path.string() + ": " + std::strerror(errno));
  // Read at its size in one piece: a buffer grown while reading would hold up to twice the
  // file's bytes (measured: a 537 MB model peaked at 1.6 GB while loading).
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw Error("cannot read " + path.string() + ": " + ec.message());
  // The model keeps the buffer: its float32 control points stay where they were read.
  auto bytes = std::make_shared<std::vector<std::uint8_t>>(static_cast<size_t>(size));
  in.read(reinterpret_cast<char*>(bytes->data()), static_cast<std::streamsize>(bytes->size()));
  if (in.gcount() != static_cast<std::streamsize>(bytes->size()) || in.peek() != EOF)
    throw Error("cannot read " + path.string() + ": its size changed while it was read");
  const std::span<const std::uint8_t> view(*bytes);
  return parseTimeVaryingModel(view, path.string(), formatVersion, std::move(bytes));
}

Model loadModel(const std::filesystem::path& path, std::uint32_t* formatVersion) {
  return loadTimeVaryingModel(path, formatVersion).first();
}

std::int64_t loadedModelBytes(const ModelFileSummary& m) {
  const std::int64_t points =
      m.controlCounts[0] * m.controlCounts[1] * m.controlCounts[2] * m.slabs;
  return 4 * points + (m.coder == ControlCoder::kZfp ? static_cast<std::int64_t>(m.fileBytes) : 0);
}

ModelFileSummary summarizeModelHead(std::span<const std::uint8_t> head, std::uint64_t fileBytes,
                                    const std::string& name) {
  const ModelPrefix prefix = checkedPrefix(head, fileBytes, name);
  if (head.size() < kPrefixBytes + prefix.headerBytes)
    throw invalidModel(name, "header is incomplete");
  ModelFileSummary out;
  out.fileBytes = fileBytes;
  bool storedKnots[3] = {true, true, true};
  try {
    const json h =
        json::parse(head.begin() + kPrefixBytes, head.begin() + kPrefixBytes + prefix.headerBytes);
    out.degree = degreesOf(h);
    out.controlCounts = integers3(h, "control_counts");
    if (prefix.version >= 3) {
      const json& coding = h.at("control_points").at("coding");
      if (!coding.is_string()) throw invalidModel(name, "control-point coding must be a string");
      out.coder = parseControlCoder(coding.get<std::string>());
    }
    // The knots the file stores: all of them before version 3, else those whose rule is
    // "stored".
    for (int a = 0; a < 3; ++a)
      storedKnots[a] = prefix.version < 3 || h.at("knots").at(a).at("rule") == "stored";
    if (prefix.version >= 4 && h.contains("time")) {
      out.slabs = integerOr(h.at("time"), "control_count", 0);
      if (out.slabs < 2 || out.slabs > kMaxControlPerAxis)
        throw invalidModel(name, "time control count out of range");
    }
  } catch (const json::exception& e) {
    throw invalidModel(name, std::string("header is corrupt (") + e.what() + ")");
  }
  checkShape(out.degree, out.controlCounts, name);
  // The control points start after the stored knots (every count is at most 2^20 here).
  std::int64_t start = static_cast<std::int64_t>(kPrefixBytes + prefix.headerBytes);
  for (int a = 0; a < 3; ++a)
    if (storedKnots[a]) start += 8 * (out.controlCounts[a] + out.degree[a] + 1);
  out.readInPlace =
      out.slabs == 1 && out.coder == ControlCoder::kFloat32 && start % alignof(float) == 0;
  return out;
}

ModelFileSummary summarizeModelFile(const std::filesystem::path& path, std::uint64_t offset,
                                    std::uint64_t bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path.string() + ": " + std::strerror(errno));
  auto readAt = [&](std::uint64_t at, std::uint64_t n) {
    std::vector<std::uint8_t> out(static_cast<size_t>(n));
    in.seekg(static_cast<std::streamoff>(offset + at));
    in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n));
    out.resize(static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
    in.clear();
    return out;
  };
  std::vector<std::uint8_t> head = readAt(0, std::min<std::uint64_t>(bytes, kPrefixBytes));
  if (head.size() == kPrefixBytes && std::memcmp(head.data(), kMagic, sizeof(kMagic)) == 0) {
    const std::uint64_t headerBytes =
        std::min(readBytesAt<std::uint32_t>(head, sizeof(kMagic) + 4), kMaxHeaderBytes);
    head = readAt(0, std::min<std::uint64_t>(bytes, kPrefixBytes + headerBytes));
  }
  return summarizeModelHead(head, bytes, path.string());
}

ModelFileSummary summarizeModelFile(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw Error("cannot open " + path.string() + ": " + ec.message());
  return summarizeModelFile(path, 0, size);
}

}  // namespace mfadvr
