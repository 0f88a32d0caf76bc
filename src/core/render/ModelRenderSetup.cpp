#include "core/render/ModelRenderSetup.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/render/PieceCompositor.h"
#include "core/render/RayCaster.h"

namespace mfadvr {

namespace {
const RenderSettings& validated(const RenderSettings& s) {
  s.validate();
  return s;
}
}  // namespace

ModelRenderSetup::ModelRenderSetup(const ModelField& field, const RenderSettings& settings)
    : tables_(validated(settings)) {
  const Model& model = field.model();
  params_ = compileRayParams(settings, tables_, model.domain().min, model.domain().max);
  view_.spline = model.spline().view();
  const Vec3d extent = model.domain().extent();
  for (int a = 0; a < 3; ++a) {
    view_.boxMin[a] = model.domain().min[a];
    view_.inverseExtent[a] = 1.0 / extent[a];
  }
  view_.mask = model.mask().view();
  if (const DomainBoundary* boundary = model.boundary()) view_.boundary = boundary->view();
  // The flags' (re)build is part of the frame: its time is added to the ray casting's.
  const auto start = std::chrono::steady_clock::now();
  // Composite and additive renders skip what the transfer function hides, iso renders the cells
  // that hold no isovalue, maximum and minimum intensity renders the cells that cannot beat a
  // ray's extreme (ExtremeBounds.h; unshaded); average renders count transparent values too.
  const BlendMode blend = settings.blend;
  // Only the unshaded loops reduce with skipping (RayIntegrator.h).
  const bool unshaded = !settings.needsGradients();
  // Maximum intensity skips only when the transfer function is transparent at the low end, so
  // that rays pass over that end from their start: with a ramp from the minimum, rays through
  // a dense field (Marschner-Lobb 256^3) rarely jump far, and the tests cost more than they
  // saved (4.76 s against 4.07 s at 1000x1000; 2.48 s against 4.20 s transparent below the
  // middle; docs/rendering.md). Minimum intensity gained in both (1.11 s against 4.30 s).
  const bool maximumSkips = blend == BlendMode::Maximum && params_.transparentBeyond > -INFINITY;
  if (settings.skipEmptySpace && unshaded && (maximumSkips || blend == BlendMode::Minimum)) {
    if (EmptySpaceCache* cache = field.emptySpaceCache()) {
      extremes_ = cache->extremeBounds(model.spline());
    } else {
      extremes_ = std::make_shared<const ExtremeBounds>(buildExtremeBounds(
          view_.spline, *model.spline().spanRanges(), bezierRangesPayOff(model, settings)));
    }
    extremes_->attachTo(view_);
  } else if (settings.skipEmptySpace && blend == BlendMode::Iso) {
    const TransferFunctionTable band(isoBandTransferFunction(settings.isoSurfaces),
                                     OpacityCorrection(1.0));
    if (EmptySpaceCache* cache = field.emptySpaceCache()) {
      flags_ = cache->flags(model.spline(), band, model.controlEnvelope());
    } else {
      flags_ = std::make_shared<const EmptySpaceFlags>(buildEmptySpaceFlags(
          view_.spline, *model.spline().spanRanges(), band, bezierRangesPayOff(model, settings)));
    }
    if (flags_->emptyCells > 0) flags_->attachTo(view_);
  } else if (settings.skipEmptySpace &&
             (blend == BlendMode::Composite || (blend == BlendMode::Additive && unshaded))) {
    if (EmptySpaceCache* cache = field.emptySpaceCache()) {
      flags_ = cache->flags(model.spline(), tables_.table(), model.controlEnvelope());
    } else {
      const std::shared_ptr<const SpanRanges> ranges = model.spline().spanRanges();
      flags_ = std::make_shared<const EmptySpaceFlags>(buildEmptySpaceFlags(
          view_.spline, *ranges, tables_.table(), bezierRangesPayOff(model, settings)));
    }
    // Nothing to skip: the loop without the per-sample test.
    if (flags_->emptyCells > 0) flags_->attachTo(view_);
  }
  setupSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TransferFunction isoBandTransferFunction(const std::vector<IsoSurface>& surfaces) {
  std::vector<double> v;
  for (const IsoSurface& s : surfaces) v.push_back(s.value);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  // The table's span: the values with room on both sides; bands two entries wide.
  const double spread = v.back() - v.front();
  const double margin = std::max({spread * 0.01, std::abs(v.back()) * 1e-6, 1e-30});
  const double lo = v.front() - margin, hi = v.back() + margin;
  const double w = 2.0 * (hi - lo) / (TransferFunctionTable::kEntries - 1);
  TransferFunction tf;
  tf.space = TfSpace::Data;
  tf.color = {{lo, Vec3f::Ones()}, {hi, Vec3f::Ones()}};
  tf.opacity.push_back({lo, 0.0f});
  for (size_t i = 0; i < v.size(); ++i) {
    if (v[i] - w > tf.opacity.back().x) tf.opacity.push_back({v[i] - w, 0.0f});
    tf.opacity.push_back({v[i], 1.0f});
    if (i + 1 == v.size() || v[i + 1] - w > v[i] + w) tf.opacity.push_back({v[i] + w, 0.0f});
  }
  tf.opacity.push_back({hi, 0.0f});
  return tf;
}

// The samples the rays over the model's region would take if none were skipped, a ray's path
// taken as half the region's diagonal, per knot-span cell.
bool bezierRangesPayOff(const Model& model, const RenderSettings& s) {
  DomainBox region = model.domain();
  if (s.clipBox) {
    region.min = region.min.cwiseMax(s.clipBox->min);
    region.max = region.max.cwiseMin(s.clipBox->max);
    if ((region.max - region.min).minCoeff() < 0.0) return false;
  }
  const double rays = static_cast<double>(raysStillGoing(s.primaryRays(), s.rayEnd, region));
  const double samples = rays * 0.5 * region.extent().norm() / s.sampleDistance;
  return samples >= kBezierRangesMinSamplesPerCell *
                        static_cast<double>(model.spline().spanRanges()->cellCount());
}

}  // namespace mfadvr
