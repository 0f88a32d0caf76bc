#pragma once
// A camera with vtkCamera's semantics, so that a scene described for VTK renders the same here:
// position, focal point, view-up, vertical view angle in degrees, parallel projection with a
// parallel scale (half the viewport height in world units). resetToBounds() is
// vtkRenderer::ResetCamera; azimuth/elevation/zoom are vtkCamera's.
#include "core/render/kernel/CameraRays.h"
#include "core/util/Vec.h"

namespace mfadvr {

struct Camera {
  Vec3d position{0.0, 0.0, 1.0};
  Vec3d focalPoint{0.0, 0.0, 0.0};
  Vec3d viewUp{0.0, 1.0, 0.0};
  double viewAngle = 30.0;  // degrees, vertical
  bool parallelProjection = false;
  double parallelScale = 1.0;

  // Unit vector from the position towards the focal point.
  Vec3d directionOfProjection() const;
  double distance() const { return (focalPoint - position).norm(); }

  // Keeps the viewing direction and view-up, centres the focal point on the box and moves back
  // until a sphere around the box fits the view angle (distance = radius / sin(angle/2)); sets
  // the parallel scale to that radius. A view-up parallel to the direction is replaced.
  void resetToBounds(const Vec3d& boxMin, const Vec3d& boxMax);

  // Rotates the position about the view-up vector through the focal point (degrees).
  void azimuth(double degrees);
  // Rotates the position about the camera's right axis through the focal point (degrees), then
  // re-orthogonalizes view-up so that elevations past 90 degrees stay well defined.
  void elevation(double degrees);
  // Divides the view angle (perspective) or the parallel scale (parallel) by factor.
  void zoom(double factor);
  // Makes view-up perpendicular to the direction of projection.
  void orthogonalizeViewUp();

  // Throws mfadvr::Error on non-finite vectors, position == focal point, view-up parallel to the
  // direction, angle outside (0, 180) or non-positive parallel scale.
  void validate() const;
};

// Primary rays for a width x height image, row 0 at the top, through pixel centres.
// The formula is kernel/CameraRays.h, shared with the ray integration.
class RayGenerator {
 public:
  RayGenerator(const Camera& camera, int width, int height);
  // Origin and unit direction of the ray through pixel (x, y).
  void ray(int x, int y, Vec3d& origin, Vec3d& direction) const {
    double o[3], d[3];
    primaryRay(rays_, x, y, o, d);
    origin = Vec3d(o[0], o[1], o[2]);
    direction = Vec3d(d[0], d[1], d[2]);
  }
  const CameraRays& rays() const { return rays_; }

 private:
  CameraRays rays_;
};

}  // namespace mfadvr
