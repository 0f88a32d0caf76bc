// The pipeline classes of the VTK module: vtkMFAReader, vtkMFAEncoder (image data, meshes,
// point clouds, array selection, adaptive fits) and vtkMFAModelData's queries. Errors are
// reported through VTK's error events and leave the output empty.
#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataSetTriangleFilter.h>
#include <vtkDoubleArray.h>
#include <vtkExtentTranslator.h>
#include <vtkFieldData.h>
#include <vtkImageAlgorithm.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRTAnalyticSource.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTrivialProducer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "TestSupport.h"
#include "VtkErrorLog.h"
#include "VtkSceneFixture.h"
#include "core/analytic/BuiltinSeries.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/ScatteredSmoothingChoice.h"
#include "core/encode/StructuredEncoder.h"
#include "core/encode/TimeSeriesEncoder.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ControlCoding.h"
#include "core/model/ModelFile.h"
#include "vtkMFAEncoder.h"
#include "vtkMFAReader.h"

namespace mfadvr::test {
namespace {

StructuredGrid mlGrid(std::int64_t n) {
  return sampleBuiltin(*makeBuiltin("marschner-lobb"), {n, n, n});
}

TEST(MFAReader, ReadsAModelFile) {
  const auto path = scratchDir() / "ml.mfa";
  saveModel(*marschnerLobbModel(), path);
  ASSERT_TRUE(vtkMFAReader::CanReadFile(path.c_str()));
  vtkNew<vtkMFAReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkMFAModelData* out = reader->GetOutput();
  ASSERT_TRUE(out->HasModel());
  double b[6], r[2], g[3];
  out->GetBounds(b);
  out->GetScalarRange(r);
  EXPECT_DOUBLE_EQ(b[0], -1.0);
  EXPECT_DOUBLE_EQ(b[5], 1.0);
  EXPECT_DOUBLE_EQ(r[0], marschnerLobbModel()->valueMin());
  const Vec3d p(0.1, -0.3, 0.2);
  EXPECT_FLOAT_EQ(out->EvaluateValue(p[0], p[1], p[2]), marschnerLobbModel()->value(p));
  out->EvaluateGradient(p[0], p[1], p[2], g);
  EXPECT_FLOAT_EQ(float(g[1]), marschnerLobbModel()->valueGradient(p).gradient[1]);
  EXPECT_TRUE(out->IsInside(0, 0, 0));
  EXPECT_FALSE(out->IsInside(2, 0, 0));
  EXPECT_FALSE(out->HasDomainMask());
}

// A time-varying model: its steps and range in the pipeline's time keys, and the instant asked
// for (between steps too) in the output, as the model and as the image that carries it.
TEST(MFAReader, GivesEveryInstantOfATimeVaryingModel) {
  const auto path = scratchDir() / "blobs.mfa";
  const TimeVaryingModel series =
      encodeTimeSeries(BuiltinVolumeSeries("builtin:orbiting-blobs:12x12x12x5"), EncodeOptions(),
                       TimeSeriesOptions());
  saveModel(series, path);
  for (const bool image : {false, true}) {
    vtkNew<vtkMFAReader> reader;
    reader->SetFileName(path.c_str());
    reader->SetOutputImageData(image);
    reader->UpdateInformation();
    vtkInformation* info = reader->GetOutputInformation(0);
    ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
    ASSERT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 5);
    EXPECT_DOUBLE_EQ(info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[1], 0.25);
    const double* range = info->Get(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    EXPECT_DOUBLE_EQ(range[0], 0.0);
    EXPECT_DOUBLE_EQ(range[1], 1.0);
    for (const double t : {0.0, 0.4, 0.75}) {
      reader->UpdateTimeStep(t);
      vtkDataObject* out = reader->GetOutputDataObject(0);
      EXPECT_DOUBLE_EQ(out->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), t);
      const Vec3d p(0.3, -0.2, 0.1);
      const double expected = series.at(t).value(p);
      if (image) {
        // The carrier's point scalars: the instant on the data's grid.
        auto* carrier = vtkImageData::SafeDownCast(out);
        ASSERT_NE(carrier, nullptr);
        const Model instant = series.at(t);
        vtkDataArray* values = carrier->GetPointData()->GetScalars();
        ASSERT_NE(values, nullptr);
        for (vtkIdType i = 0; i < values->GetNumberOfTuples(); i += 97) {
          double x[3];
          carrier->GetPoint(i, x);
          EXPECT_NEAR(values->GetTuple1(i), instant.value(Vec3d(x[0], x[1], x[2])), 1e-5)
              << "t = " << t;
        }
      } else {
        EXPECT_FLOAT_EQ(vtkMFAModelData::SafeDownCast(out)->EvaluateValue(p[0], p[1], p[2]),
                        expected)
            << "t = " << t;
      }
    }
  }
  // A 3-D model advertises no time.
  const auto plain = scratchDir() / "ml.mfa";
  saveModel(*marschnerLobbModel(), plain);
  vtkNew<vtkMFAReader> reader;
  reader->SetFileName(plain.c_str());
  reader->UpdateInformation();
  EXPECT_FALSE(
      reader->GetOutputInformation(0)->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
}

TEST(MFAReader, ReportsBadFilesWithoutOutput) {
  const auto dir = scratchDir();
  const auto garbage = dir / "garbage.mfa";
  std::ofstream(garbage) << "not a model at all";
  const auto truncated = dir / "truncated.mfa";
  const std::string bytes = serializeModel(*marschnerLobbModel());
  std::ofstream(truncated, std::ios::binary).write(bytes.data(), bytes.size() / 2);
  for (const auto& [path, expected] : std::vector<std::pair<std::string, std::string>>{
           {garbage.string(), "magic"},
           {truncated.string(), "truncated"},
           {(dir / "missing.mfa").string(), "missing"}}) {
    vtkNew<vtkMFAReader> reader;
    ErrorLog log(reader);
    reader->SetFileName(path.c_str());
    reader->Update();
    EXPECT_FALSE(reader->GetOutput()->HasModel()) << path;
    EXPECT_FALSE(log.text.empty()) << path;
    EXPECT_FALSE(vtkMFAReader::CanReadFile(path.c_str()) && expected != "truncated") << path;
  }
}

// The reader checks what rendering a model will hold before it reads it (each MPI rank its own
// blocks), against MFADVR_MEMORY_LIMIT here.
TEST(MFAReader, RefusesModelsTheMemoryCannotHold) {
  const auto dir = scratchDir();
  const auto single = dir / "ml.mfa", blocks = dir / "ml-blocks.mfa";
  saveModel(*marschnerLobbModel(), single);
  saveBlockModels(encodeStructuredBlocks(mlGrid(33), {2, 1, 1}, -1, EncodeOptions{}), {2, 1, 1},
                  blocks);
  struct Limit {
    explicit Limit(const char* bytes) { setenv("MFADVR_MEMORY_LIMIT", bytes, 1); }
    ~Limit() { unsetenv("MFADVR_MEMORY_LIMIT"); }
  };
  const auto read = [](const std::filesystem::path& path, bool image, int piece, int pieces) {
    vtkNew<vtkMFAReader> reader;
    ErrorLog log(reader);
    reader->SetFileName(path.c_str());
    reader->SetOutputImageData(image);
    reader->UpdatePiece(piece, pieces, 0);
    const bool model = image ? vtkImageData::SafeDownCast(reader->GetOutputDataObject(0))
                                       ->GetFieldData()
                                       ->GetNumberOfArrays() > 0
                             : reader->GetOutput()->HasModel();
    return std::make_pair(model, log.text);
  };
  {
    const Limit tight("1K");
    for (bool image : {false, true}) {
      const auto [model, errors] = read(single, image, 0, 1);
      EXPECT_FALSE(model);
      EXPECT_NE(errors.find("reading " + single.string()), std::string::npos) << errors;
      EXPECT_NE(errors.find("1 KB are available"), std::string::npos) << errors;
    }
    const auto [model, errors] = read(blocks, true, 1, 2);
    EXPECT_FALSE(model);
    EXPECT_NE(errors.find("blocks 1..1 of " + blocks.string() + " in piece 1 of 2"),
              std::string::npos)
        << errors;
  }
  const Limit roomy("1G");
  EXPECT_TRUE(read(single, false, 0, 1).first);
  EXPECT_TRUE(read(blocks, true, 1, 2).first);
}

// zfp-coded blocks, as `mfadvr encode` writes an integer scan, read piece by piece; a block whose
// bytes are damaged is an error of the reader for the piece that reads it, never a crash.
TEST(MFAReader, ReadsZfpBlocksAndReportsADamagedOne) {
  const auto dir = scratchDir();
  const auto path = dir / "zfp-blocks.mfa";
  EncodeOptions options;
  options.coding.coder = ControlCoder::kZfp;
  const std::vector<ModelBlock> blocks = encodeStructuredBlocks(mlGrid(33), {2, 1, 1}, -1, options);
  ASSERT_EQ(blocks.size(), 2u);
  saveBlockModels(blocks, {2, 1, 1}, path);
  const auto read = [](const std::filesystem::path& file, int piece) {
    vtkNew<vtkMFAReader> reader;
    ErrorLog log(reader);
    reader->SetFileName(file.string().c_str());
    reader->SetOutputImageData(true);
    reader->UpdatePiece(piece, 2, 0);
    auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
    return std::make_pair(image->GetFieldData()->GetNumberOfArrays() > 0, log.text);
  };
  for (int piece : {0, 1}) {
    const auto [model, errors] = read(path, piece);
    EXPECT_TRUE(model) << "piece " << piece << ": " << errors;
    EXPECT_TRUE(errors.empty()) << errors;
  }
  // The last block's bytes, near the end of the file, damaged.
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto damaged = dir / "damaged.mfa";
  for (size_t i = bytes.size() - 200; i < bytes.size() - 100; ++i)
    bytes[i] = static_cast<char>(~bytes[i]);
  std::ofstream(damaged, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  const auto [model, errors] = read(damaged, 1);
  EXPECT_FALSE(model);
  EXPECT_NE(errors.find(damaged.string()), std::string::npos) << errors;
}

// An image source with time steps (as a file series is in ParaView): the builtin series' step
// at the time asked for, counting how often it runs.
class StepSource : public vtkImageAlgorithm {
 public:
  static StepSource* New();
  vtkTypeMacro(StepSource, vtkImageAlgorithm);
  std::shared_ptr<BuiltinVolumeSeries> series;
  int executions = 0;

 protected:
  StepSource() { this->SetNumberOfInputPorts(0); }
  int RequestInformation(vtkInformation*, vtkInformationVector**,
                         vtkInformationVector* outInfo) override {
    vtkInformation* info = outInfo->GetInformationObject(0);
    std::vector<double> steps;
    for (int s = 0; s < series->size(); ++s) steps.push_back(series->time(s));
    info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), steps.data(),
              static_cast<int>(steps.size()));
    const double range[2] = {steps.front(), steps.back()};
    info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
    const Index3 d = series->dims();
    const int extent[6] = {0, int(d[0]) - 1, 0, int(d[1]) - 1, 0, int(d[2]) - 1};
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outInfo) override {
    ++executions;
    vtkInformation* info = outInfo->GetInformationObject(0);
    const double t = info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    vtkImageData* out = vtkImageData::GetData(info);
    out->ShallowCopy(imageOf(series->sampleAt(t)));
    out->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
    return 1;
  }
};
vtkStandardNewMacro(StepSource);

TEST(MFAEncoder, FitsEveryTimeStepIntoOneModelAndGivesAnyInstant) {
  auto series = std::make_shared<BuiltinVolumeSeries>("builtin:orbiting-blobs:12x12x12x5");
  EncodeOptions options;
  options.controlCounts = {10, 10, 10};
  const TimeVaryingModel direct = encodeTimeSeries(*series, options, TimeSeriesOptions());
  vtkNew<StepSource> source;
  source->series = series;
  const auto path = scratchDir() / "encoded-series.mfa";
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputConnection(source->GetOutputPort());
  encoder->SetNumberOfControlPoints(10, 10, 10);
  encoder->TimeSeriesOn();
  encoder->SetModelFileName(path.c_str());
  encoder->UpdateInformation();
  vtkInformation* info = encoder->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  EXPECT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 5);
  int afterFit = 0;
  for (const double t : {0.4, 0.75, 0.0, 0.4}) {
    encoder->UpdateTimeStep(t);
    vtkDataObject* out = encoder->GetOutputDataObject(0);
    EXPECT_DOUBLE_EQ(out->GetInformation()->Get(vtkDataObject::DATA_TIME_STEP()), t);
    auto* model = vtkMFAModelData::SafeDownCast(out);
    ASSERT_NE(model, nullptr);
    ASSERT_TRUE(model->HasModel());
    for (const Vec3d& p : {Vec3d(0.3, -0.2, 0.1), Vec3d(-0.5, 0.4, 0.0)})
      EXPECT_NEAR(model->EvaluateValue(p[0], p[1], p[2]), direct.at(t).value(p), 1e-5)
          << "t = " << t;
    // Every step read for the fit (twice: the fit and its errors), none after it.
    if (afterFit == 0) afterFit = source->executions;
    EXPECT_EQ(source->executions, afterFit) << "t = " << t;
  }
  EXPECT_GE(afterFit, 10);
  // The file holds the 4-D model.
  const TimeVaryingModel saved = loadTimeVaryingModel(path);
  ASSERT_TRUE(saved.hasTime());
  EXPECT_EQ(saved.timeAxis().steps.size(), 5u);
  EXPECT_NEAR(saved.at(0.6).value(Vec3d(0.1, 0.1, 0.1)), direct.at(0.6).value(Vec3d(0.1, 0.1, 0.1)),
              1e-5);
  // A property changed: fitted again.
  encoder->SetTimeDegree(2);
  encoder->UpdateTimeStep(0.4);
  EXPECT_GT(source->executions, afterFit);
  // An input without time steps is fitted as it is, with a warning.
  vtkNew<vtkMFAEncoder> plain;
  plain->SetInputData(imageOf(mlGrid(9)));
  plain->TimeSeriesOn();
  ErrorLog warnings(plain, vtkCommand::WarningEvent);
  plain->Update();
  EXPECT_TRUE(plain->GetOutput()->HasModel());
  EXPECT_NE(warnings.text.find("fewer than two time steps"), std::string::npos) << warnings.text;
}

TEST(MFAEncoder, FitsImageDataWithTheGivenControlCounts) {
  const StructuredGrid grid = mlGrid(21);
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputData(imageOf(grid));
  encoder->SetNumberOfControlPoints(12, 14, 16);
  encoder->SetDegree(2);
  encoder->Update();
  vtkMFAModelData* out = encoder->GetOutput();
  ASSERT_TRUE(out->HasModel());
  int counts[3], degree[3];
  out->GetNumberOfControlPoints(counts);
  out->GetDegree(degree);
  EXPECT_EQ(counts[0], 12);
  EXPECT_EQ(counts[2], 16);
  EXPECT_EQ(degree[1], 2);
  EXPECT_STREQ(out->GetFieldName(), "value");
  // The reported error is the model's error at every sample.
  double worst = 0.0;
  for (std::int64_t k = 0; k < 21; k += 2)
    for (std::int64_t j = 0; j < 21; j += 2)
      for (std::int64_t i = 0; i < 21; i += 2) {
        const Vec3d p = grid.position(i, j, k);
        const double v = grid.values[static_cast<size_t>(i + 21 * (j + 21 * k))];
        worst = std::max(worst, std::abs(out->EvaluateValue(p[0], p[1], p[2]) - v));
      }
  double r[2];
  out->GetScalarRange(r);
  EXPECT_LE(worst / (r[1] - r[0]), encoder->GetLastMaxRelativeError() + 1e-6);
  EXPECT_GT(encoder->GetLastMaxRelativeError(), 0.0);
}

// A uint8 image is fitted from its own array, plane by plane (no float32 copy of it): the model
// is the one of the float samples, bit for bit, for the whole image and for a piece of it.
TEST(MFAEncoder, FitsAByteImageAsItsFloatSamples) {
  StructuredGrid grid = mlGrid(19);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(19, 19, 19);
  image->SetOrigin(grid.origin.data());
  image->SetSpacing(grid.spacing.data());
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetName("density");
  bytes->SetNumberOfTuples(vtkIdType(grid.values.size()));
  for (size_t i = 0; i < grid.values.size(); ++i) {
    bytes->SetValue(vtkIdType(i), static_cast<unsigned char>(std::lround(grid.values[i] * 250.0)));
    grid.values[i] = bytes->GetValue(vtkIdType(i));
  }
  image->GetPointData()->SetScalars(bytes);
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(image);
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputConnection(producer->GetOutputPort());
  encoder->SetNumberOfControlPoints(14, 15, 16);
  encoder->Update();
  ASSERT_TRUE(encoder->GetOutput()->HasModel());
  StructuredFitOptions fit;
  fit.controlCounts = {14, 15, 16};
  const Model expected = fitStructured(grid, fit);
  const auto same = [](const Model& a, const Model& b) {
    const auto pa = a.spline().controlPoints(), pb = b.spline().controlPoints();
    return std::equal(pa.begin(), pa.end(), pb.begin(), pb.end());
  };
  const Model& whole = *encoder->GetOutput()->GetModel();
  EXPECT_TRUE(same(whole, expected));
  EXPECT_EQ(whole.provenance().sampleType, "uint8");
  EXPECT_EQ(whole.provenance().maxError, expected.provenance().maxError);
  // Piece 1 of 2: the trivial producer gives the whole image, which the encoder fits as the
  // piece's samples with their ghost layers (the piece fit, at the whole image's density).
  encoder->UpdatePiece(1, 2, 0);
  ASSERT_TRUE(encoder->GetOutput()->HasModel());
  const auto [lo, hi] = std::minmax_element(grid.values.begin(), grid.values.end());
  EncodeOptions options;
  options.controlCounts = {14, 15, 16};
  EXPECT_TRUE(same(*encoder->GetOutput()->GetModel(),
                   encodeStructuredPiece(grid, grid.dims, options, *lo, *hi)));
}

// Under MPI a piece of an image asks its source for its own extent grown by the ghost layers, as
// one extent: the source reads just that, and adds no ghost-mark array the fit would not use.
TEST(MFAEncoder, AsksAnImageSourceForItsPieceWithGhostLayers) {
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(0, 30, 0, 30, 0, 30);
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputConnection(source->GetOutputPort());
  encoder->SetDegree(2);
  encoder->SetGhostLevels(3);
  for (int piece = 0; piece < 2; ++piece) {
    SCOPED_TRACE("piece " + std::to_string(piece));
    encoder->UpdatePiece(piece, 2, 0);
    ASSERT_TRUE(encoder->GetOutput()->HasModel());
    vtkImageData* read = source->GetOutput();
    int ext[6];
    read->GetExtent(ext);
    // The pipeline's block split of 31^3 points in two halves one axis at point 15; the piece
    // reaches 3 layers past it.
    int across = -1;
    for (int a = 0; a < 3; ++a)
      if (ext[2 * a] != 0 || ext[2 * a + 1] != 30) across = a;
    ASSERT_GE(across, 0) << "the source was asked for the whole extent";
    EXPECT_EQ(piece == 0 ? ext[2 * across + 1] : ext[2 * across], piece == 0 ? 18 : 12);
    EXPECT_EQ(read->GetPointData()->GetArray("vtkGhostType"), nullptr);
    EXPECT_FALSE(read->HasAnyGhostPoints());
    EXPECT_EQ(encoder->GetOutput()->GetModel()->provenance().sampleDims[across], 19);
  }
}

// A source that serves the same extent whatever it is asked for: a piece given fewer ghost
// layers than it asked for is fitted with what it was given, and warns; a piece given none of
// its own extent is refused.
TEST(MFAEncoder, PiecesServedAnotherExtentWarnOrFail) {
  vtkNew<vtkRTAnalyticSource> wave;
  wave->SetWholeExtent(0, 20, 0, 20, 0, 20);
  wave->Update();
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(wave->GetOutput());
  producer->SetWholeExtent(0, 20, 0, 20, 0, 40);  // split in z at 20 into two pieces
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputConnection(producer->GetOutputPort());
  encoder->SetDegree(2);
  encoder->SetGhostLevels(3);
  ErrorLog warnings(encoder, vtkCommand::WarningEvent), errors(encoder);
  encoder->UpdatePiece(0, 2, 0);
  ASSERT_TRUE(encoder->GetOutput()->HasModel()) << errors.text;
  EXPECT_NE(warnings.text.find("asked its input for the extent [0..20, 0..20, 0..23] and was "
                               "given [0..20, 0..20, 0..20]"),
            std::string::npos)
      << warnings.text;
  EXPECT_EQ(errors.text, "");
  encoder->UpdatePiece(1, 2, 0);
  EXPECT_FALSE(encoder->GetOutput()->HasModel());
  EXPECT_NE(errors.text.find("piece 1 of 2 was given the extent [0..20, 0..20, 0..20], which "
                             "holds no grid of its own extent [0..20, 0..20, 20..40]"),
            std::string::npos)
      << errors.text;
}

// More pieces than the image can be split into: the pieces left empty fit nothing (they do not
// ask for a corner of the image and fit it as a model of their own).
TEST(MFAEncoder, PiecesLeftEmptyFitNothing) {
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(0, 2, 0, 2, 0, 2);
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputConnection(source->GetOutputPort());
  encoder->SetDegree(1);
  encoder->SetGhostLevels(1);
  int whole[6] = {0, 2, 0, 2, 0, 2}, ext[6];
  vtkNew<vtkExtentTranslator> translator;
  int empty = 0, fitted = 0;
  for (int piece = 0; piece < 16; ++piece) {
    SCOPED_TRACE("piece " + std::to_string(piece));
    const bool owns = translator->PieceToExtentThreadSafe(piece, 16, 0, whole, ext,
                                                          vtkExtentTranslator::BLOCK_MODE, 0);
    encoder->UpdatePiece(piece, 16, 0);
    EXPECT_EQ(encoder->GetOutput()->HasModel(), owns);
    (owns ? fitted : empty) += 1;
  }
  EXPECT_GT(empty, 0);
  EXPECT_GT(fitted, 0);
}

// Images are fitted plainly unless ImageSmoothing is set; Smoothing is for scattered data.
TEST(MFAEncoder, ImageSmoothingSmoothsImagesOnly) {
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputData(imageOf(mlGrid(17)));
  encoder->SetSmoothing(0.5);
  encoder->Update();
  EXPECT_LT(encoder->GetLastMaxRelativeError(), 1e-5);  // interpolating, unsmoothed
  encoder->SetImageSmoothing(0.05);
  encoder->Update();
  EXPECT_GT(encoder->GetLastMaxRelativeError(), 1e-3);
  encoder->SetImageSmoothing(-1.0);
  EXPECT_EQ(encoder->GetImageSmoothing(), 0.0);
}

TEST(MFAEncoder, AdaptiveFitMeetsTheBound) {
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputData(imageOf(mlGrid(33)));
  encoder->SetMaxError(0.05);
  encoder->Update();
  ASSERT_TRUE(encoder->GetOutput()->HasModel());
  EXPECT_LE(encoder->GetLastMaxRelativeError(), 0.05);
  int counts[3];
  encoder->GetOutput()->GetNumberOfControlPoints(counts);
  EXPECT_LT(counts[0], 33);
}

TEST(MFAEncoder, PicksTheNamedArray) {
  vtkSmartPointer<vtkImageData> image = imageOf(mlGrid(11), "first");
  vtkNew<vtkDoubleArray> second;
  second->SetName("second");
  second->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i) second->SetValue(i, 100.0 + i % 5);
  image->GetPointData()->AddArray(second);

  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputData(image);
  encoder->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "second");
  encoder->Update();
  double r[2];
  encoder->GetOutput()->GetScalarRange(r);
  EXPECT_DOUBLE_EQ(r[0], 100.0);
  EXPECT_DOUBLE_EQ(r[1], 104.0);
  EXPECT_STREQ(encoder->GetOutput()->GetFieldName(), "second");

  ErrorLog log(encoder);
  encoder->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "third");
  encoder->Update();
  EXPECT_FALSE(encoder->GetOutput()->HasModel());
  EXPECT_NE(log.text.find("third"), std::string::npos) << log.text;
  EXPECT_NE(log.text.find("second"), std::string::npos) << "lists the arrays: " << log.text;
}

TEST(MFAEncoder, FitsATetrahedralMeshWithAMask) {
  // The grid split into tetrahedra: a mesh whose occupancy mask covers its whole box.
  vtkNew<vtkDataSetTriangleFilter> tets;
  tets->SetInputData(imageOf(mlGrid(15)));
  tets->TetrahedraOnlyOn();
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputConnection(tets->GetOutputPort());
  encoder->SetNumberOfControlPoints(10, 10, 10);
  encoder->Update();
  vtkMFAModelData* out = encoder->GetOutput();
  ASSERT_TRUE(out->HasModel());
  EXPECT_TRUE(out->HasDomainMask());
  EXPECT_TRUE(out->IsInside(0.1, 0.2, -0.3));
  EXPECT_LT(encoder->GetLastRMSRelativeError(), 0.1);

  // Cell samples (encode --cell-samples; a mesh gets 1 by default) change the fit, not its
  // quality here; a count the encoder has no rule for is an error without output.
  EXPECT_EQ(encoder->GetCellSamples(), -1);
  const double byDefault = out->EvaluateValue(0.1, 0.2, -0.3);
  encoder->SetCellSamples(1);
  encoder->Update();
  ASSERT_TRUE(encoder->GetOutput()->HasModel());
  EXPECT_EQ(encoder->GetOutput()->EvaluateValue(0.1, 0.2, -0.3), byDefault);
  encoder->SetCellSamples(0);
  encoder->Update();
  ASSERT_TRUE(encoder->GetOutput()->HasModel());
  EXPECT_NE(encoder->GetOutput()->EvaluateValue(0.1, 0.2, -0.3), byDefault);
  EXPECT_LT(encoder->GetLastRMSRelativeError(), 0.1);
  ErrorLog log(encoder);
  encoder->SetCellSamples(2);
  encoder->Update();
  EXPECT_FALSE(encoder->GetOutput()->HasModel());
  EXPECT_NE(log.text.find("1 or 4"), std::string::npos) << log.text;
  encoder->SetCellSamples(0);

  encoder->DomainMaskOff();
  encoder->Update();
  EXPECT_FALSE(encoder->GetOutput()->HasDomainMask());
}

TEST(MFAEncoder, FitsAPointCloud) {
  // Points in a ball: the point-coverage mask excludes the box corners.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> values;
  values->SetName("f");
  while (points->GetNumberOfPoints() < 6000) {
    const Vec3d p(u(rng), u(rng), u(rng));
    if (p.norm() > 1.0) continue;
    points->InsertNextPoint(p.data());
    values->InsertNextValue(p[0] + 2.0 * p[1] * p[2]);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  cloud->GetPointData()->SetScalars(values);
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputData(cloud);
  encoder->SetNumberOfControlPoints(8, 8, 8);
  encoder->Update();
  vtkMFAModelData* out = encoder->GetOutput();
  ASSERT_TRUE(out->HasModel());
  EXPECT_TRUE(out->HasDomainMask());
  double b[6];
  out->GetBounds(b);
  EXPECT_TRUE(out->IsInside(0, 0, 0));
  EXPECT_FALSE(out->IsInside(b[0], b[2], b[4]));
  EXPECT_NEAR(out->EvaluateValue(0.3, 0.2, -0.4), 0.3 + 2.0 * 0.2 * -0.4, 0.02);
}

// AutoSmoothing chooses the weight as `encode --smooth auto` does: noisy values get more
// smoothing than the default, the same weight as the library's choice on the same points.
TEST(MFAEncoder, AutoSmoothingChoosesTheWeightOfScatteredData) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.2);
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> values;
  values->SetName("f");
  mfadvr::ScatteredData data;
  while (points->GetNumberOfPoints() < 3000) {
    const Vec3d p(u(rng), u(rng), u(rng));
    const double v = std::sin(2.0 * p[0]) + p[1] * p[2] + noise(rng);
    points->InsertNextPoint(p.data());
    values->InsertNextValue(v);
    data.points.push_back(p);
    data.values.push_back(v);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  cloud->GetPointData()->SetScalars(values);
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputData(cloud);
  encoder->SetNumberOfControlPoints(14, 14, 14);
  encoder->Update();
  EXPECT_DOUBLE_EQ(encoder->GetLastSmoothing(), 1e-2);
  encoder->AutoSmoothingOn();
  encoder->Update();
  const double chosen = encoder->GetLastSmoothing();
  EXPECT_GT(chosen, 1e-2);
  data.source = "points";
  data.kind = "point cloud";
  mfadvr::ScatteredFitOptions o;
  o.controlCounts = {14, 14, 14};
  EXPECT_DOUBLE_EQ(chosen, mfadvr::chooseScatteredSmoothing(data, o).lambda);
}

TEST(MFAEncoder, ReportsInputsItCannotFit) {
  vtkNew<vtkMFAEncoder> encoder;
  ErrorLog log(encoder);
  vtkNew<vtkPolyData> empty;
  encoder->SetInputData(empty);
  encoder->Update();
  EXPECT_FALSE(encoder->GetOutput()->HasModel());
  EXPECT_NE(log.text.find("no points"), std::string::npos) << log.text;
}

}  // namespace
}  // namespace mfadvr::test
