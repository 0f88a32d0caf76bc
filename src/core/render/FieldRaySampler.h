#pragma once
// Any Field's sampler (Field.h: grid filters, the analytic truth, derived fields) as a ray
// sampler for the shared per-ray integration (kernel/RayIntegrator.h). Host only.
//
// Shaded renders ask the field for value and gradient together at every sample, as the grid
// filters compute both at once; unshaded ones ask for the value alone. Batches of kSampleBatch
// points (SampleBatch.h). Curvature renders take the Hessian from differences of the field's own
// gradient (PointwiseBatch::hessian).
#include <concepts>

#include "core/field/Field.h"
#include "core/render/kernel/SampleBatch.h"

namespace mfadvr {

struct RaySegment;  // kernel/RaySteps.h

template <class S, bool Shade>
class FieldRaySampler : public PointwiseBatch<FieldRaySampler<S, Shade>, kSampleBatch, Shade> {
 public:
  static constexpr bool kSkipsEmptySpace = false;
  static constexpr bool kHasInside = requires(S & s, const Vec3d& x) {
    { s.inside(x) } -> std::convertible_to<bool>;
  };

  // differenceStep: the Hessian's difference step (world units; PointwiseBatch::hessian).
  explicit FieldRaySampler(S sampler, double differenceStep = 1e-4)
      : s_(std::move(sampler)), step_(differenceStep) {}

  void beginRay(const RaySegment&) {}

  bool inside(const double p[3]) {
    if constexpr (kHasInside)
      return s_.inside(Vec3d(p[0], p[1], p[2]));
    else
      return true;
  }

  bool emptyAt(const double*, double&) { return false; }

  float pointValue(const double p[3]) { return s_.value(Vec3d(p[0], p[1], p[2])); }

  float pointValueGradient(const double p[3], float g[3]) {
    const ValueGradient vg = s_.valueGradient(Vec3d(p[0], p[1], p[2]));
    for (int a = 0; a < 3; ++a) g[a] = vg.gradient[a];
    return vg.value;
  }

  double differenceStep(int) const { return step_; }

  // The polynomial pieces of a ray, where the field has them (the grid filters but nearest):
  // the isosurface blend then walks them exactly (kernel/IsoSurfaceWalk.h) instead of sampling.
  static constexpr bool kHasPieces = requires(const S& s, const double* o, double t) {
    s.rayDegree();
    s.pieceEnd(o, o, t);
  };
  int rayDegree() const
    requires kHasPieces
  {
    return s_.rayDegree();
  }
  double pieceEnd(const double o[3], const double d[3], double t) const
    requires kHasPieces
  {
    return s_.pieceEnd(o, d, t);
  }

  // Whether samples can fall outside (a sampler without inside() cannot; one with masked()
  // says so: a model without a mask cannot).
  bool canBeOutside() const {
    if constexpr (!kHasInside)
      return false;
    else if constexpr (requires { s_.masked(); })
      return s_.masked();
    else
      return true;
  }

 private:
  S s_;
  double step_;
};

}  // namespace mfadvr
