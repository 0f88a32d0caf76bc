// The ray caster against scenes with known images, and its invariants: step refinement, early
// termination, thread count, fairness of the comparison (MFA vs trilinear against the truth).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "MarschnerLobbScene.h"
#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/StructuredEncoder.h"
#include "core/field/AnalyticField.h"
#include "core/field/ModelField.h"
#include "core/image/ImageMetrics.h"
#include "core/model/BlockModelFile.h"
#include "core/render/DeviceRenderer.h"
#include "core/render/PieceCompositor.h"
#include "core/render/RayCaster.h"
#include "core/render/ReconstructionMethod.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// A field whose value is `inside` for z > split and `outside` below, gradient zero.
struct LayeredField {
  Vec3d lo = Vec3d(-1, -1, -1), hi = Vec3d(1, 1, 1);
  double split = 0.0;
  float above = 1.0f, below = 1.0f;
  Vec3d boxMin() const { return lo; }
  Vec3d boxMax() const { return hi; }
  struct Sampler {
    const LayeredField* f;
    float value(const Vec3d& x) const { return x[2] > f->split ? f->above : f->below; }
    ValueGradient valueGradient(const Vec3d& x) const { return {value(x), Vec3f::Zero()}; }
  };
  Sampler sampler() const { return {this}; }
};

// Looks straight down -z at the unit box with a parallel projection that stays inside it.
RenderSettings slabSettings() {
  RenderSettings s;
  s.width = 8;
  s.height = 6;
  s.camera.position = Vec3d(0, 0, 5);
  s.camera.focalPoint = Vec3d(0, 0, 0);
  s.camera.parallelProjection = true;
  s.camera.parallelScale = 0.5;
  s.earlyTerminationOpacity = 2.0;  // off
  s.background = Vec3f(0.1f, 0.2f, 0.3f);
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{0.0, Vec3f(0, 0, 1)}, {1.0, Vec3f(1, 0, 0)}};
  s.transferFunction.opacity = {{0.0, 0.2f}, {1.0, 0.6f}};
  return s;
}

TEST(RayCaster, ConstantSlabIsExactlyBeerLambert) {
  const LayeredField slab;  // value 1 everywhere: red, opacity 0.6 per unit distance
  for (double dt : {0.1, 0.07, 0.5, 3.0}) {  // 0.07 and 3.0 do not divide the thickness 2
    for (double unit : {1.0, 0.25}) {
      RenderSettings s = slabSettings();
      s.sampleDistance = dt;
      s.opacityUnitDistance = unit;
      RenderStats stats;
      const Image image = renderVolume(slab, s, &stats);
      const double transmittance = std::pow(1.0 - 0.6, 2.0 / unit);
      for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
          const float* p = image.pixel(x, y);
          EXPECT_NEAR(p[0], (1 - transmittance) + transmittance * 0.1, 2e-6) << dt << " " << unit;
          EXPECT_NEAR(p[1], transmittance * 0.2, 2e-6);
          EXPECT_NEAR(p[2], transmittance * 0.3, 2e-6);
          EXPECT_NEAR(p[3], 1 - transmittance, 2e-6);
        }
      EXPECT_EQ(stats.raysHit, s.width * s.height);
      EXPECT_EQ(stats.samples,
                stats.raysHit * static_cast<std::int64_t>(std::ceil(2.0 / dt - 1e-9)));
    }
  }
}

// Opaque geometry in a VTK scene ends rays early: the slab in front of each pixel's ray end
// composites exactly as a thinner slab, with the end anywhere inside a step.
TEST(RayCaster, RayEndsCutTheSlabPerPixel) {
  const LayeredField slab;
  RenderSettings s = slabSettings();
  s.sampleDistance = 0.07;
  s.rayEnd.resize(static_cast<size_t>(s.width) * s.height);
  // The camera is 4 units above the slab's top face; ray ends go from before the slab to past it.
  for (int i = 0; i < s.width * s.height; ++i)
    s.rayEnd[i] = i == 0 ? INFINITY : static_cast<float>(3.5 + 3.0 * i / (s.width * s.height));
  const Image image = renderVolume(slab, s);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const double end = s.rayEnd[static_cast<size_t>(y) * s.width + x];
      const double thickness = std::clamp(end - 4.0, 0.0, 2.0);
      EXPECT_NEAR(image.pixel(x, y)[3], 1.0 - std::pow(0.4, thickness), 2e-6) << x << "," << y;
    }
  s.rayEnd.pop_back();
  EXPECT_THROW(renderVolume(slab, s), Error);
}

TEST(RayCaster, CompositesFrontToBack) {
  LayeredField layers;
  layers.above = 1.0f;  // red, 0.6
  layers.below = 0.0f;  // blue, 0.2
  RenderSettings s = slabSettings();
  s.sampleDistance = 0.1;
  s.background = Vec3f::Zero();
  const double a1 = 0.6, a2 = 0.2;  // each layer is one unit thick
  auto expectColour = [](const Image& image, double red, double blue) {
    const float* p = image.pixel(3, 2);
    EXPECT_NEAR(p[0], red, 1e-5);
    EXPECT_NEAR(p[2], blue, 1e-5);
  };
  // From +z the red layer is in front: red a1, blue (1 - a1) a2.
  expectColour(renderVolume(layers, s), a1, (1 - a1) * a2);
  // From -z the blue layer is in front.
  s.camera.position = Vec3d(0, 0, -5);
  expectColour(renderVolume(layers, s), (1 - a2) * a1, a2);
}

TEST(RayCaster, RaysMissingTheBoxShowTheBackground) {
  const LayeredField slab;
  RenderSettings s = slabSettings();
  s.camera.parallelScale = 4.0;  // the box covers the middle only
  RenderStats stats;
  const Image image = renderVolume(slab, s, &stats);
  const float* corner = image.pixel(0, 0);
  EXPECT_FLOAT_EQ(corner[0], 0.1f);
  EXPECT_FLOAT_EQ(corner[3], 0.0f);
  EXPECT_LT(stats.raysHit, stats.rays);
  EXPECT_GT(stats.raysHit, 0);
}

double maxAbsDifference(const Image& a, const Image& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.rgba.size(); ++i)
    worst = std::max(worst, double(std::abs(a.rgba[i] - b.rgba[i])));
  return worst;
}

double meanAbsDifference(const Image& a, const Image& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.rgba.size(); ++i) sum += std::abs(a.rgba[i] - b.rgba[i]);
  return sum / a.rgba.size();
}

TEST(RayCaster, HalvingTheStepBarelyChangesTheImage) {
  const auto ml = makeBuiltin("marschner-lobb");
  const AnalyticField truth(*ml);
  RenderSettings s = mlSettings(48);
  const Image coarse = renderVolume(truth, s);
  s.sampleDistance /= 2.0;
  const Image fine = renderVolume(truth, s);
  // Opacity correction keeps the two renders of the same field close; without it the finer
  // step would composite twice the opacity per unit length.
  EXPECT_LT(meanAbsDifference(coarse, fine), 0.004);
  EXPECT_GT(compareImages(toImage8(coarse), toImage8(fine)).psnr, 38.0);
}

TEST(RayCaster, EarlyTerminationChangesLessThanItsThreshold) {
  const auto ml = makeBuiltin("marschner-lobb");
  const AnalyticField truth(*ml);
  RenderSettings s = mlSettings(40);
  s.background = Vec3f(1, 1, 1);
  s.earlyTerminationOpacity = 2.0;
  RenderStats fullStats, ertStats;
  const Image full = renderVolume(truth, s, &fullStats);
  s.earlyTerminationOpacity = 0.95;
  const Image early = renderVolume(truth, s, &ertStats);
  // What is left after stopping is at most (1 - 0.95) of colours and background in [0, 1]...
  // colours can exceed 1 with specular, so bound by the brightest sample.
  EXPECT_LE(maxAbsDifference(full, early), 0.05 * 1.2 + 1e-6);
  EXPECT_GT(ertStats.terminated, 0);
  EXPECT_LT(ertStats.samples, fullStats.samples);
}

TEST(RayCaster, ImageDoesNotDependOnThreadCount) {
  const auto ml = makeBuiltin("marschner-lobb");
  const AnalyticField truth(*ml);
  RenderSettings s = mlSettings(37);  // not a multiple of the tile size
  s.threads = 1;
  const Image one = renderVolume(truth, s);
  s.threads = 2;
  const Image two = renderVolume(truth, s);
  s.threads = 0;
  const Image all = renderVolume(truth, s);
  EXPECT_EQ(one.rgba, two.rgba);
  EXPECT_EQ(one.rgba, all.rgba);
}

TEST(RayCaster, ProgressReachesOne) {
  const LayeredField slab;
  RenderSettings s = slabSettings();
  s.width = s.height = 64;
  double last = 0.0;
  int calls = 0;
  s.progress = [&](double f) {
    EXPECT_GE(f, last);
    last = f;
    ++calls;
  };
  s.threads = 1;
  renderVolume(slab, s);
  EXPECT_GT(calls, 1);
  EXPECT_DOUBLE_EQ(last, 1.0);
}

TEST(RayCaster, MfaBeatsTrilinearAgainstTheTruth) {
  // Marschner-Lobb at its classic 41^3: an interpolating cubic MFA model against trilinear
  // filtering of the same samples, both rendered exactly like the analytic truth.
  const auto ml = makeBuiltin("marschner-lobb");
  const StructuredGrid grid = sampleBuiltin(*ml, {41, 41, 41});
  const Model model = fitStructured(grid, StructuredFitOptions{});
  SceneData scene;
  scene.model = &model;
  scene.grid = &grid;
  scene.truth = ml.get();
  scene.differenceStep = grid.spacing;
  const RenderSettings s = mlSettings(96);
  auto render = [&](ReconstructionMethod m) {
    MethodSpec spec;
    spec.method = m;
    return toImage8(renderMethod(scene, spec, s));
  };
  const Image8 truth = render(ReconstructionMethod::Truth);
  const double mfa = compareImages(truth, render(ReconstructionMethod::Mfa)).psnr;
  const double trilinear = compareImages(truth, render(ReconstructionMethod::Trilinear)).psnr;
  EXPECT_GT(mfa, trilinear + 1.0) << "mfa " << mfa << " dB, trilinear " << trilinear << " dB";

  // The gradient test: value from the truth, gradient from the method.
  MethodSpec gradientOnly;
  gradientOnly.method = ReconstructionMethod::Truth;
  gradientOnly.gradientFrom = ReconstructionMethod::Mfa;
  const double mfaGradient =
      compareImages(truth, toImage8(renderMethod(scene, gradientOnly, s))).psnr;
  gradientOnly.gradientFrom = ReconstructionMethod::Trilinear;
  const double trilinearGradient =
      compareImages(truth, toImage8(renderMethod(scene, gradientOnly, s))).psnr;
  EXPECT_GT(mfaGradient, trilinearGradient);
}

TEST(RayCaster, PiecesWithAlignedSamplesCompositeToTheWhole) {
  // A model split into 2 x 2 x 1 pieces by clip boxes, each rendered alone over a transparent
  // background with camera-aligned steps and composited in visibility order, gives the image of
  // the whole model: the pieces take the same samples, except that a step cut by a piece
  // boundary is taken as two shorter ones.
  const auto ml = makeBuiltin("marschner-lobb");
  const StructuredGrid grid = sampleBuiltin(*ml, {24, 24, 24});
  const Model model = fitStructured(grid, StructuredFitOptions{});
  const ModelField field(model);
  RenderSettings s = mlSettings(64);
  s.earlyTerminationOpacity = 2.0;  // a whole ray would stop where a piece's ray cannot know to
  s.background = Vec3f::Zero();
  s.alignSamplesToCamera = true;
  const Image whole = renderVolume(field, s);
  const Vec3d lo = model.domain().min, hi = model.domain().max;
  const double cx = lo[0] + 0.37 * (hi[0] - lo[0]), cy = lo[1] + 0.61 * (hi[1] - lo[1]);
  std::vector<DomainBox> boxes;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      boxes.push_back(DomainBox{Vec3d(i ? cx : lo[0], j ? cy : lo[1], lo[2]),
                                Vec3d(i ? hi[0] : cx, j ? hi[1] : cy, hi[2])});
  auto renderPieces = [&](const RenderSettings& settings) {
    std::vector<Image> pieces;
    for (const DomainBox& box : boxes) {
      RenderSettings piece = settings;
      piece.clipBox = box;
      pieces.push_back(renderVolume(field, piece));
    }
    return compositeInVisibilityOrder(settings, boxes, pieces);
  };
  const Image composited = renderPieces(s);
  EXPECT_LT(maxAbsDifference(whole, composited), 0.02);
  EXPECT_LT(meanAbsDifference(whole, composited), 2e-4);
  EXPECT_GT(compareImages(toImage8(whole), toImage8(composited)).psnr, 50.0);

  // Without aligned steps each piece starts its steps where its rays enter it: further apart.
  s.alignSamplesToCamera = false;
  const Image wholeUnaligned = renderVolume(field, s);
  EXPECT_GT(meanAbsDifference(wholeUnaligned, renderPieces(s)),
            meanAbsDifference(whole, composited));

  // A clip box beside the model renders nothing; an inverted one is refused.
  RenderSettings outside = s;
  outside.clipBox = DomainBox{hi + Vec3d::Ones(), hi + Vec3d::Constant(2.0)};
  const Image empty = renderVolume(field, outside);
  EXPECT_EQ(*std::max_element(empty.rgba.begin(), empty.rgba.end()), 0.0f);
  outside.clipBox = DomainBox{hi, lo};
  EXPECT_THROW(renderVolume(field, outside), Error);
}

TEST(RayCaster, GridPiecesCompositedInOneOrderAsTheyAreRendered) {
  // Pieces that are the cells of a 3 x 2 x 2 grid (uneven faces): renderPieces renders them in
  // gridVisibilityOrder and composites each at once; the image must be the per-pixel
  // composite of all pieces' images, bit for bit, from cameras outside, inside and parallel.
  const auto ml = makeBuiltin("marschner-lobb");
  const Model model = fitStructured(sampleBuiltin(*ml, {20, 20, 20}), StructuredFitOptions{});
  const ModelField field(model);
  const Vec3d lo = model.domain().min, hi = model.domain().max;
  const double fx[4] = {0.0, 0.3, 0.55, 1.0}, fy[3] = {0.0, 0.7, 1.0}, fz[3] = {0.0, 0.45, 1.0};
  std::vector<DomainBox> boxes;
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 3; ++i)  // not in x-fastest order: the order must not matter
      for (int j = 0; j < 2; ++j) {
        auto at = [&](int a, double f) { return lo[a] + f * (hi[a] - lo[a]); };
        boxes.push_back(DomainBox{Vec3d(at(0, fx[i]), at(1, fy[j]), at(2, fz[k])),
                                  Vec3d(at(0, fx[i + 1]), at(1, fy[j + 1]), at(2, fz[k + 1]))});
      }
  int views = 0;
  for (int view = 0; view < 4; ++view) {
    RenderSettings s = mlSettings(40);
    s.background = Vec3f::Zero();
    s.alignSamplesToCamera = true;
    s.earlyTerminationOpacity = 2.0;  // per pixel, every piece is composited
    if (view == 1) {
      s.camera.azimuth(140.0);
      s.camera.elevation(-35.0);
    }
    if (view == 2) {  // inside the grid, looking across it
      s.camera.position = lo + 0.4 * (hi - lo);
      s.camera.focalPoint = hi;
    }
    if (view == 3) {
      s.camera.parallelProjection = true;
      s.camera.azimuth(-70.0);
    }
    const std::vector<size_t> order = gridVisibilityOrder(s, boxes);
    ASSERT_EQ(order.size(), boxes.size());
    std::vector<Image> images;
    for (const DomainBox& box : boxes) {
      RenderSettings piece = s;
      piece.clipBox = box;
      images.push_back(renderVolume(field, piece));
    }
    const Image perPixel = compositeInVisibilityOrder(s, boxes, images);
    std::vector<size_t> rendered;
    const Image inOrder =
        renderPieces(s, boxes, [&](size_t i, const RenderSettings& piece, RenderStats* stats) {
          rendered.push_back(i);
          return renderVolume(field, piece, stats);
        });
    EXPECT_EQ(rendered, order);
    EXPECT_EQ(inOrder.rgba, perPixel.rgba) << "view " << view;
    EXPECT_GT(*std::max_element(inOrder.rgba.begin(), inOrder.rgba.end()), 0.1f);
    ++views;
  }
  EXPECT_EQ(views, 4);

  // With early termination, a pixel whose composite is opaque ends its ray before the pieces
  // behind, and a piece that no remaining ray crosses is not rendered: a nearly opaque
  // medium, seen along x, leaves back pieces out, also through a host's skewed frustum (rays
  // whose right, up and forward are neither unit nor orthogonal). The image differs from
  // compositing every piece by at most what is left behind the termination opacity; a piece
  // left out wrongly would differ by far more.
  for (int setup = 0; setup < 3; ++setup) {
    RenderSettings s = mlSettings(40);
    s.background = Vec3f::Zero();
    s.alignSamplesToCamera = true;
    s.opacityUnitDistance = 1e-3;
    s.camera.position =
        Vec3d(lo[0] - 3.0 * (hi[0] - lo[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]));
    s.camera.focalPoint = 0.5 * (lo + hi);
    if (setup == 1) s.camera.azimuth(-25.0);  // oblique: the pieces half hide each other
    if (setup == 2) s.rays = test::skewedRays(s.primaryRays());
    std::vector<Image> images;
    for (const DomainBox& box : boxes) {
      RenderSettings piece = s;
      piece.clipBox = box;
      piece.earlyTerminationOpacity = 2.0;
      images.push_back(renderVolume(field, piece));
    }
    const Image every = compositeInVisibilityOrder(s, boxes, images);
    size_t rendered = 0;
    const Image stopped =
        renderPieces(s, boxes, [&](size_t, const RenderSettings& piece, RenderStats* stats) {
          ++rendered;
          return renderVolume(field, piece, stats);
        });
    if (setup != 1) {
      EXPECT_LT(rendered, boxes.size()) << "setup " << setup;
    }
    EXPECT_GE(rendered, 4u) << "setup " << setup;  // the front layer (x) at least
    EXPECT_LE(maxAbsDifference(every, stopped), 1.0 - 0.99 + 1e-5) << "setup " << setup;
    EXPECT_GT(*std::max_element(stopped.rgba.begin(), stopped.rgba.end()), 0.5f);
  }

  // Regions that are not the cells of one grid have no such order.
  std::vector<DomainBox> uneven = boxes;
  uneven[0].max[0] = lo[0] + 0.2 * (hi[0] - lo[0]);
  EXPECT_TRUE(gridVisibilityOrder(mlSettings(40), uneven).empty());
  std::vector<DomainBox> twice = boxes;
  twice[1] = twice[0];
  EXPECT_TRUE(gridVisibilityOrder(mlSettings(40), twice).empty());
}

// The pixels a region projects onto hold every pixel whose ray crosses the region, from
// cameras outside (perspective, parallel, a skewed host frustum) and inside it; a small region
// in front covers few of the image's pixels; rays that end at once are not counted.
TEST(RayCaster, ProjectedPixelsHoldEveryRayThatCrossesTheRegion) {
  const DomainBox whole{Vec3d(-1, -1, -1), Vec3d(1, 1, 1)};
  const DomainBox small{Vec3d(0.1, -0.2, 0.3), Vec3d(0.4, 0.1, 0.5)};
  for (int view = 0; view < 4; ++view) {
    RenderSettings s;
    s.width = 60;
    s.height = 40;
    s.camera.resetToBounds(whole.min, whole.max);
    s.camera.azimuth(30.0 + 40.0 * view);
    s.camera.elevation(20.0);
    if (view == 1) s.camera.parallelProjection = true;
    if (view == 3) s.camera.position = Vec3d(0.2, -0.1, -0.5);  // inside, behind the small box
    CameraRays rays = s.primaryRays();
    if (view == 2)
      for (int a = 0; a < 3; ++a) {
        rays.right[a] = 1.3 * rays.right[a] + 0.2 * rays.up[a];
        rays.up[a] = 0.8 * rays.up[a] + 0.1 * rays.forward[a];
      }
    for (const bool isSmall : {false, true}) {
      const DomainBox& box = isSmall ? small : whole;
      const PixelRect r = projectedPixels(rays, box);
      const double lo[3] = {box.min[0], box.min[1], box.min[2]};
      const double hi[3] = {box.max[0], box.max[1], box.max[2]};
      std::int64_t crossing = 0;
      for (int y = 0; y < rays.height; ++y)
        for (int x = 0; x < rays.width; ++x) {
          double o[3], d[3], tEnter, tExit;
          primaryRay(rays, x, y, o, d);
          if (!intersectBox(o, d, lo, hi, tEnter, tExit) || !(tExit > std::max(tEnter, 0.0)))
            continue;
          ++crossing;
          EXPECT_TRUE(x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1)
              << "view " << view << " pixel " << x << "," << y;
        }
      EXPECT_GE(r.count(), crossing);
      EXPECT_EQ(raysStillGoing(rays, {}, box), r.count());
      std::vector<float> ends(static_cast<size_t>(rays.width) * rays.height, 0.0f);
      EXPECT_EQ(raysStillGoing(rays, ends, box), 0);
      ends[static_cast<size_t>(r.y0) * rays.width + r.x0] = INFINITY;
      if (r.count() > 0) {
        EXPECT_EQ(raysStillGoing(rays, ends, box), 1);
      }
      if (isSmall && view != 3) {
        EXPECT_GT(crossing, 0) << "view " << view;
        EXPECT_LT(r.count(), std::int64_t(rays.width) * rays.height / 4) << "view " << view;
      }
    }
  }
}

// A device that renders on the CPU and records what it was asked to do.
class RecordingDevice final : public DeviceRenderer {
 public:
  std::string description() const override { return "recording"; }
  Image renderModel(const ModelField& field, const RenderSettings& settings,
                    RenderStats* stats) override {
    calls.push_back("render");
    return renderVolume(field, settings, stats);
  }
  void forgetModel() override { calls.push_back("forget"); }
  Image renderTrilinear(const PaddedGrid&, const RenderSettings&, RenderStats*) override {
    throw Error("not recorded");
  }
  std::vector<std::string> calls;
};

TEST(RayCaster, BlocksReadOneAtATimeAreEachUploadedAgain) {
  // Blocks read one at a time may lie where the block before lay: a device must not take one
  // for the model it kept. The image equals the one from the blocks in memory.
  const StructuredGrid grid = sampleBuiltinSpec("builtin:marschner-lobb:12x10x9");
  EncodeOptions o;
  o.degree = {2, 2, 2};
  const std::vector<ModelBlock> blocks = encodeStructuredBlocks(grid, {2, 1, 2}, 1, o);
  const auto path = test::scratchDir() / "streamed.mfa";
  saveBlockModels(blocks, {2, 1, 2}, path);
  const BlockModelStream stream{path, readBlockIndex(path)};
  RenderSettings s = mlSettings(32);
  s.earlyTerminationOpacity = 2.0;
  RecordingDevice device;
  MethodSpec spec;
  spec.method = ReconstructionMethod::Mfa;
  spec.device = &device;
  SceneData streamed;
  streamed.model = &blocks.front().model;
  streamed.streamedBlocks = &stream;
  const Image a = renderMethod(streamed, spec, s);
  EXPECT_EQ(device.calls, (std::vector<std::string>{"forget", "render", "forget", "render",
                                                    "forget", "render", "forget", "render"}));
  device.calls.clear();
  SceneData held;
  held.model = &blocks.front().model;
  held.blocks = &blocks;
  const Image b = renderMethod(held, spec, s);
  EXPECT_EQ(device.calls.size(), 4u);  // blocks in memory: no need to forget
  EXPECT_EQ(a.rgba, b.rgba);
}

TEST(RayCaster, MethodsNeedTheirData) {
  SceneData empty;
  RenderSettings s = slabSettings();
  s.sampleDistance = 0.1;
  for (const auto& name : reconstructionMethodNames()) {
    MethodSpec spec;
    spec.method = parseReconstructionMethod(name);
    EXPECT_THROW(renderMethod(empty, spec, s), Error) << name;
  }
  EXPECT_THROW(parseReconstructionMethod("cubic"), Error);
}

TEST(RayCaster, RejectsBadSettings) {
  const LayeredField slab;
  RenderSettings s = slabSettings();
  s.sampleDistance = 0.0;
  EXPECT_THROW(renderVolume(slab, s), Error);
  s = slabSettings();
  s.opacityUnitDistance = -1.0;
  EXPECT_THROW(renderVolume(slab, s), Error);
  s = slabSettings();
  s.transferFunction.space = TfSpace::Normalized;
  EXPECT_THROW(renderVolume(slab, s), Error);
}

}  // namespace
}  // namespace mfadvr
