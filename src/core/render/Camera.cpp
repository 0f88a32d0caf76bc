#include "core/render/Camera.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "core/util/Error.h"

namespace mfadvr {

namespace {

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

Vec3d rotateAbout(const Vec3d& v, const Vec3d& axis, double degrees) {
  return Eigen::AngleAxisd(radians(degrees), axis.normalized()) * v;
}

bool nearlyParallel(const Vec3d& a, const Vec3d& b) {
  return a.normalized().cross(b.normalized()).norm() < 1e-9;
}

}  // namespace

Vec3d Camera::directionOfProjection() const {
  return (focalPoint - position).normalized();
}

void Camera::resetToBounds(const Vec3d& boxMin, const Vec3d& boxMax) {
  Vec3d direction = directionOfProjection();
  if (!direction.allFinite()) direction = Vec3d(0, 0, -1);
  if (nearlyParallel(direction, viewUp)) {
    // Any up that is not parallel works; prefer +y, else +z, as VTK does when it warns.
    viewUp = nearlyParallel(direction, Vec3d(0, 1, 0)) ? Vec3d(0, 0, 1) : Vec3d(0, 1, 0);
  }
  const Vec3d center = 0.5 * (boxMin + boxMax);
  double radius = 0.5 * (boxMax - boxMin).norm();
  if (!(radius > 0.0)) radius = 1.0;
  const double distance = radius / std::sin(0.5 * radians(viewAngle));
  focalPoint = center;
  position = center - distance * direction;
  parallelScale = radius;
  orthogonalizeViewUp();
}

void Camera::azimuth(double degrees) {
  position = focalPoint + rotateAbout(position - focalPoint, viewUp, degrees);
}

void Camera::elevation(double degrees) {
  const Vec3d right = directionOfProjection().cross(viewUp).normalized();
  // VTK rotates about -right: a positive elevation moves the camera up.
  const Vec3d offset = rotateAbout(position - focalPoint, -right, degrees);
  position = focalPoint + offset;
  viewUp = rotateAbout(viewUp, -right, degrees);
  orthogonalizeViewUp();
}

void Camera::zoom(double factor) {
  if (!(factor > 0.0) || !std::isfinite(factor)) throw Error("zoom factor must be positive");
  if (parallelProjection)
    parallelScale /= factor;
  else
    viewAngle /= factor;
}

void Camera::orthogonalizeViewUp() {
  const Vec3d d = directionOfProjection();
  const Vec3d right = d.cross(viewUp).normalized();
  viewUp = right.cross(d).normalized();
}

void Camera::validate() const {
  if (!position.allFinite() || !focalPoint.allFinite() || !viewUp.allFinite())
    throw Error("camera position, focal point and view-up must be finite");
  if ((focalPoint - position).norm() <= 0.0)
    throw Error("camera position and focal point coincide");
  if (!(viewUp.norm() > 0.0) || nearlyParallel(viewUp, focalPoint - position))
    throw Error("camera view-up must not be zero or parallel to the viewing direction");
  if (!(viewAngle > 0.0 && viewAngle < 180.0))
    throw Error("camera view angle must lie in (0, 180) degrees");
  if (parallelProjection && !(parallelScale > 0.0 && std::isfinite(parallelScale)))
    throw Error("camera parallel scale must be positive");
}

RayGenerator::RayGenerator(const Camera& camera, int width, int height) {
  camera.validate();
  if (width <= 0 || height <= 0) throw Error("image size must be positive");
  const Vec3d forward = camera.directionOfProjection();
  const Vec3d right = forward.cross(camera.viewUp).normalized();
  const Vec3d up = right.cross(forward);
  for (int a = 0; a < 3; ++a) {
    rays_.position[a] = camera.position[a];
    rays_.forward[a] = forward[a];
    rays_.right[a] = right[a];
    rays_.up[a] = up[a];
  }
  rays_.parallel = camera.parallelProjection;
  rays_.width = width;
  rays_.height = height;
  const double aspect = static_cast<double>(width) / height;
  rays_.halfHeight =
      rays_.parallel ? camera.parallelScale : std::tan(0.5 * radians(camera.viewAngle));
  rays_.halfWidth = rays_.halfHeight * aspect;
}

}  // namespace mfadvr
