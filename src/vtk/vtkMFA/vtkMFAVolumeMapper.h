/**
 * @class   vtkMFAVolumeMapper
 * @brief   renders an MFA model directly, with exact values and gradients at every sample
 *
 * A volume mapper for ordinary VTK scenes: it takes the camera, the renderer's lights and the
 * vtkVolumeProperty (colour and scalar opacity functions, shading, ambient / diffuse /
 * specular / specular power, scalar opacity unit distance) and ray casts the model with the
 * mfadvr ray caster on the CPU, all cores. Rays stop at opaque geometry already drawn (the
 * depth buffer), so the volume blends correctly with surfaces in the scene. The image is drawn
 * pixel for pixel over the viewport as premultiplied colour (OpenGL render windows).
 *
 * Input (one port, connected the usual way: SetInputConnection / SetInputData): an MFA model
 * (vtkMFAModelData, from vtkMFAReader or vtkMFAEncoder), or any vtkDataSet (image data, a
 * mesh, a point cloud), which is encoded with GetEncoder()'s options (by default, for image
 * data, an interpolating cubic fit) and re-encoded only when it or the options change. An
 * image that carries models (the output of vtkMFAReader or vtkMFAEncoder with
 * OutputImageData on, as in ParaView) is rendered as its models: each in its own region, with
 * samples at multiples of the sample distance along each ray so that the pieces of a
 * partitioned volume, here or on other ranks, composite to the image of the whole.
 * SetMFAInputConnection / SetMFAInputData are the same port under older names.
 *
 * Blend modes composite, maximum, minimum, average (with its AverageIPScalarRange), additive
 * and isosurface (the property's GetIsoSurfaceValues(), exact crossings of the model; up to 8)
 * (docs/rendering.md gives their rules), clipping planes (up to 8) and sub-volume cropping are
 * honoured. Not supported (a warning says so once): the slice blend mode, cropping flags other
 * than the sub-volume, gradient opacity, multi-component data.
 */
#ifndef vtkMFAVolumeMapper_h
#define vtkMFAVolumeMapper_h

#include "vtkMFAModule.h"  // for export macro
#include "vtkVolumeMapper.h"

#ifndef __VTK_WRAP__
#include <functional>  // for std::function
namespace mfadvr {
struct Image;
struct RenderSettings;
}  // namespace mfadvr
#endif
#include <memory>  // for std::unique_ptr
#include <string>  // for std::string

class vtkAlgorithmOutput;
class vtkMFAEncoder;
class vtkMFAModelData;

class VTKMFA_EXPORT vtkMFAVolumeMapper : public vtkVolumeMapper {
 public:
  static vtkMFAVolumeMapper* New();
  vtkTypeMacro(vtkMFAVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  //@{
  /**
   * The data to render without a pipeline: a model, or a data set to encode. The overloads of
   * vtkVolumeMapper (vtkImageData, vtkDataSet) stay available.
   */
  using Superclass::SetInputData;
  void SetInputData(vtkMFAModelData* model);
  //@}

  /**
   * Whether `data` is image data that carries MFA models (the output of vtkMFAReader or of
   * vtkMFAEncoder with OutputImageData): what this mapper renders as models, not as samples.
   */
  static bool CarriesModels(vtkDataObject* data);

  //@{
  /**
   * Aliases of SetInputConnection / SetInputData (port 0), kept for programs written when the
   * model had a port of its own.
   */
  void SetMFAInputConnection(vtkAlgorithmOutput* output);
  void SetMFAInputData(vtkMFAModelData* model);
  //@}

  /**
   * The model rendered by the last Render (or the one the inputs give now, after an update);
   * null when there is none.
   */
  vtkMFAModelData* GetMFAInput();

  /**
   * The encoder used when the input is a data set rather than a model; set its options before
   * the first render.
   */
  vtkMFAEncoder* GetEncoder();

  //@{
  /**
   * Distance between samples along a ray, in world units. 0 (the default): half the smallest
   * spacing of the data the model was fitted to (for scattered data, of its control points or
   * mask nodes, whichever is finer), as `mfadvr render` does.
   */
  vtkSetClampMacro(SampleDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SampleDistance, double);
  //@}

  //@{
  /**
   * Rays are cast for every ImageSampleDistance-th pixel in x and y and the image is
   * magnified (1: every pixel). With AutoAdjustSampleDistances on (the default), interactive
   * frames (an allocated render time below one second, as set by the interactor's desired
   * update rate) pick a distance between the minimum and maximum that meets the allocated
   * time; still frames use ImageSampleDistance.
   */
  vtkSetClampMacro(ImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(ImageSampleDistance, double);
  vtkSetClampMacro(MinimumImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(MinimumImageSampleDistance, double);
  vtkSetClampMacro(MaximumImageSampleDistance, double, 1.0, 32.0);
  vtkGetMacro(MaximumImageSampleDistance, double);
  vtkSetMacro(AutoAdjustSampleDistances, bool);
  vtkGetMacro(AutoAdjustSampleDistances, bool);
  vtkBooleanMacro(AutoAdjustSampleDistances, bool);
  //@}

  //@{
  /**
   * A ray stops once its opacity reaches this (default 0.99; above 1 disables it).
   */
  vtkSetClampMacro(EarlyRayTerminationOpacity, double, 0.01, 2.0);
  vtkGetMacro(EarlyRayTerminationOpacity, double);
  //@}

  //@{
  /**
   * Worker threads (0, the default: all cores). Images do not depend on it.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  //@}

  //@{
  /**
   * Where the ray caster runs: DeviceAuto (the default: a CUDA GPU when this build has the CUDA
   * backend and a GPU is usable, else the CPU), DeviceCPU, or DeviceCUDA (an error, and no
   * volume drawn, when no GPU is usable). GPU and CPU images differ only by float rounding.
   * Each model is uploaded to the GPU once and kept for the next frames.
   */
  enum DeviceType { DeviceAuto = 0, DeviceCPU = 1, DeviceCUDA = 2 };
  vtkSetClampMacro(Device, int, DeviceAuto, DeviceCUDA);
  vtkGetMacro(Device, int);
  void SetDeviceToAuto() { this->SetDevice(DeviceAuto); }
  void SetDeviceToCPU() { this->SetDevice(DeviceCPU); }
  void SetDeviceToCUDA() { this->SetDevice(DeviceCUDA); }
  //@}

  //@{
  /**
   * Curvature transfer function (docs/transfer-functions.md, "Curvature transfer functions"):
   * a preset "ridges-valleys", "mean" or "gaussian" with an optional ":K" (the curvature of
   * full colour, 1 / world units; default 1 / (8 x the model's smallest data spacing)), or the
   * path of a JSON table over (k1, k2) in 1 / world units. Null or empty (the default): none.
   * Composite and isosurface blends; a specification that cannot be read is an error of the
   * render (nothing is drawn).
   */
  vtkSetStringMacro(CurvatureTransferFunction);
  vtkGetStringMacro(CurvatureTransferFunction);
  //@}

  //@{
  /**
   * Thickness-controlled contours (silhouette lines of one width in pixels, from the curvature
   * along the view): their width in pixels of the viewport (0, the default: none) and colour.
   * Composite and isosurface blends.
   */
  vtkSetClampMacro(ContourWidth, double, 0.0, 64.0);
  vtkGetMacro(ContourWidth, double);
  vtkSetVector3Macro(ContourColor, double);
  vtkGetVector3Macro(ContourColor, double);
  //@}

  //@{
  /**
   * Whether the volume writes its depth into the depth buffer, so that geometry and volumes
   * drawn after it (translucent geometry, other volumes, later renderers' layers) are hidden
   * behind it: WriteDepthNever; WriteDepthIsosurfaces (the default), the first isosurface hit of
   * each ray in the isosurface blend; WriteDepthAlways, also in the other blends the depth of
   * `mfadvr render --depth` (where a ray's opacity first reaches 0.5, its maximum or minimum
   * sample, or its first visible sample; docs/rendering.md). Pixels without one keep the depth
   * buffer as it was. A depth costs composite frames about a tenth (they then go without ray
   * packets), isosurface frames nothing.
   */
  enum { WriteDepthNever = 0, WriteDepthIsosurfaces = 1, WriteDepthAlways = 2 };
  vtkSetClampMacro(WriteDepth, int, WriteDepthNever, WriteDepthAlways);
  vtkGetMacro(WriteDepth, int);
  void SetWriteDepthToNever() { this->SetWriteDepth(WriteDepthNever); }
  void SetWriteDepthToIsosurfaces() { this->SetWriteDepth(WriteDepthIsosurfaces); }
  void SetWriteDepthToAlways() { this->SetWriteDepth(WriteDepthAlways); }
  //@}

  /**
   * The device the last frame ran on (DeviceCPU or DeviceCUDA), and its description: the GPU's
   * name, or with DeviceAuto on the CPU, why the GPU was not used.
   */
  vtkGetMacro(LastDevice, int);
  const char* GetLastDeviceDescription();

  /**
   * The image sample distance the last frame used.
   */
  vtkGetMacro(LastImageSampleDistance, double);

  //@{
  /**
   * The volume's bounds: the model's box in world coordinates.
   */
  double* GetBounds() VTK_SIZEHINT(6) override;
  void GetBounds(double bounds[6]) override;
  //@}

  vtkDataObject* GetDataObjectInput() override;

#ifndef __VTK_WRAP__
  /**
   * C++ only: renders the scene with `render` instead of the model (which still gives the
   * bounds), e.g. another reconstruction of the same data through the same ray caster, for side
   * by side comparisons (the `mfadvr view` command). The function receives the settings the
   * mapper derived from the VTK scene, in the model's coordinates, and returns the premultiplied
   * image (background 0). An empty function restores the model.
   */
  void SetFieldRenderer(std::function<mfadvr::Image(const mfadvr::RenderSettings&)> render);
#endif

  void Render(vtkRenderer* ren, vtkVolume* vol) override;

 protected:
  vtkMFAVolumeMapper();
  ~vtkMFAVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  double SampleDistance = 0.0;
  double ImageSampleDistance = 1.0;
  double MinimumImageSampleDistance = 1.0;
  double MaximumImageSampleDistance = 8.0;
  bool AutoAdjustSampleDistances = true;
  double EarlyRayTerminationOpacity = 0.99;
  int NumberOfThreads = 0;
  int Device = DeviceAuto;
  int LastDevice = DeviceCPU;
  double LastImageSampleDistance = 1.0;
  char* CurvatureTransferFunction = nullptr;
  double ContourWidth = 0.0;
  double ContourColor[3] = {0.0, 0.0, 0.0};
  int WriteDepth = WriteDepthIsosurfaces;

 private:
  vtkMFAVolumeMapper(const vtkMFAVolumeMapper&) = delete;
  void operator=(const vtkMFAVolumeMapper&) = delete;

  vtkMFAModelData* UpdateModel();
  double ChooseImageSampleDistance(vtkVolume* vol);
  void WarnOnce(const std::string& note);

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
