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
  if (lights.size() + (headlight ? 1 : 0) > static_cast<size_t>(kMaxLights))
    throw Error("at most " + std::to_string(kMaxLights) + " lights are supported");
  for (const auto& l : lights) {
    if (!l.direction.allFinite() || !(l.direction.norm() > 0.0))
      throw Error("a light direction must be a finite non-zero vector");
    if (!l.color.allFinite() || (l.color.array() < 0.0f).any() || !(l.intensity >= 0.0f))
      throw Error("a light's colour and intensity must be non-negative");
  }
}

ShadingParams makeShadingParams(const Lighting& lighting, const Vec3d& cameraDirection) {
  lighting.validate();
  ShadingParams s;
  s.ambient = lighting.ambient;
  s.diffuse = lighting.diffuse;
  s.specular = lighting.specular;
  s.specularPower = lighting.specularPower;
  if (s.specularPower == std::floor(s.specularPower) && s.specularPower <= 1024.0f)
    s.integerPower = static_cast<int>(s.specularPower);
  auto add = [&](const Vec3d& travel, const Vec3f& color) {
    const Vec3f to = (-travel.normalized()).cast<float>();
    for (int c = 0; c < 3; ++c) {
      s.toLight[s.lightCount][c] = to[c];
      s.lightColor[s.lightCount][c] = color[c];
    }
    ++s.lightCount;
  };
  if (lighting.headlight) add(cameraDirection, Vec3f::Ones());
  for (const auto& l : lighting.lights) add(l.direction, l.color * l.intensity);
  // Without a normal a sample is lit as if it faced every light head-on (no specular).
  float sum = 0.0f;
  for (int i = 0; i < s.lightCount; ++i)
    sum += (s.lightColor[i][0] + s.lightColor[i][1] + s.lightColor[i][2]) / 3.0f;
  s.diffuseSum = s.diffuse * sum;
  return s;
}

}  // namespace mfadvr
