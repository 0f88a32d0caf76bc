#pragma once
// Everything about a render except the field: image size, camera, transfer function, shading,
// sampling and compositing. The same settings render every reconstruction method.
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "core/model/DomainBox.h"
#include "core/render/BlendMode.h"
#include "core/render/Camera.h"
#include "core/render/CurvatureTransferFunction.h"
#include "core/render/Lighting.h"
#include "core/render/TransferFunction.h"
#include "core/render/TransferFunction2D.h"
#include "core/render/kernel/CameraRays.h"
#include "core/render/kernel/RayParams.h"  // kMaxClipPlanes

namespace mfadvr {

// A clipping plane: points x with normal . (x - point) >= 0 are kept (the side the normal points
// to, as VTK's mappers keep it).
struct ClipPlane {
  Vec3d point = Vec3d::Zero();
  Vec3d normal = Vec3d::UnitZ();
};

// One isosurface of the iso blend: its value (data units), colour and opacity (none: the
// transfer function's at the value).
struct IsoSurface {
  double value = 0.0;
  std::optional<Vec3f> color;
  std::optional<float> opacity;
};

struct RenderSettings {
  int width = 512, height = 512;
  Camera camera;
  // The primary rays, when they do not come from `camera` alone: a host that renders into
  // another program's frame (VTK, ParaView) takes them from that program's projection, which
  // may be off axis (a tile of a larger image, a shifted window centre). Their width and
  // height must be the image's. `camera` still gives the view direction for shading.
  std::optional<CameraRays> rays;
  // The rays of every pixel: `rays`, else those of `camera`.
  CameraRays primaryRays() const;
  // Must be resolved to data values (TransferFunction::resolved) against the value range that
  // is common to every method being compared.
  TransferFunction transferFunction;
  // Opacities are per this many world units (VTK's ScalarOpacityUnitDistance); must be > 0.
  double opacityUnitDistance = 1.0;
  // Gradient opacity (vtkVolumeProperty::SetGradientOpacity): each sample's step opacity times
  // this piecewise-linear function of |grad f| (x: data units per world unit, sorted; opacity in
  // [0, 1]; clamped to its end values). Empty: none. Composite blend only.
  std::vector<OpacityPoint> gradientOpacity;
  // A 2-D transfer function over (value, |grad f|) that replaces transferFunction's colour and
  // opacity (vtkVolumeProperty::SetTransferFunction2D). Composite blend only.
  std::optional<TransferFunction2D> transferFunction2D;
  // A curvature transfer function (CurvatureTransferFunction.h): colour and opacity from the
  // principal curvatures of the level set through each visible sample (or isosurface hit).
  // Composite and iso blends.
  std::optional<CurvatureTransferFunction> curvatureTransferFunction;
  // Thickness-controlled contours (kernel/CurvatureTransferView.h): their width in pixels (0:
  // none) and colour. Composite and iso blends.
  double contourPixels = 0.0;
  Vec3f contourColor = Vec3f::Zero();
  // Whether samples are classified by the curvature (either of the two above): the renderers
  // then evaluate the gradient and Hessian of every visible sample.
  bool classifiesCurvature() const { return curvatureTransferFunction || contourPixels > 0.0; }
  // Whether samples are classified by their gradient as well (gradient opacity, 2-D transfer
  // function, curvature): the renderers then evaluate the gradient of every visible sample,
  // shaded or not.
  bool classifiesGradients() const {
    return !gradientOpacity.empty() || transferFunction2D || classifiesCurvature();
  }
  // Whether the ray loop needs gradients at all: shading or classification.
  bool needsGradients() const { return shade || classifiesGradients(); }
  bool shade = false;
  Lighting lighting;
  // Distance between samples along a ray, world units; must be > 0.
  double sampleDistance = 1.0;
  // Stop a ray once its accumulated opacity reaches this (>= 1 disables early termination).
  double earlyTerminationOpacity = 0.99;
  Vec3f background = Vec3f::Zero();
  // Where each pixel's ray ends, for opaque geometry in front of the volume's far side: empty
  // (rays end where they leave the field's box) or width * height distances along the rays
  // from their origins (RayGenerator), row 0 at the top; +inf means no limit for that pixel.
  // Nothing beyond is sampled, and the last step is shortened to end there.
  std::vector<float> rayEnd;
  // Render only inside this box (intersected with the field's box), world units: a piece of a
  // distributed volume renders its own region and a compositor blends the pieces. None (the
  // default): the whole field.
  std::optional<DomainBox> clipBox;
  // How samples become a pixel (BlendMode.h).
  BlendMode blend = BlendMode::Composite;
  // Average blend: only values in [first, second] count (VTK's AverageIPScalarRange); none: all.
  std::optional<std::pair<double, double>> averageRange;
  // Iso blend: the surfaces (1 to kMaxIsoValues).
  std::vector<IsoSurface> isoSurfaces;
  // The user's clipping planes and cropping box (world units): rays are clipped to them
  // analytically, for every method, so that the images compare.
  std::vector<ClipPlane> clipPlanes;
  std::optional<DomainBox> crop;
  // Also compute, per pixel, a ray distance from the camera position (Image::depth): where the
  // ray's opacity first reaches 0.5 (composite), the extreme sample if it is visible (max,
  // min), the first sample that adds to the pixel (average, additive); NaN where there is none.
  bool depth = false;
  // Steps start at multiples of the sample distance along each ray (from its origin) instead of
  // where the ray enters the box, so that pieces of a partitioned volume sample the same points
  // as the whole volume; the first and last steps of a ray are shorter. Off by default (the
  // images of the evaluation protocol sample from the box entry).
  bool alignSamplesToCamera = false;
  // Worker threads; 0 uses all cores. The image does not depend on it.
  int threads = 0;
  // MFA models: pass over knot-span cells the transfer function makes invisible (exact: the
  // image is the same either way; off only to measure what it saves).
  bool skipEmptySpace = true;
  // Called now and then with the finished fraction (0..1], from one thread at a time.
  std::function<void(double)> progress;

  // Throws mfadvr::Error naming the first bad setting.
  void validate() const;
};

struct RenderStats {
  double seconds = 0.0;         // wall time of the ray casting
  std::int64_t rays = 0;        // pixels
  std::int64_t raysHit = 0;     // rays that crossed the box
  std::int64_t samples = 0;     // field samples used (not those outside a domain mask)
  std::int64_t terminated = 0;  // rays stopped early
  std::int64_t skipped = 0;     // samples passed over by empty-space skipping (MFA models)
};

}  // namespace mfadvr
