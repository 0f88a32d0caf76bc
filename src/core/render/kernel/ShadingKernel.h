#pragma once
// Blinn-Phong shading of volume samples with vtkVolumeProperty's coefficients (host and device).
// Lighting.h describes the model; makeShadingParams() fills these plain structs from it.
//
// The normal is the normalized field gradient, turned to face the viewer (two-sided lighting:
// a volume has no outside). A sample whose gradient is (numerically) zero has no normal; it gets
// the ambient and diffuse terms as if it faced the light, and no specular, so that homogeneous
// regions keep their transfer-function colour instead of turning black.
#include <cmath>

#include "core/util/HostDevice.h"

namespace mfadvr {

inline constexpr int kMaxLights = 8;

struct ShadingParams {
  float ambient = 0.0f, diffuse = 0.0f, specular = 0.0f, specularPower = 1.0f;
  int integerPower = -1;    // specularPower when it is a whole number <= 1024, else -1
  float diffuseSum = 0.0f;  // diffuse x the lights' mean colours: the no-normal case
  int lightCount = 0;
  float toLight[kMaxLights][3];     // unit vectors towards the lights
  float lightColor[kMaxLights][3];  // colour times intensity
};

// Per ray: the vector to the eye and the half vectors for that view direction.
struct RayShading {
  float toEye[3];
  float half[kMaxLights][3];
};

MFADVR_HD MFADVR_INLINE void prepareRayShading(const ShadingParams& s, const float dir[3],
                                               RayShading& r) {
  const float n = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  for (int c = 0; c < 3; ++c) r.toEye[c] = -dir[c] / n;
  for (int i = 0; i < s.lightCount; ++i) {
    float h[3];
    for (int c = 0; c < 3; ++c) h[c] = s.toLight[i][c] + r.toEye[c];
    const float hn = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (int c = 0; c < 3; ++c) r.half[i][c] = hn > 1e-6f ? h[c] / hn : 0.0f;  // light from behind
  }
}

// nh^power; by repeated squaring when the power is a whole number (the usual case, and exact),
// since powf costs as much as the rest of the shading.
MFADVR_HD MFADVR_INLINE float specularTerm(const ShadingParams& s, float nh) {
  if (s.integerPower < 0) return powf(nh, s.specularPower);
  float result = 1.0f, base = nh;
  for (int e = s.integerPower; e > 0; e >>= 1) {
    if (e & 1) result *= base;
    base *= base;
  }
  return result;
}

// Shaded colour of a sample with transfer-function colour `color` and field gradient `g`.
MFADVR_HD MFADVR_INLINE void shadeSample(const ShadingParams& s, const RayShading& r,
                                         const float color[3], const float g[3], float out[3]) {
  const float g2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
  if (!(g2 > 1e-30f)) {
    const float k = s.ambient + s.diffuseSum;
    for (int c = 0; c < 3; ++c) out[c] = color[c] * k;
    return;
  }
  const float inv = 1.0f / sqrtf(g2);
  float n[3] = {g[0] * inv, g[1] * inv, g[2] * inv};
  if (n[0] * r.toEye[0] + n[1] * r.toEye[1] + n[2] * r.toEye[2] < 0.0f)
    for (int c = 0; c < 3; ++c) n[c] = -n[c];
  float diffuse[3] = {0.0f, 0.0f, 0.0f}, specular[3] = {0.0f, 0.0f, 0.0f};
  for (int i = 0; i < s.lightCount; ++i) {
    const float* l = s.toLight[i];
    const float nl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
    if (nl <= 0.0f) continue;
    for (int c = 0; c < 3; ++c) diffuse[c] += nl * s.lightColor[i][c];
    const float* h = r.half[i];
    const float nh = n[0] * h[0] + n[1] * h[1] + n[2] * h[2];
    if (nh > 0.0f) {
      const float sp = specularTerm(s, nh);
      for (int c = 0; c < 3; ++c) specular[c] += sp * s.lightColor[i][c];
    }
  }
  for (int c = 0; c < 3; ++c)
    out[c] = s.ambient * color[c] + s.diffuse * diffuse[c] * color[c] + s.specular * specular[c];
}

}  // namespace mfadvr
