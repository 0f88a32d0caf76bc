#pragma once
// Blinn-Phong shading of volume samples, with vtkVolumeProperty's coefficients: what the user
// sets. The per-sample formula is in kernel/ShadingKernel.h.
#include <cmath>
#include <vector>

#include "core/render/kernel/ShadingKernel.h"
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

// The plain shading parameters of the ray integration (kernel/ShadingKernel.h) for `lighting`
// and a camera looking along `cameraDirection` (the headlight travels that way). Validates.
ShadingParams makeShadingParams(const Lighting& lighting, const Vec3d& cameraDirection);

}  // namespace mfadvr
