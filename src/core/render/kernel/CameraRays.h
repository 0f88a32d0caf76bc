#pragma once
// Primary rays of a camera as a plain struct (host and device): a ray from the camera through
// the centre of pixel (x, y), row 0 at the top. RayGenerator (Camera.h) fills it from a Camera.
#include <cmath>

#include "core/util/HostDevice.h"

namespace mfadvr {

struct CameraRays {
  double position[3], forward[3], right[3], up[3];
  double halfWidth = 0.0, halfHeight = 0.0;  // image plane at distance 1, or parallel extent
  bool parallel = false;
  int width = 1, height = 1;
};

// Origin and unit direction of the ray through pixel (x, y).
MFADVR_HD MFADVR_INLINE void primaryRay(const CameraRays& c, int x, int y, double o[3],
                                        double d[3]) {
  const double sx = (2.0 * (x + 0.5) / c.width - 1.0) * c.halfWidth;
  const double sy = (1.0 - 2.0 * (y + 0.5) / c.height) * c.halfHeight;
  if (c.parallel) {
    for (int a = 0; a < 3; ++a) {
      o[a] = c.position[a] + sx * c.right[a] + sy * c.up[a];
      d[a] = c.forward[a];
    }
  } else {
    for (int a = 0; a < 3; ++a) {
      o[a] = c.position[a];
      d[a] = c.forward[a] + sx * c.right[a] + sy * c.up[a];
    }
    const double n = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int a = 0; a < 3; ++a) d[a] /= n;
  }
}

// The inverse of a ray's direction for intersectBoxInverse: 1 / d per axis, 0 where d is 0.
MFADVR_HD MFADVR_INLINE void inverseDirection(const double d[3], double inv[3]) {
  for (int a = 0; a < 3; ++a) inv[a] = d[a] != 0.0 ? 1.0 / d[a] : 0.0;
}

// intersectBox for a ray whose direction's inverse is known (inverseDirection): many boxes per
// ray without a division each.
MFADVR_HD MFADVR_INLINE bool intersectBoxInverse(const double o[3], const double d[3],
                                                 const double inv[3], const double lo[3],
                                                 const double hi[3], double& tEnter,
                                                 double& tExit) {
  tEnter = -INFINITY;
  tExit = INFINITY;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double t0 = (lo[a] - o[a]) * inv[a], t1 = (hi[a] - o[a]) * inv[a];
    if (t0 > t1) {
      const double tmp = t0;
      t0 = t1;
      t1 = tmp;
    }
    tEnter = tEnter > t0 ? tEnter : t0;
    tExit = tExit < t1 ? tExit : t1;
  }
  return tEnter <= tExit;
}

// Entry and exit distances of the ray o + t d (d unit) through the box [lo, hi]; false if it
// misses. Entry may be negative when the origin is inside the box.
MFADVR_HD MFADVR_INLINE bool intersectBox(const double o[3], const double d[3], const double lo[3],
                                          const double hi[3], double& tEnter, double& tExit) {
  double inv[3];
  inverseDirection(d, inv);
  return intersectBoxInverse(o, d, inv, lo, hi, tEnter, tExit);
}

}  // namespace mfadvr
