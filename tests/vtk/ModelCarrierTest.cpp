// Models carried by image data (the form ParaView moves): the reader's and the encoder's
// image output, multi-block files read whole or piece by piece, the encoder's pieces with ghost
// layers, and the mapper rendering carriers like the models themselves.
#include <gtest/gtest.h>

#include <cmath>

#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkTrivialProducer.h>
#include <vtkUnsignedCharArray.h>

#include "TestSupport.h"
#include "VtkSceneFixture.h"
#include "core/encode/PieceEncoder.h"
#include "core/image/ImageMetrics.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "vtkMFAEncoder.h"
#include "vtkMFAReader.h"

namespace mfadvr::test {
namespace {

StructuredGrid mlGrid() {
  return sampleBuiltin(*makeBuiltin("marschner-lobb"), {41, 41, 41});
}

TEST(ModelCarrier, ReaderOutputsAnImageThatRendersLikeTheModel) {
  const auto path = scratchDir() / "carrier.mfa";
  saveModel(*marschnerLobbModel(), path);
  VtkVolumeScene scene(marschnerLobbModel(), true);
  const Image8 reference = scene.render();

  vtkNew<vtkMFAReader> reader;
  reader->SetFileName(path.c_str());
  reader->OutputImageDataOn();
  reader->Update();
  auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  ASSERT_NE(image, nullptr);
  EXPECT_EQ(reader->GetOutput(), nullptr);
  // The data's 41^3 grid over the model's box, holding the model's values there (which, for an
  // interpolating fit, are the samples).
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 41);
  EXPECT_EQ(dims[2], 41);
  double b[6];
  image->GetBounds(b);
  EXPECT_DOUBLE_EQ(b[0], -1.0);
  EXPECT_DOUBLE_EQ(b[5], 1.0);
  const StructuredGrid samples = mlGrid();
  vtkDataArray* values = image->GetPointData()->GetScalars();
  ASSERT_EQ(values->GetNumberOfTuples(), samples.sampleCount());
  double worst = 0.0;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    worst = std::max(worst, std::abs(values->GetTuple1(i) - samples.values[i]));
  EXPECT_LT(worst, 1e-5);

  // The mapper's model uses the carrier's bytes in place: it holds a reference to them.
  auto* carried = vtkUnsignedCharArray::SafeDownCast(image->GetFieldData()->GetArray("MFAModel0"));
  ASSERT_NE(carried, nullptr);
  const int referencesBefore = carried->GetReferenceCount();
  scene.mapper->SetInputConnection(reader->GetOutputPort());
  const Image8 viaCarrier = scene.render();
  EXPECT_EQ(carried->GetReferenceCount(), referencesBefore + 1);
  // The carrier path samples at multiples of the step from the camera, the model path from
  // where each ray enters the box: the same volume sampled at other points.
  EXPECT_GT(compareImages(reference, viaCarrier).psnr, 33.0);
  double mb[6];
  scene.mapper->GetBounds(mb);
  EXPECT_DOUBLE_EQ(mb[1], 1.0);

  // A damaged carrier is an error, not a crash.
  vtkNew<vtkImageData> broken;
  broken->DeepCopy(image);
  auto* bytes = vtkUnsignedCharArray::SafeDownCast(broken->GetFieldData()->GetArray("MFAModel0"));
  ASSERT_NE(bytes, nullptr);
  bytes->SetValue(40, static_cast<unsigned char>(bytes->GetValue(40) ^ 0x5a));
  scene.mapper->SetInputData(broken);
  EXPECT_EQ(coverage(scene.render(), scene.coreSettings().background), 0.0);
}

// The scene's model as a single carrier: the reference of the partitioned renders (the same
// camera-aligned samples).
Image8 singleCarrierImage(VtkVolumeScene& scene, const std::filesystem::path& dir) {
  const auto path = dir / "single-carrier.mfa";
  saveModel(*marschnerLobbModel(), path);
  vtkNew<vtkMFAReader> reader;
  reader->SetFileName(path.c_str());
  reader->OutputImageDataOn();
  scene.mapper->SetInputConnection(reader->GetOutputPort());
  return scene.render();
}

TEST(ModelCarrier, MultiBlockFilesRenderWholeOrPieceByPiece) {
  const auto dir = scratchDir();
  const auto path = dir / "carrier-blocks.mfa";
  saveBlockModels(encodeStructuredBlocks(mlGrid(), {2, 2, 1}, -1, EncodeOptions{}), {2, 2, 1},
                  path);
  VtkVolumeScene scene(marschnerLobbModel(), true);
  const Image8 reference = singleCarrierImage(scene, dir);

  vtkNew<vtkMFAReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();  // a multi-block file needs image output
  EXPECT_FALSE(reader->GetOutput()->HasModel());
  reader->OutputImageDataOn();
  scene.mapper->SetInputConnection(reader->GetOutputPort());
  const Image8 all = scene.render();  // one piece: every block, composited
  EXPECT_GT(compareImages(reference, all).psnr, 40.0);

  // Pieces split the blocks: 4 pieces read one each, 2 pieces two each, 8 pieces share them
  // (a slab of a block each).
  auto regionCount = [&](int piece, int pieces) {
    reader->UpdatePiece(piece, pieces, 0);
    auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
    vtkDataArray* regions = image->GetFieldData()->GetArray("MFARegions");
    return regions ? regions->GetNumberOfTuples() : 0;
  };
  EXPECT_EQ(regionCount(3, 4), 1);
  EXPECT_EQ(regionCount(1, 2), 2);
  EXPECT_EQ(regionCount(0, 8), 1);
  EXPECT_EQ(regionCount(7, 8), 1);

  // Every piece is a sub-extent of the one whole image the reader announces (one origin and
  // spacing), and the pieces' regions tile the whole box, for any number of pieces.
  reader->UpdateInformation();
  int whole[6];
  reader->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  for (int pieces : {1, 2, 3, 4, 5, 8, 13}) {
    SCOPED_TRACE(pieces);
    double volume = 0.0;
    int cells = 0;
    for (int piece = 0; piece < pieces; ++piece) {
      reader->UpdatePiece(piece, pieces, 0);
      auto* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
      if (image->GetNumberOfPoints() == 0) continue;
      int extent[6];
      image->GetExtent(extent);
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(extent[2 * a], whole[2 * a]);
        EXPECT_LE(extent[2 * a + 1], whole[2 * a + 1]);
        EXPECT_DOUBLE_EQ(image->GetOrigin()[a], -1.0);  // the box's corner, on every piece
      }
      cells += image->GetNumberOfCells();
      vtkDataArray* regions = image->GetFieldData()->GetArray("MFARegions");
      for (vtkIdType r = 0; r < regions->GetNumberOfTuples(); ++r) {
        const double* b = regions->GetTuple(r);
        volume += (b[1] - b[0]) * (b[3] - b[2]) * (b[5] - b[4]);
      }
    }
    EXPECT_NEAR(volume, 8.0, 1e-9);  // [-1, 1]^3
    EXPECT_EQ(cells, (whole[1] - whole[0]) * (whole[3] - whole[2]) * (whole[5] - whole[4]));
  }
}

TEST(ModelCarrier, EncoderPiecesCompositeToTheWholeImage) {
  const StructuredGrid grid = mlGrid();
  VtkVolumeScene scene(marschnerLobbModel(), true);
  const Image8 reference = singleCarrierImage(scene, scratchDir());
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(imageOf(grid));
  vtkNew<vtkMFAEncoder> encoder;
  encoder->SetInputConnection(producer->GetOutputPort());
  encoder->OutputImageDataOn();
  // Each piece: its own region, a model over its samples and ghost layers.
  std::vector<vtkSmartPointer<vtkImageData>> carriers;
  for (int piece = 0; piece < 2; ++piece) {
    encoder->UpdatePiece(piece, 2, 0);
    auto copy = vtkSmartPointer<vtkImageData>::New();
    copy->DeepCopy(vtkImageData::SafeDownCast(encoder->GetOutputDataObject(0)));
    carriers.push_back(copy);
  }
  double a[6], b[6];
  carriers[0]->GetBounds(a);
  carriers[1]->GetBounds(b);
  // Neighbours along one axis, sharing a face, together the whole box.
  int shared = 0;
  for (int axis = 0; axis < 3; ++axis)
    if (std::abs(a[2 * axis + 1] - b[2 * axis]) < 1e-9 ||
        std::abs(b[2 * axis + 1] - a[2 * axis]) < 1e-9)
      ++shared;
  EXPECT_EQ(shared, 1);
  // The carriers' cells partition the data's cells, whatever the number of pieces (ParaView's
  // default opacity unit distance is derived from the cell count).
  EXPECT_EQ(carriers[0]->GetNumberOfCells() + carriers[1]->GetNumberOfCells(), 40 * 40 * 40);
  // Rendered through two volumes in one scene, back one first: VTK draws volumes in the order
  // they were added, and each mapper blends over what is drawn (premultiplied).
  vtkNew<vtkMFAVolumeMapper> second;
  second->SetSampleDistance(0.02);
  vtkNew<vtkVolume> secondVolume;
  secondVolume->SetMapper(second);
  secondVolume->SetProperty(scene.property);
  const double* cam = scene.renderer->GetActiveCamera()->GetPosition();
  auto distance = [&](const double* bounds) {
    double d = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double c = 0.5 * (bounds[2 * axis] + bounds[2 * axis + 1]) - cam[axis];
      d += c * c;
    }
    return d;
  };
  const bool firstIsFar = distance(a) > distance(b);
  scene.mapper->SetInputData(carriers[firstIsFar ? 0 : 1]);
  second->SetInputData(carriers[firstIsFar ? 1 : 0]);
  scene.renderer->AddVolume(secondVolume);
  const Image8 pieces = scene.render();
  EXPECT_GT(compareImages(reference, pieces).psnr, 40.0);
}

// PassInputValues: the carrier's point scalars are the input's samples, the input's own array
// (shared, not copied) on one piece and on each of two; a piece's carrier then keeps the
// input's extent, the cells outside its own region marked as ghost cells. The models are those
// of the default carrier.
TEST(ModelCarrier, EncoderCanPassTheInputSamplesThrough) {
  vtkSmartPointer<vtkImageData> input = imageOf(mlGrid());
  vtkDataArray* samples = input->GetPointData()->GetScalars();
  ASSERT_NE(samples, nullptr);
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(input);
  vtkNew<vtkMFAEncoder> evaluated, passed;
  for (vtkMFAEncoder* e : {evaluated.Get(), passed.Get()}) {
    e->SetInputConnection(producer->GetOutputPort());
    e->OutputImageDataOn();
  }
  passed->PassInputValuesOn();
  // The carried model's control points (its provenance holds the fit's time, which differs).
  const auto controlPoints = [](vtkImageData* carrier) {
    auto* bytes =
        vtkUnsignedCharArray::SafeDownCast(carrier->GetFieldData()->GetAbstractArray("MFAModel0"));
    if (!bytes) return std::vector<float>();
    const Model m = parseModel({bytes->GetPointer(0), size_t(bytes->GetNumberOfTuples())});
    return std::vector<float>(m.spline().controlPoints().begin(), m.spline().controlPoints().end());
  };
  const int pieceCounts[] = {1, 2};
  for (int pieces : pieceCounts)
    for (int piece = 0; piece < pieces; ++piece) {
      SCOPED_TRACE("piece " + std::to_string(piece) + " of " + std::to_string(pieces));
      evaluated->UpdatePiece(piece, pieces, 0);
      passed->UpdatePiece(piece, pieces, 0);
      auto* a = vtkImageData::SafeDownCast(evaluated->GetOutputDataObject(0));
      auto* b = vtkImageData::SafeDownCast(passed->GetOutputDataObject(0));
      ASSERT_TRUE(a && b);
      int ea[6], eb[6], ein[6];
      a->GetExtent(ea);
      b->GetExtent(eb);
      input->GetExtent(ein);
      for (int i = 0; i < 6; ++i) EXPECT_EQ(eb[i], ein[i]);
      // The ghost cells: exactly the cells outside the evaluated carrier's (the piece's own).
      vtkUnsignedCharArray* ghosts = b->GetCellGhostArray();
      if (pieces == 1) {
        EXPECT_FALSE(b->HasAnyGhostCells());
      } else {
        ASSERT_NE(ghosts, nullptr);
        vtkIdType owned = 0;
        for (int k = eb[4]; k < eb[5]; ++k)
          for (int j = eb[2]; j < eb[3]; ++j)
            for (int i = eb[0]; i < eb[1]; ++i) {
              int ijk[3] = {i, j, k};
              const bool own =
                  i >= ea[0] && i < ea[1] && j >= ea[2] && j < ea[3] && k >= ea[4] && k < ea[5];
              const bool ghost = ghosts->GetValue(b->ComputeCellId(ijk)) != 0;
              ASSERT_EQ(ghost, !own) << i << " " << j << " " << k;
              owned += own;
            }
        EXPECT_EQ(owned, a->GetNumberOfCells());
      }
      const std::vector<float> ctrl = controlPoints(b);
      EXPECT_FALSE(ctrl.empty());
      EXPECT_EQ(controlPoints(a), ctrl);
      vtkDataArray* values = b->GetPointData()->GetScalars();
      ASSERT_NE(values, nullptr);
      EXPECT_EQ(values, samples);  // shared, not copied
      ASSERT_EQ(values->GetNumberOfTuples(), b->GetNumberOfPoints());
      // Every carrier point holds the input's sample there; the evaluated carrier holds the
      // interpolating model's value, which differs from it by rounding only.
      vtkDataArray* modelValues = a->GetPointData()->GetScalars();
      double worst = 0.0;
      for (int k = ea[4]; k <= ea[5]; ++k)
        for (int j = ea[2]; j <= ea[3]; ++j)
          for (int i = ea[0]; i <= ea[1]; ++i) {
            int ijk[3] = {i, j, k};
            const vtkIdType at = b->ComputePointId(ijk), in = input->ComputePointId(ijk);
            ASSERT_EQ(values->GetTuple1(at), samples->GetTuple1(in)) << i << " " << j << " " << k;
            worst = std::max(worst, std::abs(modelValues->GetTuple1(a->ComputePointId(ijk)) -
                                             values->GetTuple1(at)));
          }
      EXPECT_LT(worst, 1e-4);
    }
}

}  // namespace
}  // namespace mfadvr::test
