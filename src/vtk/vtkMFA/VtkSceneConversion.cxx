#include "VtkSceneConversion.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>

namespace mfadvr::vtkglue {

namespace {

constexpr int kSamples = 1024;

Vec3d toVec(const double* v) {
  return Vec3d(v[0], v[1], v[2]);
}

bool plainSegments(const double* node, int midpointIndex) {
  return std::abs(node[midpointIndex] - 0.5) < 1e-12 && std::abs(node[midpointIndex + 1]) < 1e-12;
}

std::vector<ColorPoint> colorPoints(vtkColorTransferFunction* f, std::vector<std::string>& notes) {
  std::vector<ColorPoint> out;
  const int n = f->GetSize();
  bool exact = f->GetColorSpace() == VTK_CTF_RGB;
  for (int i = 0; i < n && exact; ++i) {
    double node[6];
    f->GetNodeValue(i, node);
    exact = plainSegments(node, 4);
  }
  if (exact) {
    for (int i = 0; i < n; ++i) {
      double node[6];
      f->GetNodeValue(i, node);
      out.push_back({node[0], Vec3f(float(node[1]), float(node[2]), float(node[3]))});
    }
  } else {
    const double* range = f->GetRange();
    std::vector<double> table(3 * kSamples);
    f->GetTable(range[0], range[1], kSamples, table.data());
    for (int i = 0; i < kSamples; ++i) {
      const double x = range[0] + (range[1] - range[0]) * i / (kSamples - 1);
      out.push_back(
          {x, Vec3f(float(table[3 * i]), float(table[3 * i + 1]), float(table[3 * i + 2]))});
    }
  }
  if (!f->GetClamping()) notes.push_back("colour transfer function clamping off is ignored");
  return out;
}

std::vector<ColorPoint> grayPoints(vtkPiecewiseFunction* f) {
  std::vector<ColorPoint> out;
  const double* range = f->GetRange();
  for (int i = 0; i < kSamples; ++i) {
    const double x = range[0] + (range[1] - range[0]) * i / (kSamples - 1);
    const float g = static_cast<float>(std::clamp(f->GetValue(x), 0.0, 1.0));
    out.push_back({x, Vec3f(g, g, g)});
  }
  return out;
}

std::vector<OpacityPoint> opacityPoints(vtkPiecewiseFunction* f) {
  std::vector<OpacityPoint> out;
  const int n = f->GetSize();
  bool exact = true;
  for (int i = 0; i < n && exact; ++i) {
    double node[4];
    f->GetNodeValue(i, node);
    exact = plainSegments(node, 2);
  }
  if (exact) {
    for (int i = 0; i < n; ++i) {
      double node[4];
      f->GetNodeValue(i, node);
      out.push_back({node[0], static_cast<float>(std::clamp(node[1], 0.0, 1.0))});
    }
  } else {
    const double* range = f->GetRange();
    for (int i = 0; i < kSamples; ++i) {
      const double x = range[0] + (range[1] - range[0]) * i / (kSamples - 1);
      out.push_back({x, static_cast<float>(std::clamp(f->GetValue(x), 0.0, 1.0))});
    }
  }
  return out;
}

}  // namespace

Vec3d WorldToModel::point(const Vec3d& p) const {
  return vector(p) + Vec3d(offset[0], offset[1], offset[2]);
}

Vec3d WorldToModel::vector(const Vec3d& v) const {
  Vec3d out;
  for (int r = 0; r < 3; ++r)
    out[r] = linear[r][0] * v[0] + linear[r][1] * v[1] + linear[r][2] * v[2];
  return out;
}

WorldToModel worldToModelOf(vtkMatrix4x4* modelToWorld) {
  WorldToModel t;
  if (!modelToWorld) return t;
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(modelToWorld, inverse);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t.linear[r][c] = inverse->GetElement(r, c);
    t.offset[r] = inverse->GetElement(r, 3);
  }
  // A similarity has L L^T = s^2 I.
  double gram[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      gram[r][c] = t.linear[r][0] * t.linear[c][0] + t.linear[r][1] * t.linear[c][1] +
                   t.linear[r][2] * t.linear[c][2];
  const double s2 = (gram[0][0] + gram[1][1] + gram[2][2]) / 3.0;
  t.scale = std::sqrt(s2);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (std::abs(gram[r][c] - (r == c ? s2 : 0.0)) > 1e-9 * s2) t.similarity = false;
  return t;
}

Camera cameraFromVtk(vtkCamera* camera, const WorldToModel& toModel) {
  Camera c;
  c.position = toModel.point(toVec(camera->GetPosition()));
  c.focalPoint = toModel.point(toVec(camera->GetFocalPoint()));
  c.viewUp = toModel.vector(toVec(camera->GetViewUp())).normalized();
  c.viewAngle = camera->GetViewAngle();
  c.parallelProjection = camera->GetParallelProjection() != 0;
  c.parallelScale = camera->GetParallelScale() * toModel.scale;
  return c;
}

CameraRays raysFromVtk(vtkRenderer* renderer, const WorldToModel& toModel, int width, int height) {
  int w = 0, h = 0, x0 = 0, y0 = 0;
  renderer->GetTiledSizeAndOrigin(&w, &h, &x0, &y0);
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkMatrix4x4* worldToClip = camera->GetCompositeProjectionTransformMatrix(
      static_cast<double>(std::max(w, 1)) / std::max(h, 1), -1, 1);
  vtkNew<vtkMatrix4x4> clipToWorld;
  vtkMatrix4x4::Invert(worldToClip, clipToWorld);
  // Points of the near (z = -1) or far (z = 1) clipping plane at normalized device x, y.
  auto unproject = [&](double x, double y, double z) {
    const double clip[4] = {x, y, z, 1.0};
    double world[4];
    clipToWorld->MultiplyPoint(clip, world);
    return toModel.point(Vec3d(world[0], world[1], world[2]) / world[3]);
  };
  // primaryRay walks the image plane as p(sx, sy) = base + sx right + sy up with sx, sy the
  // normalized device coordinates of the pixel centre (half extents 1): the near plane's
  // points are exactly such an affine function of them, whatever the frustum.
  const Vec3d n00 = unproject(0, 0, -1);
  const Vec3d right = unproject(1, 0, -1) - n00, up = unproject(0, 1, -1) - n00;
  CameraRays r;
  r.width = width;
  r.height = height;
  r.halfWidth = r.halfHeight = 1.0;
  r.parallel = camera->GetParallelProjection() != 0;
  Vec3d origin, forward;
  if (r.parallel) {
    origin = n00;  // rays start on the near plane and run parallel
    forward = (unproject(0, 0, 1) - n00).normalized();
  } else {
    origin = toModel.point(toVec(camera->GetPosition()));  // rays through the eye
    forward = n00 - origin;
  }
  for (int a = 0; a < 3; ++a) {
    r.position[a] = origin[a];
    r.forward[a] = forward[a];
    r.right[a] = right[a];
    r.up[a] = up[a];
  }
  return r;
}

TransferFunction transferFunctionFromVtk(vtkVolumeProperty* property,
                                         std::vector<std::string>& notes) {
  TransferFunction tf;
  tf.space = TfSpace::Data;
  if (property->GetColorChannels(0) == 1)
    tf.color = grayPoints(property->GetGrayTransferFunction(0));
  else
    tf.color = colorPoints(property->GetRGBTransferFunction(0), notes);
  tf.opacity = opacityPoints(property->GetScalarOpacity(0));
  if (tf.color.empty()) tf.color.push_back({0.0, Vec3f(1, 1, 1)});
  if (tf.opacity.empty()) tf.opacity.push_back({0.0, 1.0f});
  return tf;
}

std::vector<OpacityPoint> gradientOpacityFromVtk(vtkVolumeProperty* property,
                                                 const WorldToModel& toModel) {
  if (property->GetTransferFunctionMode() != vtkVolumeProperty::TF_1D ||
      !property->HasGradientOpacity(0) || property->GetDisableGradientOpacity(0))
    return {};
  std::vector<OpacityPoint> points = opacityPoints(property->GetGradientOpacity(0));
  bool constantOne = true;
  for (OpacityPoint& p : points) {
    constantOne = constantOne && p.alpha == 1.0f;
    // |grad f| per world unit -> per model unit (model lengths are world lengths x scale).
    p.x = std::max(0.0, p.x / toModel.scale);
  }
  if (constantOne) return {};
  return points;
}

std::optional<TransferFunction2D> transferFunction2DFromVtk(vtkVolumeProperty* property,
                                                            const WorldToModel& toModel,
                                                            std::vector<std::string>& notes) {
  if (property->GetTransferFunctionMode() != vtkVolumeProperty::TF_2D) return std::nullopt;
  vtkImageData* image = property->GetTransferFunction2D(0);
  vtkDataArray* rgba = image ? image->GetPointData()->GetScalars() : nullptr;
  int dims[3] = {0, 0, 0};
  if (image) image->GetDimensions(dims);
  if (!rgba || rgba->GetNumberOfComponents() != 4 || dims[0] < 2 || dims[1] < 2 || dims[2] != 1) {
    notes.push_back(
        "the 2-D transfer function needs an image of at least 2 x 2 points with 4 components "
        "(RGBA); rendering with the 1-D transfer function");
    return std::nullopt;
  }
  TransferFunction2D tf;
  tf.width = dims[0];
  tf.height = dims[1];
  tf.rgba.resize(static_cast<size_t>(tf.width) * tf.height * 4);
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(tf.width) * tf.height; ++i)
    for (int c = 0; c < 4; ++c)
      tf.rgba[i * 4 + c] = static_cast<float>(std::clamp(rgba->GetComponent(i, c), 0.0, 1.0));
  // The image's origin and spacing place it: x in data values, y in |grad f| per world unit.
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  tf.valueLo = origin[0];
  tf.valueHi = origin[0] + spacing[0] * (tf.width - 1);
  tf.gradientLo = std::max(0.0, origin[1]) / toModel.scale;
  tf.gradientHi = (origin[1] + spacing[1] * (tf.height - 1)) / toModel.scale;
  try {
    tf.validate();
  } catch (const std::exception& e) {
    notes.push_back(std::string(e.what()) + "; rendering with the 1-D transfer function");
    return std::nullopt;
  }
  return tf;
}

Lighting lightingFromVtk(vtkRenderer* renderer, vtkVolumeProperty* property,
                         const WorldToModel& toModel, std::vector<std::string>& notes) {
  Lighting l;
  l.ambient = static_cast<float>(property->GetAmbient(0));
  l.diffuse = static_cast<float>(property->GetDiffuse(0));
  l.specular = static_cast<float>(property->GetSpecular(0));
  l.specularPower = static_cast<float>(property->GetSpecularPower(0));
  l.headlight = false;
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  bool positional = false;
  while (vtkLight* light = lights->GetNextLight(it)) {
    if (!light->GetSwitch() || light->GetIntensity() <= 0.0) continue;
    const Vec3d from = toVec(light->GetTransformedPosition());
    const Vec3d to = toVec(light->GetTransformedFocalPoint());
    const Vec3d direction = toModel.vector(to - from);
    if (!(direction.norm() > 0.0)) continue;
    positional = positional || light->GetPositional();
    if (static_cast<int>(l.lights.size()) == mfadvr::kMaxLights) {
      notes.push_back("only the first " + std::to_string(mfadvr::kMaxLights) + " lights are used");
      break;
    }
    DirectionalLight d;
    d.direction = direction.normalized();
    const double* rgb = light->GetDiffuseColor();
    d.color = Vec3f(float(rgb[0]), float(rgb[1]), float(rgb[2]));
    d.intensity = static_cast<float>(light->GetIntensity());
    l.lights.push_back(d);
  }
  if (positional)
    notes.push_back("positional lights are treated as directional (no cone, no attenuation)");
  return l;
}

}  // namespace mfadvr::vtkglue
