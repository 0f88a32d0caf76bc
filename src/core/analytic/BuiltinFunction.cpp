#include "core/analytic/BuiltinFunction.h"

#include <cmath>
#include <numbers>
#include <regex>

#include <tbb/parallel_for.h>

#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr {
namespace {

constexpr double kPi = std::numbers::pi;

// Marschner & Lobb (1994), fM = 6, alpha = 0.25 (paper eq. 2).
class MarschnerLobb final : public BuiltinFunction {
 public:
  std::string name() const override { return "marschner-lobb"; }
  Index3 defaultDims() const override { return {41, 41, 41}; }
  double value(const Vec3d& x) const override {
    const double r = std::hypot(x[0], x[1]);
    const double rho = std::cos(2.0 * kPi * kFm * std::cos(kPi * r / 2.0));
    return (1.0 - std::sin(kPi * x[2] / 2.0) + kAlpha * (1.0 + rho)) / (2.0 * (1.0 + kAlpha));
  }
  double valueGradient(const Vec3d& x, Vec3d& g) const override {
    const double r = std::hypot(x[0], x[1]);
    const double phase = 2.0 * kPi * kFm * std::cos(kPi * r / 2.0);
    const double rho = std::cos(phase);
    const double scale = 1.0 / (2.0 * (1.0 + kAlpha));
    // d rho / dr divided by r; sin(pi r/2)/r tends to pi/2 at the axis.
    const double sinc = r > 1e-8 ? std::sin(kPi * r / 2.0) / r : kPi / 2.0;
    const double drho_over_r = std::sin(phase) * 2.0 * kPi * kFm * (kPi / 2.0) * sinc;
    g[0] = scale * kAlpha * drho_over_r * x[0];
    g[1] = scale * kAlpha * drho_over_r * x[1];
    g[2] = -scale * (kPi / 2.0) * std::cos(kPi * x[2] / 2.0);
    return (1.0 - std::sin(kPi * x[2] / 2.0) + kAlpha * (1.0 + rho)) * scale;
  }

 private:
  static constexpr double kFm = 6.0;
  static constexpr double kAlpha = 0.25;
};

// One radial Gaussian: vmax * exp(-(l - mu)^2 / (2 sigma^2)), l = |x - c| / R (paper eq. 1, with
// Vmin = 0 and mu = 0).
struct Beam {
  Vec3d center;
  double radius;
  double valueGradient(const Vec3d& x, Vec3d* g) const {
    constexpr double kVmax = 255.0, kSigma = 1.0 / 3.0;
    const Vec3d d = x - center;
    const double l2 = d.squaredNorm() / (radius * radius);
    const double v = kVmax * std::exp(-l2 / (2.0 * kSigma * kSigma));
    // d/dx of exp(-|d|^2 / (2 sigma^2 R^2)) = -d / (sigma^2 R^2) * exp(...)
    if (g) *g = -v / (kSigma * kSigma * radius * radius) * d;
    return v;
  }
};

class GaussianBeam final : public BuiltinFunction {
 public:
  std::string name() const override { return "gaussian-beam"; }
  Index3 defaultDims() const override { return {64, 64, 64}; }
  double value(const Vec3d& x) const override { return beam_.valueGradient(x, nullptr); }
  double valueGradient(const Vec3d& x, Vec3d& g) const override {
    return beam_.valueGradient(x, &g);
  }

 private:
  Beam beam_{Vec3d::Zero(), std::sqrt(3.0)};
};

// Four beams on the diagonal x = y of the plane z = 0. Beam k is the single beam shrunk into an
// axis-aligned box of side 2^-k; the boxes touch corner to corner from (-1,-1) onwards, so that
// on the default 128^3 grid (spacing 2/127) a view of box k covers about 64^3 / 8^k samples.
class GaussianBeams final : public BuiltinFunction {
 public:
  GaussianBeams() {
    for (int k = 0; k < kGaussianBeamCount; ++k) {
      const BeamBox box = gaussianBeamsBox(k);
      beams_[k] = Beam{box.centre, std::sqrt(3.0) * box.side / 2.0};
    }
  }
  std::string name() const override { return "gaussian-beams"; }
  Index3 defaultDims() const override { return {128, 128, 128}; }
  double value(const Vec3d& x) const override {
    double v = 0.0;
    for (const Beam& b : beams_) v += b.valueGradient(x, nullptr);
    return v;
  }
  double valueGradient(const Vec3d& x, Vec3d& g) const override {
    double v = 0.0;
    g.setZero();
    for (const Beam& b : beams_) {
      Vec3d gb;
      v += b.valueGradient(x, &gb);
      g += gb;
    }
    return v;
  }

 private:
  Beam beams_[kGaussianBeamCount];
};

// A CT-like head phantom in Hounsfield units, for trying the CT transfer-function presets on
// data with the value ranges of a real scan: air (-1000) around a head of soft tissue (40), a
// skull cap of bone (1000) over its upper part, brain (30), and contrast-filled vessels (350):
// two horizontal rings below the cap and a vertical vessel joining them. Each structure is a
// smooth indicator S(t) = 1 / (1 + exp(-t / w)) of an implicit function t that is smooth
// everywhere (squared distances, planes), so that the value and its gradient are analytic.
class CtHead final : public BuiltinFunction {
 public:
  std::string name() const override { return "ct-head"; }
  Index3 defaultDims() const override { return {128, 128, 128}; }
  double value(const Vec3d& x) const override {
    Vec3d g;
    return valueGradient(x, g);
  }
  double valueGradient(const Vec3d& x, Vec3d& g) const override {
    Vec3d gHead, gOuter, gInner;
    const double head = ellipsoid(x, 1.0, gHead);
    const double outer = ellipsoid(x, 0.93, gOuter);
    const double inner = ellipsoid(x, 0.84, gInner);
    // Smooth union of the vessels, U = 1 - prod(1 - T_i), confined to the brain.
    Vec3d gTubes[3];
    const double tubes[3] = {ring(x, -0.05, gTubes[0]), ring(x, -0.4, gTubes[1]),
                             column(x, gTubes[2])};
    double rest = 1.0;
    for (double t : tubes) rest *= 1.0 - t;
    Vec3d gUnion = Vec3d::Zero();
    for (int i = 0; i < 3; ++i) {
      double others = 1.0;
      for (int j = 0; j < 3; ++j)
        if (j != i) others *= 1.0 - tubes[j];
      gUnion += others * gTubes[i];
    }
    const double vessels = (1.0 - rest) * inner;
    const Vec3d gVessels = inner * gUnion + (1.0 - rest) * gInner;
    // The skull: the shell between the outer and inner ellipsoids, above z = 0.15.
    double capSlope = 0.0;
    const double cap = smoothStep(x[2] - 0.15, capSlope);
    const double shell = outer - inner;
    const Vec3d gSkull = cap * (gOuter - gInner) + Vec3d(0.0, 0.0, capSlope * shell);
    g = kTissue * gHead + kBone * gSkull + kBrain * gInner + kContrast * gVessels;
    return kAir + kTissue * head + kBone * cap * shell + kBrain * inner + kContrast * vessels;
  }

 private:
  // Steps of the value from one material to the next.
  static constexpr double kAir = -1000.0, kTissue = 1040.0, kBone = 960.0, kBrain = -10.0,
                          kContrast = 320.0;
  static constexpr double kWidth = 0.012;  // of the transitions, in domain units
  static constexpr double kRadii[3] = {0.72, 0.86, 0.9};

  // S(t) and dS/dt.
  static double smoothStep(double t, double& slope) {
    const double s = 1.0 / (1.0 + std::exp(-t / kWidth));
    slope = s * (1.0 - s) / kWidth;
    return s;
  }
  // Inside the head's ellipsoid scaled by `scale`: t = (1 - q^2) / 2 * 0.8, with q the
  // ellipsoidal radius (about the distance to the surface near it, for radii near 0.8).
  static double ellipsoid(const Vec3d& x, double scale, Vec3d& g) {
    double q2 = 0.0;
    Vec3d dq2;
    for (int a = 0; a < 3; ++a) {
      const double r = kRadii[a] * scale;
      q2 += x[a] * x[a] / (r * r);
      dq2[a] = 2.0 * x[a] / (r * r);
    }
    double slope = 0.0;
    const double s = smoothStep(0.4 * (1.0 - q2), slope);
    g = -0.4 * slope * dq2;
    return s;
  }
  // A tube of radius r around a curve, from the squared distance d2 to it:
  // t = (r^2 - d2) / (2 r), about r - d near the wall.
  static double tube(double d2, const Vec3d& dd2, Vec3d& g) {
    constexpr double r = 0.045;
    double slope = 0.0;
    const double s = smoothStep((r * r - d2) / (2.0 * r), slope);
    g = -slope / (2.0 * r) * dd2;
    return s;
  }
  // A horizontal ring of radius 0.35 around the z axis at height h.
  static double ring(const Vec3d& x, double h, Vec3d& g) {
    constexpr double R = 0.35;
    const double rho = std::sqrt(x[0] * x[0] + x[1] * x[1]);
    const double d2 = (rho - R) * (rho - R) + (x[2] - h) * (x[2] - h);
    Vec3d dd2(0.0, 0.0, 2.0 * (x[2] - h));
    if (rho > 1e-12) {  // on the axis the ring is far away and d2 is flat in x and y
      dd2[0] = 2.0 * (rho - R) * x[0] / rho;
      dd2[1] = 2.0 * (rho - R) * x[1] / rho;
    }
    return tube(d2, dd2, g);
  }
  // A vertical vessel through (0.35, 0) joining the rings.
  static double column(const Vec3d& x, Vec3d& g) {
    const double dx = x[0] - 0.35, dy = x[1];
    return tube(dx * dx + dy * dy, Vec3d(2.0 * dx, 2.0 * dy, 0.0), g);
  }
};

// A scan-like field for quantization studies: a sharp, high-contrast ball (bone beside soft
// tissue) and a soft, low-contrast Gaussian blob on a gently varying background. At 8 bits the
// blob spans about 15 levels and the background 10: quantization terraces show on their
// isosurfaces, while the ball's edge (180 units over 4 w) needs little or no smoothing.
// F = 30 + 180 H + 12 B + 4 sin(kWave y), H = 1 / (1 + exp((|x - c1| - r) / w)),
// B = exp(-|x - c2|^2 / (2 sigma^2)).
class SoftAndSharp final : public BuiltinFunction {
 public:
  std::string name() const override { return "soft-and-sharp"; }
  Index3 defaultDims() const override { return {64, 64, 64}; }
  double value(const Vec3d& x) const override {
    Vec3d g;
    return valueGradient(x, g);
  }
  double valueGradient(const Vec3d& x, Vec3d& g) const override {
    const Vec3d d1 = x - Vec3d(-0.35, 0.0, 0.0), d2 = x - Vec3d(0.5, 0.0, 0.05);
    const double r1 = d1.norm();
    const double h = 1.0 / (1.0 + std::exp((r1 - kBallRadius) / kBallWidth));
    const double b = std::exp(-d2.squaredNorm() / (2.0 * kBlobSigma * kBlobSigma));
    // dH/dx = -H (1 - H) / w * d1 / |d1| (zero at the centre, where H is flat).
    const Vec3d gBall = r1 > 1e-12 ? Vec3d(-h * (1.0 - h) / kBallWidth / r1 * d1) : Vec3d::Zero();
    const Vec3d gBlob = -b / (kBlobSigma * kBlobSigma) * d2;
    g = kBall * gBall + kBlob * gBlob +
        Vec3d(0.0, kWave * kWaveAmplitude * std::cos(kWave * x[1]), 0.0);
    return kBackground + kBall * h + kBlob * b + kWaveAmplitude * std::sin(kWave * x[1]);
  }

 private:
  static constexpr double kBackground = 30.0, kBall = 180.0, kBlob = 12.0, kWaveAmplitude = 4.0;
  static constexpr double kBallRadius = 0.35, kBallWidth = 0.015, kBlobSigma = 0.22, kWave = 5.6;
};

}  // namespace

BeamBox gaussianBeamsBox(int k) {
  if (k < 0 || k >= kGaussianBeamCount)
    throw Error("gaussian-beams has beams 0.." + std::to_string(kGaussianBeamCount - 1) + ", not " +
                std::to_string(k));
  double start = -1.0;
  for (int i = 0; i < k; ++i) start += std::ldexp(1.0, -i);
  const double side = std::ldexp(1.0, -k);
  const double c = start + side / 2.0;
  return BeamBox{Vec3d(c, c, 0.0), side};
}

std::vector<std::string> builtinNames() {
  return {"marschner-lobb", "gaussian-beam", "gaussian-beams", "ct-head", "soft-and-sharp"};
}

std::unique_ptr<BuiltinFunction> makeBuiltin(const std::string& name) {
  if (name == "marschner-lobb") return std::make_unique<MarschnerLobb>();
  if (name == "gaussian-beam") return std::make_unique<GaussianBeam>();
  if (name == "gaussian-beams") return std::make_unique<GaussianBeams>();
  if (name == "ct-head") return std::make_unique<CtHead>();
  if (name == "soft-and-sharp") return std::make_unique<SoftAndSharp>();
  std::string known;
  for (const auto& n : builtinNames()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown built-in function '" + name + "' (known: " + known + ")");
}

BuiltinSpec parseBuiltinSpec(const std::string& spec) {
  static const std::regex re(R"(builtin:([a-z\-]+)(?::(\d+)(?:x(\d+)x(\d+))?)?)");
  std::smatch m;
  if (!std::regex_match(spec, m, re))
    throw Error("malformed built-in spec '" + spec +
                "': expected builtin:NAME, builtin:NAME:N or builtin:NAME:NXxNYxNZ");
  BuiltinSpec out;
  out.name = m[1];
  const auto f = makeBuiltin(out.name);
  if (!m[2].matched) {
    out.dims = f->defaultDims();
    return out;
  }
  auto parse = [&](const std::string& s) -> std::int64_t {
    if (s.size() > 6) throw Error("grid size in '" + spec + "' is too large");
    const long v = std::stol(s);
    if (v < 2) throw Error("grid size in '" + spec + "' must be at least 2 per axis");
    return v;
  };
  const std::int64_t nx = parse(m[2]);
  out.dims = m[3].matched ? Index3{nx, parse(m[3]), parse(m[4])} : Index3{nx, nx, nx};
  return out;
}

StructuredGrid builtinGridLayout(const BuiltinFunction& f, const Index3& dims) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 2) throw Error("a built-in function is sampled with at least 2 samples per axis");
  StructuredGrid g;
  g.dims = dims;
  const Vec3d lo = BuiltinFunction::domainMin(), hi = BuiltinFunction::domainMax();
  g.origin = lo;
  for (int a = 0; a < 3; ++a) g.spacing[a] = (hi[a] - lo[a]) / static_cast<double>(dims[a] - 1);
  g.source = "builtin:" + f.name() + ":" + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) +
             "x" + std::to_string(dims[2]);
  g.fieldName = f.name();
  g.sampleType = "float64";
  g.inputBytes = g.sampleCount() * static_cast<std::int64_t>(sizeof(double));
  return g;
}

void fillBuiltinSamples(const BuiltinFunction& f, StructuredGrid& g) {
  requireMemory(std::int64_t(sizeof(float)) * g.sampleCount(),
                "sampling " + f.name() + " on " + std::to_string(g.dims[0]) + "x" +
                    std::to_string(g.dims[1]) + "x" + std::to_string(g.dims[2]) + " samples");
  g.values.resize(static_cast<size_t>(g.sampleCount()));
  tbb::parallel_for(std::int64_t(0), g.dims[2], [&](std::int64_t k) {
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i) g.at(i, j, k) = f.value(g.position(i, j, k));
  });
}

StructuredGrid sampleBuiltin(const BuiltinFunction& f, const Index3& dims) {
  StructuredGrid g = builtinGridLayout(f, dims);
  fillBuiltinSamples(f, g);
  return g;
}

StructuredGrid sampleBuiltinSpec(const std::string& spec) {
  const BuiltinSpec s = parseBuiltinSpec(spec);
  return sampleBuiltin(*makeBuiltin(s.name), s.dims);
}

}  // namespace mfadvr
