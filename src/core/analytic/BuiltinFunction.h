#pragma once
// Analytic scalar fields on [-1,1]^3 with exact value and gradient: the ground truth of the
// evaluation (docs/architecture.md, Evaluation protocol) and inputs that need no files.
//
// Spec syntax: builtin:NAME, builtin:NAME:N (N^3 samples) or builtin:NAME:NXxNYxNZ.
// Names: marschner-lobb (default 41^3), gaussian-beam (default 64^3),
// gaussian-beams (default 128^3; a diagonal row of four beams whose boxes hold 64^3, 32^3,
// 16^3 and 8^3 samples of that default grid), ct-head (default 128^3; a head phantom in
// Hounsfield units for the CT transfer-function presets), soft-and-sharp (default 64^3; a sharp
// high-contrast ball beside a soft low-contrast blob, for quantization studies). docs/builtins.md
// states the formulas.
#include <memory>
#include <string>
#include <vector>

#include "core/grid/StructuredGrid.h"
#include "core/util/Vec.h"

namespace mfadvr {

class BuiltinFunction {
 public:
  virtual ~BuiltinFunction() = default;
  virtual std::string name() const = 0;
  virtual double value(const Vec3d& x) const = 0;
  // Value and physical gradient at x, one pass.
  virtual double valueGradient(const Vec3d& x, Vec3d& gradient) const = 0;
  // The grid the bare `builtin:NAME` spec samples.
  virtual Index3 defaultDims() const = 0;

  static Vec3d domainMin() { return Vec3d::Constant(-1.0); }
  static Vec3d domainMax() { return Vec3d::Constant(1.0); }
};

// The names `builtin:` accepts.
std::vector<std::string> builtinNames();

// Throws mfadvr::Error for an unknown name.
std::unique_ptr<BuiltinFunction> makeBuiltin(const std::string& name);

struct BuiltinSpec {
  std::string name;
  Index3 dims{0, 0, 0};
};

inline bool isBuiltinSpec(const std::string& input) {
  return input.rfind("builtin:", 0) == 0;
}

// Parses builtin:NAME[:N | :NXxNYxNZ]; throws mfadvr::Error with the accepted forms.
BuiltinSpec parseBuiltinSpec(const std::string& spec);

// The row of beams of `gaussian-beams`: beam k (0..3) is the single beam shrunk into the
// axis-aligned cube of side 2^-k centred at `centre` (on the diagonal x = y of the plane z = 0).
// The evaluation frames these cubes for its zoom levels 1..4.
constexpr int kGaussianBeamCount = 4;
struct BeamBox {
  Vec3d centre;
  double side = 0.0;
};
// Throws mfadvr::Error for k outside 0..3.
BeamBox gaussianBeamsBox(int k);

// The grid of dims points per axis spanning [-1,1]^3 (endpoints included), without values.
StructuredGrid builtinGridLayout(const BuiltinFunction& f, const Index3& dims);
// Evaluates the function at every sample position of `grid` (any box of such a layout).
void fillBuiltinSamples(const BuiltinFunction& f, StructuredGrid& grid);

// Samples the function on dims points per axis spanning [-1,1]^3 (endpoints included).
StructuredGrid sampleBuiltin(const BuiltinFunction& f, const Index3& dims);

// parseBuiltinSpec + makeBuiltin + sampleBuiltin.
StructuredGrid sampleBuiltinSpec(const std::string& spec);

}  // namespace mfadvr
