#pragma once
// What a VTK scene says about a volume, in the core renderer's terms: the camera, the transfer
// function and the lights of a renderer and a vtkVolumeProperty, expressed in the volume's own
// (model) coordinates. Used by vtkMFAVolumeMapper; private to the module.
#include <optional>
#include <string>
#include <vector>

#include "core/render/Camera.h"
#include "core/render/Lighting.h"
#include "core/render/TransferFunction.h"
#include "core/render/TransferFunction2D.h"
#include "core/render/kernel/CameraRays.h"

class vtkCamera;
class vtkMatrix4x4;
class vtkRenderer;
class vtkVolumeProperty;

namespace mfadvr::vtkglue {

// World to model coordinates of a volume: x_model = linear * x_world + offset. Rays, distances
// and depths map exactly when the volume's matrix is a similarity (rotation, translation,
// uniform scale); `similarity` says whether it is, and `scale` is model units per world unit.
struct WorldToModel {
  double linear[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double offset[3] = {0, 0, 0};
  double scale = 1.0;
  bool similarity = true;

  Vec3d point(const Vec3d& p) const;
  Vec3d vector(const Vec3d& v) const;
};

// From the volume's model-to-world matrix (vtkProp3D::GetMatrix).
WorldToModel worldToModelOf(vtkMatrix4x4* modelToWorld);

// The camera in model coordinates (parallel scale in model units).
Camera cameraFromVtk(vtkCamera* camera, const WorldToModel& toModel);

// The primary rays of `renderer`'s current projection, in model coordinates, for an image of
// width x height pixels over the renderer's (tiled) viewport: the same frustum as VTK's own
// mappers, including a shifted window centre, view shear and the tiles of a large screenshot.
CameraRays raysFromVtk(vtkRenderer* renderer, const WorldToModel& toModel, int width, int height);

// The property's colour (or gray) and scalar opacity functions of component 0, in data values.
// Piecewise-linear RGB functions with default midpoints and sharpness convert exactly, node by
// node; any other (HSV/Lab/diverging colour space, shaped segments) is sampled at 1024 points
// over its node range. `notes` receives what cannot be honoured (for a warning).
TransferFunction transferFunctionFromVtk(vtkVolumeProperty* property,
                                         std::vector<std::string>& notes);

// The property's gradient opacity (component 0, 1-D mode, not disabled) with |grad f| in model
// units; empty when there is none or it is 1 everywhere.
std::vector<OpacityPoint> gradientOpacityFromVtk(vtkVolumeProperty* property,
                                                 const WorldToModel& toModel);

// The property's 2-D transfer function (TF_2D mode): an image of RGBA points placed by its origin
// and spacing, x in data values and y in |grad f| per world unit. None in 1-D mode, or (with a
// note) when the image is not such a table.
std::optional<TransferFunction2D> transferFunction2DFromVtk(vtkVolumeProperty* property,
                                                            const WorldToModel& toModel,
                                                            std::vector<std::string>& notes);

// The renderer's switched-on lights as directional lights in model coordinates, with the
// property's coefficients; positional lights shine from their position towards their focal
// point (noted).
Lighting lightingFromVtk(vtkRenderer* renderer, vtkVolumeProperty* property,
                         const WorldToModel& toModel, std::vector<std::string>& notes);

}  // namespace mfadvr::vtkglue
