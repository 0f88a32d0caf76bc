#pragma once
// Scenes of the GPU tests: Marschner-Lobb models of every kernel the GPU instantiates (degrees 1
// to 5, mixed degrees, a domain mask, a mesh's exact boundary) and transfer functions of every
// kind. Synthetic: the test
// program must run on a machine without data files.
#include <map>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/StructuredEncoder.h"
#include "core/model/Model.h"
#include "core/render/RenderSettings.h"

namespace mfadvr::test {

inline const StructuredGrid& mlGrid() {
  static const StructuredGrid g = sampleBuiltin(*makeBuiltin("marschner-lobb"), {33, 33, 33});
  return g;
}

inline Model fitted(int degree, int controls) {
  StructuredFitOptions o;
  o.degree = {degree, degree, degree};
  o.controlCounts = {controls, controls, controls};
  return fitStructured(mlGrid(), o);
}

inline const Model& mlModel(int degree) {
  static std::map<int, Model> cache;
  auto it = cache.find(degree);
  if (it == cache.end()) it = cache.emplace(degree, fitted(degree, 24)).first;
  return it->second;
}

// Degrees 2 and 3 on different axes: the run-time-degree kernel.
inline const Model& mixedDegreeModel() {
  static const Model m = [] {
    StructuredFitOptions o;
    o.degree = {2, 3, 2};
    o.controlCounts = {20, 24, 22};
    return fitStructured(mlGrid(), o);
  }();
  return m;
}

inline const Model& maskedModel() {
  static const Model m = [] {
    Model copy = mlModel(3);
    copy.setMask(test::ballMask());
    return copy;
  }();
  return m;
}

// A mesh's model: mlModel(3) on the octahedron of 8 tetrahedra around the box's centre, its
// corners 0.45 of the box's width from the centre. The exact boundary, not the ball mask it also
// carries, decides what is inside.
inline const Model& boundedModel() {
  static const Model m = [] {
    Model copy = mlModel(3);
    copy.setMask(test::ballMask());
    copy.setBoundary(test::octahedronBoundary(0.5 * (copy.domain().min + copy.domain().max),
                                              0.45 * (copy.domain().max - copy.domain().min)[0]));
    return copy;
  }();
  return m;
}

inline TransferFunction tfWith(TfSpace space, std::vector<OpacityPoint> opacity) {
  TransferFunction tf;
  tf.space = space;
  tf.color = {
      {0.0, Vec3f(0.1f, 0.2f, 1.0f)}, {0.5, Vec3f(1, 1, 1)}, {1.0, Vec3f(1.0f, 0.3f, 0.1f)}};
  tf.opacity = std::move(opacity);
  return tf;
}

// Steps, ramps, a band, everything visible, nothing visible; data and normalized space.
inline std::vector<TransferFunction> transferFunctions() {
  return {
      tfWith(TfSpace::Data, {{0.5, 0.0f}, {0.5, 0.8f}, {1.0, 0.8f}}),
      tfWith(TfSpace::Data, {{0.0, 0.0f}, {0.6, 0.0f}, {0.9, 1.0f}}),
      tfWith(TfSpace::Data, {{0.0, 0.0f}, {0.2, 0.0f}, {0.25, 0.7f}, {0.3, 0.0f}, {1.0, 0.0f}}),
      tfWith(TfSpace::Data, {{0.0, 0.0f}, {1.0, 1.0f}}),
      tfWith(TfSpace::Data, {{0.0, 0.0f}, {1.0, 0.0f}}),
      tfWith(TfSpace::Normalized, {{0.0, 0.0f}, {0.7, 0.1f}, {1.0, 0.9f}}),
  };
}

// A 2-D transfer function over values [0, 1] and |grad f| in [0, 4]: colour ramps along both
// axes, opaque only at higher values and gradients (the gradient tests of both devices).
inline TransferFunction2D stripedTransferFunction2D() {
  TransferFunction2D t;
  t.width = 12;
  t.height = 6;
  t.valueHi = 1.0;
  t.gradientHi = 4.0;
  for (int j = 0; j < t.height; ++j)
    for (int i = 0; i < t.width; ++i)
      t.rgba.insert(t.rgba.end(), {float(i) / (t.width - 1), 0.5f, float(j) / (t.height - 1),
                                   j >= 2 && i >= 4 ? 0.7f : 0.0f});
  return t;
}

inline RenderSettings settingsFor(const Vec3d& lo, const Vec3d& hi, const TransferFunction& tf,
                                  bool shade) {
  RenderSettings s;
  s.width = 96;
  s.height = 80;
  s.camera.resetToBounds(lo, hi);
  s.camera.azimuth(25);
  s.camera.elevation(15);
  s.sampleDistance = 0.01;
  s.opacityUnitDistance = 0.03;
  // Renders take data-space functions: normalized ones span about the model's values.
  s.transferFunction = tf.resolved(-0.1, 1.1);
  s.shade = shade;
  s.background = Vec3f(0.1f, 0.1f, 0.15f);
  return s;
}

}  // namespace mfadvr::test
