#include "core/render/Lighting.h"

#include <string>

#include "core/util/Error.h"

namespace mfadvr {

void Lighting::validate() const {
  auto check = [](float v, const char* what) {
    if (!(v >= 0.0f) || !std::isfinite(v))
      throw Error(std::string("shading ") + what + " must be a non-negative number");
  };
  check(ambient, "ambient");
  check(diffuse, "diffuse");
  check(specular, "specular");
  check(specularPower, "specular power");
  if (lights.size() + (headlight ? 1 : 0) > static_cast<size_t>(Shader::kMaxLights))
    throw Error("at most " + std::to_string(Shader::kMaxLights) + " lights are supported");
  for (const auto& l : lights) {
    if (!l.direction.allFinite() || !(l.direction.norm() > 0.0))
      throw Error("a light direction must be a finite non-zero vector");
    if (!l.color.allFinite() || (l.color.array() < 0.0f).any() || !(l.intensity >= 0.0f))
      throw Error("a light's colour and intensity must be non-negative");
  }
}

Shader::Shader(const Lighting& lighting, const Vec3d& cameraDirection)
    : ambient_(lighting.ambient),
      diffuseK_(lighting.diffuse),
      specularK_(lighting.specular),
      power_(lighting.specularPower) {
  lighting.validate();
  if (power_ == std::floor(power_) && power_ <= 1024.0f) integerPower_ = static_cast<int>(power_);
  auto add = [&](const Vec3d& travel, const Vec3f& color) {
    toLight_[count_] = (-travel.normalized()).cast<float>();
    lightColor_[count_] = color;
    ++count_;
  };
  if (lighting.headlight) add(cameraDirection, Vec3f::Ones());
  for (const auto& l : lighting.lights) add(l.direction, l.color * l.intensity);
  // Without a normal a sample is lit as if it faced every light head-on (no specular).
  float sum = 0.0f;
  for (int i = 0; i < count_; ++i) sum += lightColor_[i].mean();
  diffuseSum_ = diffuseK_ * sum;
  setView(cameraDirection.cast<float>());
}

void Shader::setView(const Vec3f& rayDirection) {
  toEye_ = -rayDirection.normalized();
  for (int i = 0; i < count_; ++i) {
    const Vec3f h = toLight_[i] + toEye_;
    const float n = h.norm();
    half_[i] = n > 1e-6f ? Vec3f(h / n) : Vec3f::Zero();  // light straight from behind
  }
}

}  // namespace mfadvr
