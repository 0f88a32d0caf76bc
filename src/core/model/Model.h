#pragma once
// An MFA model: a tensor-product B-spline, the physical box it covers, the value range of the
// data it was fitted to, and where it came from.
//
// Queries take physical coordinates. The box maps affinely onto the spline's [0,1]^3, so a
// physical derivative is the parametric one divided by the box extent of that axis
// (docs/architecture.md, Parameter space and gradients). Points outside the box are clamped onto
// it.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "core/mask/DomainBoundary.h"
#include "core/mask/DomainMask.h"
#include "core/model/ControlCoding.h"
#include "core/model/ControlEnvelope.h"
#include "core/model/DomainBox.h"
#include "core/spline/TensorBSpline.h"
#include "core/util/Vec.h"

namespace mfadvr {

// What the model was fitted from and how well; stored in the .mfa header and shown by `info`.
struct Provenance {
  std::string source;            // input path or builtin spec
  std::string field;             // scalar name
  std::string sampleType;        // source storage type
  Index3 sampleDims{0, 0, 0};    // input grid size (0 when scattered)
  std::int64_t inputPoints = 0;  // scattered inputs: number of points (0 for grids)
  std::string fieldAssociation;  // scattered inputs: e.g. "point data"
  std::int64_t inputBytes = 0;
  std::string encoder;  // e.g. "structured-least-squares"
  std::string created;  // UTC time, ISO 8601
  std::string toolVersion;
  double fitSeconds = 0.0;
  double maxError = 0.0;  // absolute, over all input samples
  double rmsError = 0.0;  // absolute
  double smoothing = 0.0;  // lambda of the roughness penalty (DerivativePenalty.h); 0: none
};

class Model {
 public:
  Model() = default;
  Model(TensorBSpline spline, DomainBox domain, double valueMin, double valueMax,
        Provenance provenance = {});

  const TensorBSpline& spline() const { return spline_; }
  const DomainBox& domain() const { return domain_; }
  double valueMin() const { return valueMin_; }
  double valueMax() const { return valueMax_; }
  // The range transfer functions normalize by (e.g. the whole volume's, for one block of it).
  void setValueRange(double valueMin, double valueMax) {
    valueMin_ = valueMin;
    valueMax_ = valueMax;
  }
  const Provenance& provenance() const { return provenance_; }
  Provenance& provenance() { return provenance_; }

  // Where the model is defined (empty: the whole box). Models of meshes and point clouds carry
  // one; the renderer treats samples outside it as empty.
  const DomainMask& mask() const { return mask_; }
  void setMask(DomainMask mask) { mask_ = std::move(mask); }
  // Models of meshes also carry the mesh's exact boundary (DomainBoundary.h), which then decides
  // what is inside; the mask stays for readers that do not use the boundary and for rays that
  // cross the boundary more often than the renderer follows.
  const DomainBoundary* boundary() const { return boundary_ ? boundary_.get() : nullptr; }
  void setBoundary(std::shared_ptr<const DomainBoundary> boundary) {
    boundary_ = boundary && !boundary->empty() ? std::move(boundary) : nullptr;
  }
  bool inside(const Vec3d& x) const {
    if (boundary_) return boundary_->contains(x);
    return mask_.insideParameter(domain_.toParameter(x));  // clamps onto the box
  }

  // An instant of a time-varying model carries the envelope of its slabs (ControlEnvelope.h):
  // renderers that keep skip flags across frames build them from it once for every instant.
  // Null for other models; the constructor never sets it, so a model made from new control
  // points has none.
  const ControlEnvelope* controlEnvelope() const { return envelope_.get(); }
  const std::shared_ptr<const ControlEnvelope>& sharedControlEnvelope() const { return envelope_; }
  void setControlEnvelope(std::shared_ptr<const ControlEnvelope> envelope) {
    envelope_ = std::move(envelope);
  }

  // How the file stores the control points (ControlCoding.h). The coded bytes, when present, are
  // the ones the model was read from or coded to (codeControlPoints): they decode to
  // spline().controlPoints() exactly, and the writer stores them as they are.
  const ControlCoding& controlCoding() const { return coding_; }
  const std::string* codedControlPoints() const { return codedControls_.get(); }
  void setControlCoding(ControlCoding coding, std::shared_ptr<const std::string> coded = nullptr) {
    coding_ = coding;
    codedControls_ = std::move(coded);
  }

  // Spacing of the data the model stands for, per axis: the recorded sample grid's, else the
  // finer of the control-point and mask-node spacings (so that a step of half of it resolves
  // the mask's boundary). Renderers take their default step from it.
  Vec3d dataSpacing() const;

  float value(const Vec3d& x) const { return spline_.value(domain_.toParameter(x)); }
  // Value and physical gradient.
  ValueGradient valueGradient(const Vec3d& x) const;
  // Value, physical gradient and physical Hessian.
  ValueGradientHessian valueGradientHessian(const Vec3d& x) const;

  // Batched queries over all cores; gradients/hessians may be empty spans to skip them.
  // Output spans must match points.size() when non-empty.
  void evaluate(std::span<const Vec3d> points, std::span<float> values,
                std::span<Vec3f> gradients = {}, std::span<Sym3f> hessians = {}) const;

 private:
  TensorBSpline spline_;
  DomainBox domain_;
  Vec3f invExtent_ = Vec3f::Ones();
  double valueMin_ = 0.0, valueMax_ = 0.0;
  Provenance provenance_;
  DomainMask mask_;
  std::shared_ptr<const DomainBoundary> boundary_;  // shared: models are copied freely
  ControlCoding coding_;
  std::shared_ptr<const std::string> codedControls_;  // shared: models are copied freely
  std::shared_ptr<const ControlEnvelope> envelope_;
};

}  // namespace mfadvr
