#include "core/render/RenderSettings.h"

#include <cmath>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {

void RenderSettings::validate() const {
  if (width <= 0 || height <= 0 || width > 32768 || height > 32768)
    throw Error("image size must be between 1x1 and 32768x32768, got " + std::to_string(width) +
                "x" + std::to_string(height));
  camera.validate();
  if (rays && (rays->width != width || rays->height != height))
    throw Error("internal: the primary rays are for another image size");
  transferFunction.validate();
  if (transferFunction.space != TfSpace::Data)
    throw Error("internal: the transfer function must be resolved to data values before rendering");
  if (!(opacityUnitDistance > 0.0) || !std::isfinite(opacityUnitDistance))
    throw Error("opacity unit distance must be positive");
  if (!(sampleDistance > 0.0) || !std::isfinite(sampleDistance))
    throw Error("sample distance must be positive");
  if (!(earlyTerminationOpacity > 0.0) || !std::isfinite(earlyTerminationOpacity))
    throw Error("early ray termination opacity must be in (0, 1] (or above 1 to disable it)");
  if (!background.allFinite()) throw Error("background colour must be finite");
  if (!rayEnd.empty()) {
    if (rayEnd.size() != static_cast<size_t>(width) * static_cast<size_t>(height))
      throw Error("ray ends must hold one distance per pixel (" + std::to_string(width) + "x" +
                  std::to_string(height) + "), got " + std::to_string(rayEnd.size()));
    for (float t : rayEnd)
      if (std::isnan(t)) throw Error("ray ends must not be NaN");
  }
  if (clipBox && !(clipBox->min.allFinite() && clipBox->max.allFinite() &&
                   (clipBox->min.array() <= clipBox->max.array()).all()))
    throw Error("the clip box must be finite with min <= max on every axis");
  if (clipPlanes.size() > static_cast<size_t>(kMaxClipPlanes))
    throw Error("at most " + std::to_string(kMaxClipPlanes) + " clipping planes, got " +
                std::to_string(clipPlanes.size()));
  for (const ClipPlane& c : clipPlanes)
    if (!c.point.allFinite() || !c.normal.allFinite() || !(c.normal.norm() > 0.0))
      throw Error("a clipping plane needs a finite point and a non-zero normal");
  if (crop && !(crop->min.allFinite() && crop->max.allFinite() &&
                (crop->min.array() <= crop->max.array()).all()))
    throw Error("the cropping box must be finite with min <= max on every axis");
  if (averageRange && !(std::isfinite(averageRange->first) && std::isfinite(averageRange->second) &&
                        averageRange->first <= averageRange->second))
    throw Error("the average range must be finite with min <= max");
  if (blend == BlendMode::Iso && isoSurfaces.empty())
    throw Error("the iso blend needs at least one isovalue");
  if (isoSurfaces.size() > static_cast<size_t>(kMaxIsoValues))
    throw Error("at most " + std::to_string(kMaxIsoValues) + " isovalues, got " +
                std::to_string(isoSurfaces.size()));
  for (const IsoSurface& i : isoSurfaces) {
    if (!std::isfinite(i.value)) throw Error("isovalues must be finite");
    if (i.color && !((i.color->array() >= 0.0f).all() && (i.color->array() <= 1.0f).all()))
      throw Error("isosurface colours must lie in [0, 1]");
    if (i.opacity && !(*i.opacity >= 0.0f && *i.opacity <= 1.0f))
      throw Error("isosurface opacities must lie in [0, 1]");
  }
  for (size_t i = 0; i < gradientOpacity.size(); ++i) {
    const OpacityPoint& p = gradientOpacity[i];
    if (!(std::isfinite(p.x) && p.x >= 0.0))
      throw Error("gradient opacity: |grad f| points must be finite and >= 0");
    if (i > 0 && p.x < gradientOpacity[i - 1].x)
      throw Error("gradient opacity: the |grad f| points must be sorted");
    if (!(p.alpha >= 0.0f && p.alpha <= 1.0f))
      throw Error("gradient opacity: opacities must lie in [0, 1]");
  }
  if (transferFunction2D) transferFunction2D->validate();
  if (curvatureTransferFunction) curvatureTransferFunction->validate();
  if (!(std::isfinite(contourPixels) && contourPixels >= 0.0))
    throw Error("contour width must be a finite number of pixels >= 0");
  if (!((contourColor.array() >= 0.0f).all() && (contourColor.array() <= 1.0f).all()))
    throw Error("contour colour components must lie in [0, 1]");
  if ((!gradientOpacity.empty() || transferFunction2D) && blend != BlendMode::Composite)
    throw Error(std::string("gradient opacity and 2-D transfer functions apply to the composite "
                            "blend, not ") +
                blendModeName(blend));
  if (classifiesCurvature() && blend != BlendMode::Composite && blend != BlendMode::Iso)
    throw Error(std::string("curvature transfer functions and contours apply to the composite "
                            "and iso blends, not ") +
                blendModeName(blend));
  if (threads < 0) throw Error("thread count must be >= 0 (0: all cores)");
  if (shade) lighting.validate();
}

CameraRays RenderSettings::primaryRays() const {
  return rays ? *rays : RayGenerator(camera, width, height).rays();
}

}  // namespace mfadvr
