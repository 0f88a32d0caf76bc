/**
 * @class   vtkMFAEncoder
 * @brief   fits an MFA model to image data, a mesh or a point cloud
 *
 * The input is any vtkDataSet. vtkImageData (axis-aligned) is fitted as a grid by separable
 * least squares; every other data set is fitted as scattered points (regularized least squares)
 * and gets a domain mask: mesh occupancy when it has 3-D cells, point coverage otherwise. The
 * output is a vtkMFAModelData. The options are those of `mfadvr encode` (docs/encoding.md).
 *
 * The scalar field is chosen with SetInputArrayToProcess(0, 0, 0, association, name); by
 * default the active point scalars (else the first one-component point array, else a cell
 * array, averaged to the points).
 *
 * In a parallel pipeline (ParaView's ranks), each piece fits its own part: image data are
 * requested as the piece's extent grown by GhostLevels layers of the neighbouring pieces'
 * samples (one extent, not ghost levels: the input then carries no ghost-mark array), fitted
 * together with them, and the model renders only the piece's own extent (PieceEncoder.h); a
 * plain scalar array is read where it is, without a float32 copy; control counts are
 * then for the whole image and scaled to the piece. With OutputImageData on, the output is an
 * image carrying the model and its region (vtkMFAModelAlgorithm), which is how ParaView moves
 * it.
 *
 * With TimeSeries on, image data whose source advertises time steps (a file series in ParaView)
 * become one 4-D model (docs/time-varying.md): the steps are read from the input one at a time
 * (the encoder asks its input for each step's time, UpdateTimeStep), fitted, and the output is
 * the model at the time asked for, any time in the range. The model is kept until a property or
 * the input changes: playing the animation contracts it, without reading the steps again.
 *
 * Errors (no scalar field, bad options, a flat box) are reported with vtkErrorMacro and leave
 * the output empty.
 */
#ifndef vtkMFAEncoder_h
#define vtkMFAEncoder_h

#include "vtkMFAModelAlgorithm.h"
#include "vtkMFAModule.h"  // for export macro

#ifndef __VTK_WRAP__
#include <memory>  // for std::shared_ptr
#include <string>  // for the field name

namespace mfadvr {
struct EncodeOptions;
struct FitReport;
}  // namespace mfadvr
#endif

class VTKMFA_EXPORT vtkMFAEncoder : public vtkMFAModelAlgorithm {
 public:
  static vtkMFAEncoder* New();
  vtkTypeMacro(vtkMFAEncoder, vtkMFAModelAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The data set to encode, without a pipeline (SetInputConnection connects one).
   */
  void SetInputData(vtkDataObject* data) { this->SetInputDataObject(0, data); }

  //@{
  /**
   * Spline degree on every axis, 1..7 (default 3).
   */
  vtkSetClampMacro(Degree, int, 1, 7);
  vtkGetMacro(Degree, int);
  //@}

  //@{
  /**
   * Control points per axis (0: the default, which for a grid is the sample count, i.e.
   * interpolation). With MaxError set, the starting counts of adaptive refinement.
   */
  vtkSetVector3Macro(NumberOfControlPoints, int);
  vtkGetVector3Macro(NumberOfControlPoints, int);
  //@}

  //@{
  /**
   * Adaptive encoding: refine the knots until the maximum error at every input sample is at
   * most MaxError times the value range (0, the default: a fixed-size fit).
   */
  vtkSetClampMacro(MaxError, double, 0.0, 1.0);
  vtkGetMacro(MaxError, double);
  //@}

  //@{
  /**
   * Adaptive encoding: per-axis cap on control points (0: the sample count for grids, 256 for
   * scattered data) and on refinement rounds (default 30).
   */
  vtkSetVector3Macro(MaxNumberOfControlPoints, int);
  vtkGetVector3Macro(MaxNumberOfControlPoints, int);
  vtkSetClampMacro(MaxRounds, int, 1, 1000);
  vtkGetMacro(MaxRounds, int);
  //@}

  //@{
  /**
   * Scattered inputs: weight of the curvature penalty (default 1e-2, dimensionless).
   */
  vtkSetClampMacro(Smoothing, double, 0.0, 1e6);
  vtkGetMacro(Smoothing, double);
  //@}

  //@{
  /**
   * Scattered inputs: choose the Smoothing weight from the data by hold-out cross-validation,
   * as `mfadvr encode --smooth auto` (one point in eight held out; several fits, so an encode
   * takes several times longer; docs/encoding.md). Off by default. Each piece chooses its own
   * (pieces of a mesh are fitted apart). GetLastSmoothing() gives the weight the fit used.
   */
  vtkSetMacro(AutoSmoothing, bool);
  vtkGetMacro(AutoSmoothing, bool);
  vtkBooleanMacro(AutoSmoothing, bool);
  //@}

  //@{
  /**
   * Scattered inputs: how far the knots follow the points' density along each axis, 0 (uniform)
   * to 0.99, as `encode --knot-density`; -1 (the default): 0.75 for meshes (control points
   * gather where the mesh is refined), 0 for point clouds.
   */
  vtkSetClampMacro(KnotDensity, double, -1.0, 0.99);
  vtkGetMacro(KnotDensity, double);
  //@}

  //@{
  /**
   * Meshes: samples of the mesh's own field (linear in each tetrahedron) fitted per tetrahedron
   * beside its points, as `encode --cell-samples`: 0 (the points alone), 1 (centroids) or 4;
   * -1 (the default): the encoder's choice, 1 for meshes, 0 for point clouds and for fits with
   * a MaxError or automatic smoothing. Other values make the update fail. Point clouds: -1 or 0.
   */
  vtkSetMacro(CellSamples, int);
  vtkGetMacro(CellSamples, int);
  //@}

  //@{
  /**
   * Image data: weight lambda of the roughness penalty, a smoothing fit for noisy or quantized
   * samples (default 0: none; at most 1e4; docs/denoise.md). The same lambda for every piece, so
   * that pieces agree; `mfadvr encode --smooth auto` chooses one from the data.
   */
  vtkSetClampMacro(ImageSmoothing, double, 0.0, 1e4);
  vtkGetMacro(ImageSmoothing, double);
  //@}

  //@{
  /**
   * With OutputImageData and image data whose field is a point array: the carrier's point
   * scalars are the input's samples (the input's own array, shared without a copy) instead of
   * the model evaluated on the grid. A piece of a parallel pipeline then keeps the input's
   * extent, ghost layers included, its cells outside the piece's own extent marked as ghost
   * cells (vtkGhostType); the models' regions stay the piece's own. Saves the evaluation and a
   * float per sample (docs/paraview.md); slices, contours and colour ranges of the carrier
   * then show the data, the volume the model. Default off.
   */
  vtkSetMacro(PassInputValues, bool);
  vtkGetMacro(PassInputValues, bool);
  vtkBooleanMacro(PassInputValues, bool);
  //@}

  //@{
  /**
   * Scattered inputs: whether the model gets a domain mask (default on), and the mask's nodes
   * along the longest box axis (0: the default for the kind of input).
   */
  vtkSetMacro(DomainMask, bool);
  vtkGetMacro(DomainMask, bool);
  vtkBooleanMacro(DomainMask, bool);
  vtkSetClampMacro(MaskResolution, int, 0, 4096);
  vtkGetMacro(MaskResolution, int);
  //@}

  //@{
  /**
   * Image data split into pieces: sample layers of the neighbouring pieces each piece is fitted
   * with, so that the pieces' models agree across their common faces (-1, the default:
   * 2 x (Degree + 1)).
   */
  vtkSetClampMacro(GhostLevels, int, -1, 1024);
  vtkGetMacro(GhostLevels, int);
  //@}

  //@{
  /**
   * Image data with time steps: fit every step into one 4-D model and output it at the time
   * asked for (any time in the input's range, not only its steps), instead of fitting the step
   * asked for on its own (default off). The options above apply to the 4-D model as to
   * `mfadvr encode SERIES` (MaxError refines one set of knots for every step). One process only:
   * a parallel pipeline's pieces are an error in this mode.
   */
  vtkSetMacro(TimeSeries, bool);
  vtkGetMacro(TimeSeries, bool);
  vtkBooleanMacro(TimeSeries, bool);
  //@}

  //@{
  /**
   * TimeSeries: the degree in time (1..7, default 3; lowered for fewer steps) and the control
   * points in time (0, the default: one per step, interpolating every step; fewer: a
   * least-squares fit in time), as `encode --time-degree` and `--time-ctrl`.
   */
  vtkSetClampMacro(TimeDegree, int, 1, 7);
  vtkGetMacro(TimeDegree, int);
  vtkSetClampMacro(TimeControlPoints, int, 0, 1 << 20);
  vtkGetMacro(TimeControlPoints, int);
  //@}

  //@{
  /**
   * Write each fitted model (the 4-D model with TimeSeries) to this .mfa file, whole or not at
   * all (empty, the default: not written). `mfadvr render`, `view` and vtkMFAReader open it.
   */
  vtkSetStringMacro(ModelFileName);
  vtkGetStringMacro(ModelFileName);
  //@}

  //@{
  /**
   * Results of the last fit: maximum and RMS error over every input sample, relative to the
   * value range, and the fit's wall time in seconds.
   */
  vtkGetMacro(LastMaxRelativeError, double);
  vtkGetMacro(LastRMSRelativeError, double);
  vtkGetMacro(LastFitSeconds, double);
  // The smoothing weight of the last fit (the chosen one with AutoSmoothing).
  vtkGetMacro(LastSmoothing, double);
  //@}

 protected:
  vtkMFAEncoder();
  ~vtkMFAEncoder() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int EffectiveGhostLevels() const;
  // The sample layers a piece asks for beyond its own extent: the ghost levels the output was
  // asked for and EffectiveGhostLevels().
  int PieceLayers(vtkInformation* outputRequest) const;

  int Degree = 3;
  int GhostLevels = -1;
  int NumberOfControlPoints[3] = {0, 0, 0};
  double MaxError = 0.0;
  int MaxNumberOfControlPoints[3] = {0, 0, 0};
  int MaxRounds = 30;
  double Smoothing = 1e-2;
  bool AutoSmoothing = false;
  double KnotDensity = -1.0;
  int CellSamples = -1;
  double ImageSmoothing = 0.0;
  bool DomainMask = true;
  int MaskResolution = 0;
  bool PassInputValues = false;
  bool TimeSeries = false;
  int TimeDegree = 3;
  int TimeControlPoints = 0;
  char* ModelFileName = nullptr;

  double LastMaxRelativeError = 0.0;
  double LastRMSRelativeError = 0.0;
  double LastFitSeconds = 0.0;
  double LastSmoothing = 0.0;

 private:
#ifndef __VTK_WRAP__
  // The 4-D model of TimeSeries, with what it was fitted from.
  struct SeriesFit;
  std::shared_ptr<SeriesFit> Series;
  // TimeSeries: fits (or reuses) the 4-D model and outputs the instant asked for; `options`
  // are the properties' (their smoothing the scattered one).
  int RequestSeriesData(vtkInformationVector** inInfo, vtkInformationVector* outInfo,
                        const std::string& field, const mfadvr::EncodeOptions& properties);
  // The Last* results of a fit, the warning of a bound not reached, and the model file.
  template <class M>
  void TakeFit(const mfadvr::FitReport& report, const M& model, bool adaptive);
#endif
  vtkMFAEncoder(const vtkMFAEncoder&) = delete;
  void operator=(const vtkMFAEncoder&) = delete;
};

#endif
