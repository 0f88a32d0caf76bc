/**
 * @class   vtkMFAVolumeRepresentation
 * @brief   ParaView's volume representation of image data, rendering MFA models
 *
 * The "MFA Volume" representation: ParaView's image volume representation (colour and
 * opacity maps, shading, lights, ordered compositing across ranks) with vtkMFAVolumeMapper in
 * place of VTK's mappers. Its input is an image that carries MFA models (the output of the MFA
 * reader or the MFA Encode filter); each rank renders the models it holds, each in its region,
 * and ParaView composites the ranks' premultiplied images in visibility order by their bounds.
 */
#ifndef vtkMFAVolumeRepresentation_h
#define vtkMFAVolumeRepresentation_h

#include "vtkImageVolumeRepresentation.h"
#include "vtkMFAParaViewModule.h"  // for export macro

class vtkMFAVolumeMapper;

class VTKMFAPARAVIEW_EXPORT vtkMFAVolumeRepresentation : public vtkImageVolumeRepresentation {
 public:
  static vtkMFAVolumeRepresentation* New();
  vtkTypeMacro(vtkMFAVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  //@{
  /**
   * Forwarded to vtkMFAVolumeMapper: distance between samples along a ray (0: half the data
   * spacing), early ray termination opacity, image sample distance of still frames and the
   * largest one of interactive frames.
   */
  void SetSampleDistance(double distance);
  void SetEarlyRayTerminationOpacity(double opacity);
  void SetImageSampleDistance(double distance);
  void SetMaximumImageSampleDistance(double distance);
  //@}

  //@{
  /**
   * Forwarded to vtkMFAVolumeMapper: the curvature transfer function (a preset
   * "ridges-valleys", "mean", "gaussian" with an optional ":K", or a JSON table's path; empty:
   * none), the contours' width in pixels (0: none) and their colour.
   */
  void SetCurvatureTransferFunction(const char* spec);
  void SetContourWidth(double pixels);
  void SetContourColor(double r, double g, double b);
  //@}

  //@{
  /**
   * The blend mode: ParaView's Blend Mode (SetBlendMode, which in ParaView 5.11 lists
   * Composite, Isosurface and Slice) unless the representation's own MFABlendMode is set to one
   * of vtkVolumeMapper's modes (composite, maximum, minimum, average intensity, additive,
   * isosurface); -1, the default: ParaView's.
   */
  void SetBlendMode(int mode);
  void SetMFABlendMode(int mode);
  //@}

  //@{
  /**
   * Where the mapper's ray caster runs (vtkMFAVolumeMapper::SetDevice): 0 auto (a CUDA GPU when
   * the plugin was built with the CUDA backend and one is usable, else the CPU), 1 the CPU, 2
   * CUDA (an error and no image when no GPU can render). GetLastDeviceDescription says where the
   * last frame ran: the GPU's name, or the CPU and why not the GPU.
   */
  void SetDevice(int device);
  const char* GetLastDeviceDescription();
  //@}

 protected:
  vtkMFAVolumeRepresentation();
  ~vtkMFAVolumeRepresentation() override;

  /**
   * The mapper (set in the constructor; the superclass holds it as a vtkVolumeMapper).
   */
  vtkMFAVolumeMapper* GetMFAMapper();

  /**
   * As the superclass, except for a carrier with ghost cells (MFA Encode's output on a rank, with
   * Pass Input Values: its scalars are the input's own array, ghost layers included). The
   * superclass would crop the ghost cells away, a copy of the rank's piece; the mapper renders
   * the models' regions only, so it takes the carrier whole, and the regions are the bounds
   * (outline, ordered compositing) of the rank.
   */
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * As the superclass, then the blend mode chosen by SetBlendMode / SetMFABlendMode.
   */
  void UpdateMapperParameters() override;

 private:
  void ApplyBlendMode();
  int ParaViewBlendMode = 0;  // vtkVolumeMapper::COMPOSITE_BLEND
  int MFABlendMode = -1;

  vtkMFAVolumeRepresentation(const vtkMFAVolumeRepresentation&) = delete;
  void operator=(const vtkMFAVolumeRepresentation&) = delete;
};

#endif
