#include "core/render/ModelRenderSetup.h"

#include <chrono>

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
    : table_(validated(settings).transferFunction,
             OpacityCorrection(settings.sampleDistance / settings.opacityUnitDistance)) {
  const Model& model = field.model();
  params_ = compileRayParams(settings, table_, model.domain().min, model.domain().max);
  view_.spline = model.spline().view();
  const Vec3d extent = model.domain().extent();
  for (int a = 0; a < 3; ++a) {
    view_.boxMin[a] = model.domain().min[a];
    view_.inverseExtent[a] = 1.0 / extent[a];
  }
  view_.mask = model.mask().view();
  // The flags' (re)build is part of the frame: its time is added to the ray casting's.
  const auto start = std::chrono::steady_clock::now();
  // Only composite renders skip: in the other blend modes a transparent value still sets the
  // extreme or the average.
  if (settings.skipEmptySpace && settings.blend == BlendMode::Composite) {
    if (EmptySpaceCache* cache = field.emptySpaceCache()) {
      flags_ = cache->flags(model.spline(), table_);
    } else {
      const std::shared_ptr<const SpanRanges> ranges = model.spline().spanRanges();
      flags_ = std::make_shared<const EmptySpaceFlags>(
          buildEmptySpaceFlags(view_.spline, *ranges, table_, bezierRangesPayOff(model, settings)));
    }
    // Nothing to skip: the loop without the per-sample test.
    if (flags_->emptyCells > 0) flags_->attachTo(view_);
  }
  setupSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
