#pragma once
// Blinn-Phong shading of volume samples, with vtkVolumeProperty's coefficients.
//
// The normal is the normalized field gradient, turned to face the viewer (two-sided lighting:
// a volume has no outside). A sample whose gradient is (numerically) zero has no normal; it gets
// the ambient and diffuse terms as if it faced the light, and no specular, so that homogeneous
// regions keep their transfer-function colour instead of turning black.
#include <cmath>
#include <vector>

#include "core/util/Vec.h"

namespace mfadvr {

// A light at infinity. `direction` is the way the light travels (from the light into the scene),
// like vtkLight's focal point minus position.
struct DirectionalLight {
  Vec3d direction{0.0, 0.0, -1.0};
  Vec3f color{1.0f, 1.0f, 1.0f};
  float intensity = 1.0f;
};

struct Lighting {
  float ambient = 0.3f;
  float diffuse = 0.7f;
  float specular = 0.2f;
  float specularPower = 10.0f;
  bool headlight = true;                 // a white light travelling along the view direction
  std::vector<DirectionalLight> lights;  // in addition to the headlight

  // Throws mfadvr::Error on negative or non-finite coefficients or a zero light direction.
  void validate() const;
};

// Per-ray shading state: the light vectors (towards the lights) and half vectors for one view
// direction, so that the per-sample work is a few dot products.
class Shader {
 public:
  static constexpr int kMaxLights = 8;

  // viewDirection: the ray's unit direction (from the eye into the scene).
  Shader(const Lighting& lighting, const Vec3d& cameraDirection);
  void setView(const Vec3f& rayDirection);

  // Shaded colour of a sample with transfer-function colour `color` and field gradient `g`.
  // Always inlined: it runs at every visible sample of a shaded render.
  [[gnu::always_inline]] inline Vec3f shade(const Vec3f& color, const Vec3f& g) const {
    const float g2 = g.squaredNorm();
    if (!(g2 > 1e-30f)) return color * (ambient_ + diffuseSum_);
    Vec3f n = g * (1.0f / std::sqrt(g2));
    if (n.dot(toEye_) < 0.0f) n = -n;
    Vec3f diffuse = Vec3f::Zero(), specular = Vec3f::Zero();
    for (int i = 0; i < count_; ++i) {
      const float nl = n.dot(toLight_[i]);
      if (nl <= 0.0f) continue;
      diffuse += nl * lightColor_[i];
      const float nh = n.dot(half_[i]);
      if (nh > 0.0f) specular += specularTerm(nh) * lightColor_[i];
    }
    return ambient_ * color + diffuseK_ * diffuse.cwiseProduct(color) + specularK_ * specular;
  }

 private:
  // nh^power; by repeated squaring when the power is a whole number (the usual case, and exact),
  // since powf costs as much as the rest of the shading.
  [[gnu::always_inline]] inline float specularTerm(float nh) const {
    if (integerPower_ < 0) return std::pow(nh, power_);
    float result = 1.0f, base = nh;
    for (int e = integerPower_; e > 0; e >>= 1) {
      if (e & 1) result *= base;
      base *= base;
    }
    return result;
  }

  int integerPower_ = -1;
  float ambient_, diffuseK_, specularK_, power_, diffuseSum_;
  int count_ = 0;
  Vec3f toEye_ = Vec3f::UnitZ();
  Vec3f toLight_[kMaxLights];
  Vec3f half_[kMaxLights];
  Vec3f lightColor_[kMaxLights];  // colour times intensity
};

}  // namespace mfadvr
