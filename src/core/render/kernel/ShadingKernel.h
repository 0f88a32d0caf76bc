#pragma once
// Blinn-Phong shading of volume samples with vtkVolumeProperty's coefficients (host and device).
// Lighting.h describes the model; makeShadingParams() fills these plain structs from it.
//
// The normal is the normalized field gradient, turned to face the viewer (two-sided lighting:
// a volume has no outside). A sample whose gradient is (numerically) zero has no normal; it gets
// the ambient and diffuse terms as if it faced the light, and no specular, so that homogeneous
// regions keep their transfer-function colour instead of turning black.
#include <cmath>
#include <type_traits>

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

// Per ray: the vector to the eye and the half vectors for that view direction. F is float, or
// on the host a vector of lanes holding a packet of rays (RayPacketIntegrator.h).
template <class F>
struct RayShadingOf {
  F toEye[3];
  F half[kMaxLights][3];
};
using RayShading = RayShadingOf<float>;

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
template <class F>
MFADVR_HD MFADVR_INLINE F specularTerm(const ShadingParams& s, F nh) {
  if (s.integerPower < 0) {
    if constexpr (std::is_arithmetic_v<F>) {
      return powf(nh, s.specularPower);
    } else {
      return mapLanes(nh, [&](float v) { return powf(v, s.specularPower); });
    }
  }
  F result = F{} + 1.0f, base = nh;
  for (int e = s.integerPower; e > 0; e >>= 1) {
    if (e & 1) result *= base;
    base *= base;
  }
  return result;
}

// a . b, with the rounding of fusedMultiplyAdd: the same for one value and for lanes.
template <class F, class G>
MFADVR_HD MFADVR_INLINE F dot3(const F a[3], const G b[3]) {
  return fusedMultiplyAdd(a[2], F{} + b[2], fusedMultiplyAdd(a[1], F{} + b[1], a[0] * b[0]));
}

// Shaded colour of a sample with transfer-function colour `color` and field gradient `g`: one
// sample (F = float), or on the host one sample of each ray of a packet (F a vector of lanes).
// Written with selects rather than branches, and with explicit multiply-adds, so that both forms
// are one formula and every lane gets bit for bit what a single sample would.
template <class F>
MFADVR_HD MFADVR_INLINE void shadeSample(const ShadingParams& s, const RayShadingOf<F>& r,
                                         const F color[3], const F g[3], F out[3]) {
  const F g2 = dot3(g, g);
  const auto hasNormal = g2 > 1e-30f;
  const F inv = 1.0f / squareRoot(hasNormal ? g2 : 1.0f);
  F n[3] = {g[0] * inv, g[1] * inv, g[2] * inv};
  const auto back = dot3(n, r.toEye) < 0.0f;
  for (int c = 0; c < 3; ++c) n[c] = back ? -n[c] : n[c];
  F diffuse[3] = {}, specular[3] = {};
  for (int i = 0; i < s.lightCount; ++i) {
    const F nl = dot3(n, s.toLight[i]);
    const auto lit = nl > 0.0f;
    const F litNl = lit ? nl : 0.0f;
    const F nh = dot3(n, r.half[i]);
    const auto shines = lit & (nh > 0.0f);
    const F sp = shines ? specularTerm(s, nh) : 0.0f;
    for (int c = 0; c < 3; ++c) {
      const F light = F{} + s.lightColor[i][c];
      diffuse[c] = fusedMultiplyAdd(litNl, light, diffuse[c]);
      specular[c] = fusedMultiplyAdd(sp, light, specular[c]);
    }
  }
  const float flat = s.ambient + s.diffuseSum;  // no normal: as if facing the light
  for (int c = 0; c < 3; ++c) {
    const F matte = fusedMultiplyAdd(s.diffuse * diffuse[c], color[c], s.ambient * color[c]);
    const F shaded = fusedMultiplyAdd(F{} + s.specular, specular[c], matte);
    out[c] = hasNormal ? shaded : color[c] * flat;
  }
}

}  // namespace mfadvr
