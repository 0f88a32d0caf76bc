#include "vtkMFAEncoder.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkExtentTranslator.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationVector.h"
#include "vtkMFAModelData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <sstream>
#include <string>

#include "VtkModelImage.h"
#include "core/encode/Encoder.h"
#include "core/encode/FitReport.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/TimeSeriesEncoder.h"
#include "core/grid/VolumeSeries.h"
#include "core/model/Model.h"
#include "core/model/ModelFile.h"
#include "core/model/TimeVaryingModel.h"
#include "core/util/Error.h"
#include "io/VtkDataConversion.h"

vtkStandardNewMacro(vtkMFAEncoder);

vtkMFAEncoder::vtkMFAEncoder() {
  this->SetNumberOfInputPorts(1);
  // Active point scalars unless the caller picks an array.
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
                               vtkDataSetAttributes::SCALARS);
}

vtkMFAEncoder::~vtkMFAEncoder() {
  this->SetModelFileName(nullptr);
}

// The 4-D model of TimeSeries and what it was fitted from: it serves every time asked for until
// the pipeline (this filter's properties or anything upstream) changes.
struct vtkMFAEncoder::SeriesFit {
  std::shared_ptr<const mfadvr::TimeVaryingModel> model;
  vtkMTimeType pipelineTime = 0;
  std::vector<double> steps;
  std::string field;
  double loadedTime = 0.0;  // the step the input holds after the fit
  // The instant last given (rendering one time again does not contract the time axis again).
  std::shared_ptr<const mfadvr::Model> instant;
  double instantTime = 0.0;
};

void vtkMFAEncoder::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Degree: " << this->Degree << "\n";
  os << indent << "NumberOfControlPoints: " << this->NumberOfControlPoints[0] << " "
     << this->NumberOfControlPoints[1] << " " << this->NumberOfControlPoints[2] << "\n";
  os << indent << "MaxError: " << this->MaxError << "\n";
  os << indent << "MaxNumberOfControlPoints: " << this->MaxNumberOfControlPoints[0] << " "
     << this->MaxNumberOfControlPoints[1] << " " << this->MaxNumberOfControlPoints[2] << "\n";
  os << indent << "MaxRounds: " << this->MaxRounds << "\n";
  os << indent << "Smoothing: " << this->Smoothing << "\n";
  os << indent << "AutoSmoothing: " << this->AutoSmoothing << "\n";
  os << indent << "ImageSmoothing: " << this->ImageSmoothing << "\n";
  os << indent << "KnotDensity: " << this->KnotDensity << "\n";
  os << indent << "CellSamples: " << this->CellSamples << "\n";
  os << indent << "DomainMask: " << this->DomainMask << "\n";
  os << indent << "MaskResolution: " << this->MaskResolution << "\n";
  os << indent << "GhostLevels: " << this->GhostLevels << "\n";
  os << indent << "PassInputValues: " << this->PassInputValues << "\n";
  os << indent << "TimeSeries: " << this->TimeSeries << "\n";
  os << indent << "TimeDegree: " << this->TimeDegree << "\n";
  os << indent << "TimeControlPoints: " << this->TimeControlPoints << "\n";
  os << indent << "ModelFileName: " << (this->ModelFileName ? this->ModelFileName : "(none)")
     << "\n";
}

int vtkMFAEncoder::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkMFAEncoder::EffectiveGhostLevels() const {
  return this->GhostLevels >= 0
             ? this->GhostLevels
             : mfadvr::defaultGhostLayers({this->Degree, this->Degree, this->Degree});
}

int vtkMFAEncoder::PieceLayers(vtkInformation* out) const {
  using SDDP = vtkStreamingDemandDrivenPipeline;
  const int asked = out->Has(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS())
                        ? out->Get(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS())
                        : 0;
  return asked + this->EffectiveGhostLevels();
}

namespace {

// The extent of `whole` that the piece `request` asks for owns without ghost layers (its
// UPDATE_PIECE_NUMBER of UPDATE_NUMBER_OF_PIECES), as the pipeline splits a whole extent
// (vtkExtentTranslator, the split mode the request gives, else blocks).
bool ownExtent(vtkInformation* request, const int whole[6], int ext[6]) {
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!request->Has(SDDP::UPDATE_NUMBER_OF_PIECES())) return false;
  const int piece = request->Get(SDDP::UPDATE_PIECE_NUMBER());
  const int pieces = request->Get(SDDP::UPDATE_NUMBER_OF_PIECES());
  const int mode = request->Has(vtkExtentTranslator::UPDATE_SPLIT_MODE())
                       ? request->Get(vtkExtentTranslator::UPDATE_SPLIT_MODE())
                       : vtkExtentTranslator::BLOCK_MODE;
  vtkNew<vtkExtentTranslator> translator;
  int w[6];
  std::copy(whole, whole + 6, w);
  return translator->PieceToExtentThreadSafe(piece, pieces, 0, w, ext, mode, 0) != 0;
}

// `own` grown by `layers` samples on every side, within `whole`: the extent a piece asks its
// image source for.
void growExtent(const int own[6], const int whole[6], int layers, int out[6]) {
  for (int a = 0; a < 3; ++a) {
    out[2 * a] = std::max(whole[2 * a], own[2 * a] - layers);
    out[2 * a + 1] = std::min(whole[2 * a + 1], own[2 * a + 1] + layers);
  }
}

std::string extentText(const int e[6]) {
  std::ostringstream out;
  out << "[" << e[0] << ".." << e[1] << ", " << e[2] << ".." << e[3] << ", " << e[4] << ".." << e[5]
      << "]";
  return out.str();
}

// The piece count the output was asked for (1 when none).
int requestedPieces(vtkInformation* out) {
  using SDDP = vtkStreamingDemandDrivenPipeline;
  return out->Has(SDDP::UPDATE_NUMBER_OF_PIECES()) ? out->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) : 1;
}

// The input's time steps (empty when it advertises none).
std::vector<double> inputTimeSteps(vtkInformation* in) {
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!in->Has(SDDP::TIME_STEPS())) return {};
  const double* t = in->Get(SDDP::TIME_STEPS());
  return std::vector<double>(t, t + in->Length(SDDP::TIME_STEPS()));
}

// The time an output request asks for, clamped to [first, last]; the first without one.
double requestedTime(vtkInformation* out, double first, double last) {
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!out->Has(SDDP::UPDATE_TIME_STEP())) return first;
  return std::clamp(out->Get(SDDP::UPDATE_TIME_STEP()), first, last);
}

vtkMTimeType pipelineTimeOf(vtkAlgorithm* algorithm) {
  auto* executive = vtkDemandDrivenPipeline::SafeDownCast(algorithm->GetExecutive());
  return executive ? executive->GetPipelineMTime() : algorithm->GetMTime();
}

// The steps of the encoder's input, each read when the encoder asks for it: the input's
// producer is updated at that step's time (as UpdateTimeStep does), so that one step is held at
// a time.
class PipelineSeries final : public mfadvr::VolumeSeries {
 public:
  PipelineSeries(vtkAlgorithm* producer, int port, std::vector<double> steps, std::string field,
                 double* loaded)
      : producer_(producer),
        port_(port),
        steps_(std::move(steps)),
        field_(std::move(field)),
        loaded_(loaded) {}
  int size() const override { return static_cast<int>(steps_.size()); }
  double time(int s) const override { return steps_[static_cast<size_t>(s)]; }
  std::string stepName(int s) const override {
    std::ostringstream name;
    name << "time step " << s << " (t = " << time(s) << ")";
    return name.str();
  }
  std::string source() const override {
    return std::string("VTK ") + producer_->GetClassName() + " time steps";
  }
  mfadvr::StructuredGrid load(int s) const override {
    using SDDP = vtkStreamingDemandDrivenPipeline;
    auto* executive = SDDP::SafeDownCast(producer_->GetExecutive());
    if (!executive) throw mfadvr::Error("the input's producer has no streaming executive");
    producer_->GetOutputInformation(port_)->Set(SDDP::UPDATE_TIME_STEP(), time(s));
    if (!executive->Update(port_))
      throw mfadvr::Error("the input failed to produce " + stepName(s));
    *loaded_ = time(s);
    auto* image = vtkImageData::SafeDownCast(producer_->GetOutputDataObject(port_));
    if (!image)
      throw mfadvr::Error(
          "TimeSeries encodes image data; the input's " + stepName(s) + " is " +
          (producer_->GetOutputDataObject(port_)
               ? std::string("a ") + producer_->GetOutputDataObject(port_)->GetClassName()
               : std::string("empty")));
    return mfadvr::gridFromVtkImage(image, field_, source() + ", " + stepName(s));
  }

 private:
  vtkAlgorithm* producer_;
  int port_;
  std::vector<double> steps_;
  std::string field_;
  double* loaded_;
};

}  // namespace

int vtkMFAEncoder::RequestUpdateExtent(vtkInformation*, vtkInformationVector** inInfo,
                                       vtkInformationVector* outInfo) {
  vtkInformation* out = outInfo->GetInformationObject(0);
  vtkInformation* in = inInfo[0]->GetInformationObject(0);
  using SDDP = vtkStreamingDemandDrivenPipeline;
  const int pieces = requestedPieces(out);
  // A 4-D model that still serves: the input stays at the step it holds (no step is read again
  // for an instant the model gives).
  if (this->TimeSeries && this->Series && this->Series->model &&
      this->Series->pipelineTime == pipelineTimeOf(this) &&
      this->Series->steps == inputTimeSteps(in)) {
    in->Set(SDDP::UPDATE_TIME_STEP(), this->Series->loadedTime);
  }
  if (pieces > 1) {
    const int layers = this->PieceLayers(out);
    int ext[6], whole[6];
    if (in->Has(SDDP::WHOLE_EXTENT()) &&
        (in->Get(SDDP::WHOLE_EXTENT(), whole), ownExtent(out, whole, ext))) {
      // An image: its piece grown by the layers, asked for as one extent (as image filters ask
      // for the neighbourhoods of their kernels) and not as a piece with ghost levels, for which
      // the pipeline would add a ghost-mark array (1 byte per point) to the input that the fit
      // does not use (the carrier marks its own ghost cells). One piece of that extent, so
      // that a reader does not split it again.
      int asked[6];
      growExtent(ext, whole, layers, asked);
      in->Set(SDDP::UPDATE_EXTENT(), asked, 6);
      in->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
      in->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
      in->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    } else {
      in->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), layers);
    }
  }
  return 1;
}

namespace {

// The samples of `source` (a point array of `image`) on a carrier's grid: the array itself
// when the grid is the image's, a copy of the grid's extent when it lies within the image's,
// null when the grid is not the image's (the carrier then evaluates the model).
vtkSmartPointer<vtkDataArray> inputValuesOn(vtkImageData* image, vtkDataArray* source,
                                            const mfadvr::vtkglue::CarrierGrid& g) {
  const int* ext = image->GetExtent();
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  bool same = true;
  for (int a = 0; a < 3; ++a) {
    const double tolerance = 1e-6 * std::abs(spacing[a]);
    if (std::abs(g.spacing[a] - spacing[a]) > tolerance ||
        std::abs(g.origin[a] - origin[a]) > tolerance || g.extent[2 * a] < ext[2 * a] ||
        g.extent[2 * a + 1] > ext[2 * a + 1])
      return nullptr;
    same = same && g.extent[2 * a] == ext[2 * a] && g.extent[2 * a + 1] == ext[2 * a + 1];
  }
  if (same) return source;
  vtkSmartPointer<vtkDataArray> part;
  part.TakeReference(source->NewInstance());
  part->SetName(source->GetName());
  part->SetNumberOfComponents(source->GetNumberOfComponents());
  const vtkIdType nx = g.extent[1] - g.extent[0] + 1;
  part->SetNumberOfTuples(nx * (g.extent[3] - g.extent[2] + 1) * (g.extent[5] - g.extent[4] + 1));
  const vtkIdType inX = ext[1] - ext[0] + 1, inY = ext[3] - ext[2] + 1;
  vtkIdType to = 0;
  for (int k = g.extent[4]; k <= g.extent[5]; ++k)
    for (int j = g.extent[2]; j <= g.extent[3]; ++j, to += nx) {
      const vtkIdType from =
          (g.extent[0] - ext[0]) + inX * ((j - ext[2]) + inY * vtkIdType(k - ext[4]));
      part->InsertTuples(to, nx, from, source);
    }
  return part;
}

}  // namespace

int vtkMFAEncoder::RequestData(vtkInformation*, vtkInformationVector** inInfo,
                               vtkInformationVector* outInfo) {
  vtkDataSet* input = vtkDataSet::GetData(inInfo[0]);
  vtkDataObject* output = outInfo->GetInformationObject(0)->Get(vtkDataObject::DATA_OBJECT());
  output->Initialize();
  if (!input) {
    vtkErrorMacro("no input data set");
    return 0;
  }

  // A named array from SetInputArrayToProcess; an attribute type (the default) means the
  // active scalars, which is what an empty field name asks the conversions for.
  std::string field;
  if (vtkInformation* array = this->GetInputArrayInformation(0)) {
    if (array->Has(vtkDataObject::FIELD_NAME())) {
      field = array->Get(vtkDataObject::FIELD_NAME());
    }
  }

  mfadvr::EncodeOptions options;
  options.degree = {this->Degree, this->Degree, this->Degree};
  for (int a = 0; a < 3; ++a) {
    options.controlCounts[a] = this->NumberOfControlPoints[a];
  }
  options.smoothing = this->Smoothing;
  if (this->KnotDensity >= 0.0) {
    options.knotDensity = this->KnotDensity;
  }
  if (this->CellSamples != -1) {
    options.cellSamples = this->CellSamples;
  }
  if (this->MaxError > 0.0) {
    mfadvr::AdaptiveOptions adaptive;
    adaptive.maxRelativeError = this->MaxError;
    for (int a = 0; a < 3; ++a) {
      adaptive.maxControlCounts[a] = this->MaxNumberOfControlPoints[a];
    }
    adaptive.maxRounds = this->MaxRounds;
    options.adaptive = adaptive;
  }
  options.mask.enabled = this->DomainMask;
  options.mask.longestAxisNodes = this->MaskResolution;
  options.progress = [this](double fraction, const std::string&) {
    this->UpdateProgress(fraction);
  };

  if (this->TimeSeries) {
    if (inputTimeSteps(inInfo[0]->GetInformationObject(0)).size() >= 2) {
      return this->RequestSeriesData(inInfo, outInfo, field, options);
    }
    vtkWarningMacro(
        "TimeSeries: the input advertises fewer than two time steps; the data set "
        "is fitted as it is");
  }

  const std::string source = std::string("VTK ") + input->GetClassName();
  vtkInformation* in = inInfo[0]->GetInformationObject(0);
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* request = outInfo->GetInformationObject(0);  // the piece asked for
  const int pieces = requestedPieces(request);
  if (input->GetNumberOfPoints() == 0 && pieces > 1) {
    return 1;  // this piece holds no data: nothing to fit or render
  }
  try {
    mfadvr::FitReport report;
    mfadvr::Model model;
    double region[6];
    bool hasRegion = false;
    int reach[6];  // the carrier's extent with the piece's ghost layers, where it keeps them
    bool hasReach = false;
    int firstIndex[3] = {0, 0, 0};  // of the carrier's first point, in the input's index space
    bool fromImage = false;
    mfadvr::vtkglue::CarrierValues values;  // the input's samples for the carrier, if asked
    if (auto* image = vtkImageData::SafeDownCast(input)) {
      // The fit reads a plain scalar array where it is, plane by plane: no float32 copy of the
      // image (4 bytes per sample) at the encoder's peak.
      mfadvr::GridSamples inPlace;
      mfadvr::StructuredGrid grid = mfadvr::gridFromVtkImage(image, field, source, &inPlace);
      const mfadvr::GridSamples fitSamples = inPlace.empty() ? mfadvr::GridSamples(grid) : inPlace;
      fromImage = true;
      if (this->PassInputValues && this->OutputImageData) {
        vtkDataArray* samples = grid.fieldAssociation == "point data"
                                    ? image->GetPointData()->GetArray(grid.fieldName.c_str())
                                    : nullptr;
        if (samples && samples->GetNumberOfComponents() == 1) {
          values = [image, samples](const mfadvr::vtkglue::CarrierGrid& g) {
            return inputValuesOn(image, samples, g);
          };
        } else {
          vtkWarningMacro(
              "PassInputValues: the field is not a point array of the image; the "
              "output carries the model's values");
        }
      }
      // Smoothing is the scattered fit's regularization; images have their own weight.
      options.smoothing = this->ImageSmoothing;
      const int* dataExtent = image->GetExtent();
      for (int a = 0; a < 3; ++a) firstIndex[a] = dataExtent[2 * a];
      int own[6], whole[6];
      if (pieces > 1 && in->Has(SDDP::WHOLE_EXTENT()) &&
          (in->Get(SDDP::WHOLE_EXTENT(), whole), ownExtent(request, whole, own))) {
        // One piece with its ghost layers: fitted at the whole image's control-point density,
        // rendered in its own extent only.
        int ext[6], asked[6];
        image->GetExtent(ext);
        growExtent(own, whole, this->PieceLayers(request), asked);
        // A source that serves its own piece whatever it is asked for (RequestUpdateExtent
        // asked for one extent): fit what it holds of this piece, or refuse when that is not
        // a grid of the piece.
        bool holdsAsked = true;
        for (int a = 0; a < 3; ++a) {
          holdsAsked =
              holdsAsked && ext[2 * a] <= asked[2 * a] && ext[2 * a + 1] >= asked[2 * a + 1];
          if (std::min(ext[2 * a + 1], own[2 * a + 1]) - std::max(ext[2 * a], own[2 * a]) < 1)
            throw mfadvr::Error(
                "piece " + std::to_string(request->Get(SDDP::UPDATE_PIECE_NUMBER())) + " of " +
                std::to_string(pieces) + " was given the extent " + extentText(ext) +
                ", which holds no grid of its own extent " + extentText(own) +
                " (the input was asked for " + extentText(asked) + ")");
        }
        if (!holdsAsked) {
          vtkWarningMacro(<< "piece " << request->Get(SDDP::UPDATE_PIECE_NUMBER()) << " of "
                          << pieces << " asked its input for the extent " << extentText(asked)
                          << " and was given " << extentText(ext)
                          << ": it is fitted with the samples it was given (fewer ghost layers "
                             "or part of its own extent)");
        }
        const mfadvr::Index3 wholeDims{whole[1] - whole[0] + 1, whole[3] - whole[2] + 1,
                                       whole[5] - whole[4] + 1};
        const auto [lo, hi] = fitSamples.range();
        model =
            mfadvr::encodeStructuredPiece(grid, fitSamples, wholeDims, options, lo, hi, &report);
        for (int a = 0; a < 3; ++a) {
          own[2 * a] = std::max(own[2 * a], ext[2 * a]);
          own[2 * a + 1] = std::min(own[2 * a + 1], ext[2 * a + 1]);
          region[2 * a] = image->GetOrigin()[a] + own[2 * a] * image->GetSpacing()[a];
          region[2 * a + 1] = image->GetOrigin()[a] + own[2 * a + 1] * image->GetSpacing()[a];
        }
        hasRegion = true;
        for (int a = 0; a < 3; ++a) firstIndex[a] = own[2 * a];
        // Passed values: the carrier keeps the piece's ghost layers (as ghost cells) so that
        // its scalars are the input's array itself, not a copy of the piece's own extent.
        if (values) {
          std::copy(ext, ext + 6, reach);
          hasReach = true;
        }
      } else {
        model = mfadvr::encodeStructured(grid, fitSamples, options, &report);
      }
    } else {
      options.autoSmoothing = this->AutoSmoothing;
      model = mfadvr::encodeScattered(mfadvr::scatteredFromVtkDataSet(input, field, source),
                                      options, &report);
    }
    this->TakeFit(report, model, options.adaptive.has_value());
    this->SetOutputModel(outInfo, std::make_shared<const mfadvr::Model>(std::move(model)),
                         hasRegion ? region : nullptr, fromImage ? firstIndex : nullptr, values,
                         hasReach ? reach : nullptr);
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

int vtkMFAEncoder::RequestSeriesData(vtkInformationVector** inInfo, vtkInformationVector* outInfo,
                                     const std::string& field,
                                     const mfadvr::EncodeOptions& properties) {
  vtkInformation* in = inInfo[0]->GetInformationObject(0);
  vtkInformation* request = outInfo->GetInformationObject(0);
  const std::vector<double> steps = inputTimeSteps(in);
  try {
    if (requestedPieces(request) > 1) {
      throw mfadvr::Error(
          "TimeSeries fits the whole series in one process; this pipeline asks for " +
          std::to_string(requestedPieces(request)) +
          " pieces (encode the series with `mfadvr encode` and open the model with the MFA "
          "reader, which serves every rank)");
    }
    const vtkMTimeType pipelineTime = pipelineTimeOf(this);
    if (!this->Series || !this->Series->model || this->Series->pipelineTime != pipelineTime ||
        this->Series->steps != steps || this->Series->field != field) {
      int port = 0;
      vtkAlgorithm* producer = this->GetInputAlgorithm(0, 0, port);
      if (!producer) throw mfadvr::Error("TimeSeries needs an input connection, not input data");
      auto fit = std::make_shared<SeriesFit>();
      fit->pipelineTime = pipelineTime;
      fit->steps = steps;
      fit->field = field;
      this->Series.reset();
      const PipelineSeries series(producer, port, steps, field, &fit->loadedTime);
      mfadvr::EncodeOptions options = properties;
      options.smoothing = this->ImageSmoothing;  // image data
      mfadvr::TimeSeriesOptions time;
      time.degree = this->TimeDegree;
      time.controlCount = this->TimeControlPoints;
      time.zfpForIntegerSamples = true;  // as `mfadvr encode`
      mfadvr::FitReport report;
      fit->model = std::make_shared<const mfadvr::TimeVaryingModel>(
          mfadvr::encodeTimeSeries(series, options, time, &report));
      this->TakeFit(report, *fit->model, options.adaptive.has_value());
      this->Series = fit;
    }
    SeriesFit& fit = *this->Series;
    const mfadvr::TimeAxis& axis = fit.model->timeAxis();
    const double t = requestedTime(request, axis.begin, axis.end);
    if (!fit.instant || fit.instantTime != t) {
      fit.instant = std::make_shared<const mfadvr::Model>(fit.model->at(t));
      fit.instantTime = t;
    }
    this->SetOutputModel(outInfo, fit.instant);
    vtkDataObject* output = request->Get(vtkDataObject::DATA_OBJECT());
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

template <class M>
void vtkMFAEncoder::TakeFit(const mfadvr::FitReport& report, const M& model, bool adaptive) {
  const double range = report.valueMax > report.valueMin ? report.valueMax - report.valueMin : 1.0;
  this->LastMaxRelativeError = report.maxError / range;
  this->LastRMSRelativeError = report.rmsError / range;
  this->LastFitSeconds = report.seconds;
  this->LastSmoothing = report.smoothing;
  if (adaptive && !report.reachedTarget) {
    vtkWarningMacro("the error bound " << this->MaxError << " was not reached ("
                                       << report.stopReason << "); the best model has max error "
                                       << this->LastMaxRelativeError);
  }
  if (this->ModelFileName && *this->ModelFileName) {
    mfadvr::saveModel(model, this->ModelFileName);
  }
}
