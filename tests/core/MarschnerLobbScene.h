#pragma once
// Test helper: the shaded Marschner-Lobb scene of the renderer's invariant tests.
#include "core/analytic/BuiltinFunction.h"
#include "core/render/RenderSettings.h"

namespace mfadvr {

// A shaded render of the Marschner-Lobb truth, the workhorse of the invariant tests.
inline RenderSettings mlSettings(int size) {
  RenderSettings s;
  s.width = s.height = size;
  s.camera.resetToBounds(BuiltinFunction::domainMin(), BuiltinFunction::domainMax());
  s.camera.azimuth(30);
  s.camera.elevation(20);
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{0.0, Vec3f(0.2f, 0.3f, 1.0f)}, {1.0, Vec3f(1.0f, 0.8f, 0.3f)}};
  s.transferFunction.opacity = {{0.0, 0.0f}, {0.45, 0.0f}, {0.55, 0.8f}, {1.0, 0.8f}};
  s.opacityUnitDistance = 0.05;
  s.sampleDistance = 0.01;
  s.shade = true;
  return s;
}

}  // namespace mfadvr
