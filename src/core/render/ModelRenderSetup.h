#pragma once
// Everything a render of the MFA model needs besides the driver that walks the pixels: the
// transfer-function table, the plain ray parameters and model view, and the empty-space flags
// (taken from the field's cache, rebuilt only when the transfer function's zero set changed;
// or, with no cache, built for this frame, with Bezier ranges only where they pay off). The CPU
// driver (ModelRenderer.cpp) and the CUDA driver (src/gpu) both start from it, so that the two
// render exactly the same scene.
#include <memory>

#include "core/field/ModelField.h"
#include "core/render/ClassificationTables.h"
#include "core/render/EmptySpaceGrid.h"
#include "core/render/RenderSettings.h"
#include "core/render/TransferFunctionTable.h"
#include "core/render/kernel/RayParams.h"
#include "core/render/kernel/SplineRaySampler.h"

namespace mfadvr {

class ModelRenderSetup {
 public:
  // Validates the settings (throws mfadvr::Error). The field and settings must outlive this.
  ModelRenderSetup(const ModelField& field, const RenderSettings& settings);
  // params() and view() point into this object: it stays where it was made.
  ModelRenderSetup(const ModelRenderSetup&) = delete;
  ModelRenderSetup& operator=(const ModelRenderSetup&) = delete;

  const RayParams& params() const { return params_; }
  const ModelView& view() const { return view_; }
  // Whether samples can fall outside the model's domain (a mask or an exact boundary).
  bool masked() const { return view_.mask.nodes != nullptr || view_.boundary.nodes != nullptr; }
  // Whether the view carries empty-space flags (skipping on and something to skip).
  bool skips() const { return view_.empty != nullptr; }
  // Whether it carries extreme bounds (maximum and minimum intensity skipping, host only).
  bool skipsExtremes() const { return view_.extremeUpper != nullptr; }
  // The flags behind view().empty / emptyPyramid, or null. Shared with the field's cache: the
  // same object comes back while the model and the transfer function's zero set are unchanged.
  std::shared_ptr<const EmptySpaceFlags> emptySpaceFlags() const {
    return skips() ? flags_ : nullptr;
  }
  // Time spent building the flags: part of the frame.
  double setupSeconds() const { return setupSeconds_; }

 private:
  ClassificationTables tables_;
  RayParams params_;
  ModelView view_;
  std::shared_ptr<const EmptySpaceFlags> flags_;
  std::shared_ptr<const ExtremeBounds> extremes_;
  double setupSeconds_ = 0.0;
};

// Whether flags built for one render of `model` with `settings` (no cache: a streamed block)
// are worth the Bezier ranges' cost: the rays over the model's region (clipped to
// settings.clipBox, less those that end at once) would take at least
// kBezierRangesMinSamplesPerCell samples per cell if none were skipped.
bool bezierRangesPayOff(const Model& model, const RenderSettings& settings);

// For the iso blend's empty-space flags: a transfer function opaque only in bands two table
// entries wide around each isovalue, so that a cell is empty exactly when no value it can take
// comes within a band (so holds no isovalue).
TransferFunction isoBandTransferFunction(const std::vector<IsoSurface>& surfaces);

}  // namespace mfadvr
