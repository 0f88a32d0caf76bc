#pragma once
// Our scene in VTK's terms: VTK data sets made from our grids and meshes, and RenderSettings
// applied to a vtkRenderer, its camera and a vtkVolumeProperty, so that VTK's volume mappers
// render the scene our ray caster renders (docs/rendering.md, "VTK baselines").
#include <vtkSmartPointer.h>

#include "core/grid/StructuredGrid.h"
#include "core/image/Image.h"
#include "core/mesh/ScatteredData.h"
#include "core/render/RenderSettings.h"

class vtkImageData;
class vtkRenderWindow;
class vtkRenderer;
class vtkUnstructuredGrid;
class vtkVolumeProperty;

namespace mfadvr {

// The grid as vtkImageData with its origin and spacing and the values as float32 point scalars
// named "value" (both x fastest).
vtkSmartPointer<vtkImageData> makeImageData(const StructuredGrid& grid);

// The mesh's tetrahedra as VTK_TETRA cells, its values as float32 point scalars "value".
// Throws mfadvr::Error when the data have no cells (a point cloud).
vtkSmartPointer<vtkUnstructuredGrid> makeTetrahedralMesh(const ScatteredData& data);

// The grid's voxels split into tetrahedra (vtkDataSetTriangleFilter: 5 per voxel, alternating so
// that neighbouring voxels share faces), with the point scalars carried over.
vtkSmartPointer<vtkUnstructuredGrid> tetrahedralize(vtkImageData* image);

// Copies position, focal point, view-up, view angle, projection and parallel scale into the
// renderer's active camera, then fits only the clipping range (never ResetCamera, which would
// change the framing).
void applyCamera(const Camera& camera, vtkRenderer* renderer);

// How a VTK mapper reads the scalar opacity function. VTK's ray casters over grids (fixed point,
// GPU) composite samples with opacity correction, 1 - (1 - a)^(step / unit distance), as ours
// does: the TF's opacity a is what one unit distance accumulates. VTK's tetrahedral renderers read
// it as an attenuation coefficient instead, a / unit distance per unit length (Bunyk and ZSweep
// through vtkUnstructuredGridPreIntegration, projected tetrahedra in its shader), which agrees
// only for small a: at a = 1 ours is opaque at once, theirs is not.
enum class VtkOpacityReading { PerUnitDistance, Attenuation };

// The resolved transfer function point by point (vtkColorTransferFunction in RGB space,
// vtkPiecewiseFunction), linear interpolation, ScalarOpacityUnitDistance, shading on/off and the
// Blinn-Phong coefficients. Our TFs may repeat an x to make a jump; VTK replaces a point with a
// repeated x, so the earlier point moves left by 1e-6 of the TF's span instead. For a mapper that
// reads opacity as attenuation, the opacity function holds the equivalent coefficient
// -ln(1 - a) (a capped at 1 - 1e-6), at the TF's points and 256 points between, so that it
// renders the same optical model as our ray caster and VTK's grid casters.
void applyTransferFunction(const RenderSettings& settings, vtkVolumeProperty* property,
                           VtkOpacityReading reading = VtkOpacityReading::PerUnitDistance);

// Our lights as vtkLights, replacing the renderer's automatic one: the headlight as a vtkLight
// headlight, each directional light as a scene light shining along its direction. VTK's shading
// adds property.Ambient x light.AmbientColor x light.Intensity for every light, and a vtkLight's
// ambient colour is black by default; our ambient term is added once, so one extra light carries
// it (ambient colour white, diffuse and specular black) and the others have black ambient.
void applyLighting(const Lighting& lighting, vtkRenderer* renderer);

// The window's colour buffer as 8-bit RGB, row 0 at the top (VTK's is at the bottom). Throws
// mfadvr::Error when the read-back is not 8-bit RGB.
Image8 readWindowRgb(vtkRenderWindow* window);

// Background colour of the renderer.
void applyBackground(const Vec3f& background, vtkRenderer* renderer);

}  // namespace mfadvr
