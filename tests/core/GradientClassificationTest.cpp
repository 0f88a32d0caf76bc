// Classification by |grad f|: gradient opacity and 2-D transfer functions. On f = x^2 (an
// interpolating cubic model reproduces it) |grad f| = 2|x| is known everywhere, so which part of
// the volume a gradient-dependent function keeps is known too; a function that does not depend on
// the gradient must give the 1-D function's image; the 1-D envelope of a 2-D function must never
// hide a value the 2-D table shows.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/encode/StructuredEncoder.h"
#include "core/field/ModelField.h"
#include "core/grid/StructuredGrid.h"
#include "core/image/ImageMetrics.h"
#include "core/render/ClassificationTables.h"
#include "core/render/RayCaster.h"
#include "core/render/ReconstructionMethod.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

// f = x^2 on [0, 1] x [-0.5, 0.5]^2: |grad f| = 2x.
StructuredGrid squareOfX() {
  StructuredGrid g;
  g.dims = {17, 9, 9};
  g.origin = Vec3d(0.0, -0.5, -0.5);
  g.spacing = Vec3d(1.0 / 16, 1.0 / 8, 1.0 / 8);
  g.values.resize(size_t(g.sampleCount()));
  for (std::int64_t k = 0; k < g.dims[2]; ++k)
    for (std::int64_t j = 0; j < g.dims[1]; ++j)
      for (std::int64_t i = 0; i < g.dims[0]; ++i) {
        const double x = g.position(i, j, k)[0];
        g.at(i, j, k) = x * x;
      }
  return g;
}

// Looking down -z with a parallel projection: pixel column c sees x = (c + 0.5) / width.
RenderSettings frontView(const StructuredGrid& g, bool shade) {
  RenderSettings s;
  s.width = 64;
  s.height = 16;
  s.camera.resetToBounds(g.boxMin(), g.boxMax());
  s.camera.parallelProjection = true;
  s.camera.parallelScale = 0.5 * s.height / s.width;
  s.camera.validate();
  s.transferFunction.space = TfSpace::Data;
  s.transferFunction.color = {{0.0, Vec3f(0.2f, 0.5f, 1.0f)}, {1.0, Vec3f(1.0f, 0.6f, 0.1f)}};
  s.transferFunction.opacity = {{0.0, 0.3f}, {1.0, 0.6f}};
  s.opacityUnitDistance = 0.1;
  s.sampleDistance = 0.02;
  s.shade = shade;
  return s;
}

// The alpha of pixel column c, middle row.
float columnAlpha(const Image& image, int c) {
  return image.pixel(c, image.height / 2)[3];
}

TEST(GradientClassification, ConstantGradientOpacityOfOneLeavesTheImageBitForBit) {
  const StructuredGrid g = squareOfX();
  const Model model = fitStructured(g, StructuredFitOptions{});
  const ModelField field(model);
  for (bool shade : {false, true}) {
    RenderSettings s = frontView(g, shade);
    const Image plain = renderVolume(field, s);
    s.gradientOpacity = {{0.0, 1.0f}, {5.0, 1.0f}};
    const Image gradient = renderVolume(field, s);
    EXPECT_EQ(plain.rgba, gradient.rgba) << "shade " << shade;
  }
}

TEST(GradientClassification, GradientOpacityKeepsTheSteepPartOfTheVolume) {
  const StructuredGrid g = squareOfX();
  const Model model = fitStructured(g, StructuredFitOptions{});
  const ModelField field(model);
  SceneData scene;
  scene.model = &model;
  scene.grid = &g;
  scene.differenceStep = g.spacing;
  RenderSettings s = frontView(g, false);
  // Opaque where |grad f| = 2x > 1 (x > 0.5), transparent below 0.9 (x < 0.45).
  s.gradientOpacity = {{0.9, 0.0f}, {1.0, 1.0f}};
  for (int method = 0; method < 2; ++method) {
    MethodSpec spec;
    spec.method = method == 0 ? ReconstructionMethod::Mfa : ReconstructionMethod::Trilinear;
    const Image image = renderMethod(scene, spec, s);
    for (int c = 0; c < s.width; ++c) {
      const double x = (c + 0.5) / s.width;
      if (x < 0.43) {
        EXPECT_EQ(columnAlpha(image, c), 0.0f) << "method " << method << " x " << x;
      }
      if (x > 0.52) {
        EXPECT_GT(columnAlpha(image, c), 0.5f) << "method " << method << " x " << x;
      }
    }
  }
  // Without it, every column is visible.
  s.gradientOpacity.clear();
  const Image plain = renderVolume(field, s);
  for (int c = 0; c < s.width; ++c) EXPECT_GT(columnAlpha(plain, c), 0.5f);
}

// A 2-D table whose rows all hold the 1-D function's colour and opacity.
TransferFunction2D rowsOf(const TransferFunction& tf, int width, int height) {
  TransferFunction2D t;
  t.width = width;
  t.height = height;
  t.valueLo = 0.0;
  t.valueHi = 1.0;
  t.gradientLo = 0.0;
  t.gradientHi = 3.0;
  t.rgba.resize(size_t(width) * height * 4);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const double v = double(i) / (width - 1);
      const Vec3f c = tf.colorAt(v);
      float* e = &t.rgba[(size_t(j) * width + i) * 4];
      e[0] = c[0];
      e[1] = c[1];
      e[2] = c[2];
      e[3] = tf.opacityAt(v);
    }
  return t;
}

TEST(GradientClassification, TwoDimensionalFunctionOfTheValueAloneMatchesTheOneDimensional) {
  const StructuredGrid g = squareOfX();
  const Model model = fitStructured(g, StructuredFitOptions{});
  const ModelField field(model);
  for (bool shade : {false, true}) {
    RenderSettings s = frontView(g, shade);
    const Image plain = renderVolume(field, s);
    // The 1-D function is linear in the value: a 2-D table reproduces it exactly between its
    // columns, up to rounding.
    s.transferFunction2D = rowsOf(s.transferFunction, 33, 5);
    const Image table = renderVolume(field, s);
    EXPECT_GT(compareImages(toImage8(plain), toImage8(table)).psnr, 50.0) << "shade " << shade;
  }
}

TEST(GradientClassification, TwoDimensionalBoxSelectsValueAndGradient) {
  const StructuredGrid g = squareOfX();
  const Model model = fitStructured(g, StructuredFitOptions{});
  const ModelField field(model);
  RenderSettings s = frontView(g, true);
  // Values 0.09 .. 1 (x > 0.3) and |grad f| 0 .. 1.4 (x < 0.7): the middle band of columns.
  s.transferFunction2D = parseTransferFunction2DJson(
      R"({"boxes": [{"value": [0.09, 1.0], "gradient": [0.0, 1.4], "color": [1, 0, 0],
                     "opacity": 0.8}], "size": [256, 128]})",
      "test");
  const Image image = renderVolume(field, s);
  for (int c = 0; c < s.width; ++c) {
    const double x = (c + 0.5) / s.width;
    const float* p = image.pixel(c, s.height / 2);
    if (x < 0.27 || x > 0.73) {
      EXPECT_EQ(p[3], 0.0f) << "x " << x;
    }
    if (x > 0.33 && x < 0.67) {
      EXPECT_GT(p[3], 0.5f) << "x " << x;
      EXPECT_GT(p[0], 4.0f * (p[1] + p[2])) << "x " << x;  // the box's red
    }
  }
}

TEST(GradientClassification, EnvelopeNeverHidesWhatTheTableShows) {
  // Narrow spikes of opacity in single columns and rows, anywhere in the table.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    TransferFunction2D t;
    t.width = std::min(5 + int(rng() % 6000), 4096);  // also wider than the 1-D table
    t.height = 3 + int(rng() % 20);
    t.valueLo = -2.0;
    t.valueHi = 3.0;
    t.gradientLo = 0.0;
    t.gradientHi = 4.0;
    t.rgba.assign(size_t(t.width) * t.height * 4, 0.0f);
    std::vector<std::pair<float, float>> spikes;  // (value, |g|) of each
    for (int spike = 0; spike < 3; ++spike) {
      const int i = int(rng() % t.width), j = int(rng() % t.height);
      t.rgba[(size_t(j) * t.width + i) * 4 + 3] = 0.5f;
      spikes.push_back({float(-2.0 + 5.0 * i / (t.width - 1)), float(4.0 * j / (t.height - 1))});
    }
    const TransferFunctionTable envelope(t, OpacityCorrection(1.0));
    std::vector<TfEntry> entries(size_t(t.width) * t.height);
    for (size_t e = 0; e < entries.size(); ++e) entries[e].alpha = t.rgba[e * 4 + 3];
    GradientTransferView view;
    view.table = entries.data();
    view.width = t.width;
    view.height = t.height;
    view.valueLo = -2.0f;
    view.valueScale = float((t.width - 1) / 5.0);
    view.gradientScale = float((t.height - 1) / 4.0);
    std::uniform_real_distribution<float> value(-2.5f, 3.5f), gradient(0.0f, 4.5f),
        near(-1.5f, 1.5f);
    int shown = 0;
    for (int k = 0; k < 20000; ++k) {
      // Half the points anywhere, half within 1.5 table cells of a spike.
      float v = value(rng), gm = gradient(rng);
      if (k % 2) {
        const auto& [sv, sg] = spikes[k % spikes.size()];
        v = sv + near(rng) * 5.0f / (t.width - 1);
        gm = std::max(0.0f, sg + near(rng) * 4.0f / (t.height - 1));
      }
      const float g[3] = {gm, 0.0f, 0.0f};
      TfEntry tf{};
      float factor;
      view.apply(v, g, tf, factor);
      if (tf.alpha > 0.0f) {
        ++shown;
        ASSERT_GT(envelope.classify(v).alpha, 0.0f)
            << "trial " << trial << " value " << v << " |g| " << g[0];
      }
    }
    EXPECT_GT(shown, 1000) << "trial " << trial;  // the spikes were met
  }
}

TEST(GradientClassification, BoxFilesAndImagesAreReadAndBadOnesRefused) {
  const TransferFunction2D boxes = parseTransferFunction2DJson(
      R"({"boxes": [{"value": [0, 1], "gradient": [0, 2], "opacity": 0.5},
                    {"value": [0.5, 1], "gradient": [1, 2], "color": [0, 1, 0], "opacity": 1}]})",
      "test");
  EXPECT_EQ(boxes.width, 256);
  EXPECT_EQ(boxes.height, 128);
  EXPECT_LT(boxes.valueLo, 0.0);
  EXPECT_GT(boxes.valueHi, 1.0);
  EXPECT_EQ(boxes.gradientLo, 0.0);
  EXPECT_GT(boxes.gradientHi, 2.0);
  // The corners beyond the boxes are transparent; the second box is over the first.
  EXPECT_EQ(boxes.entry(0, 0)[3], 0.0f);
  EXPECT_EQ(boxes.entry(boxes.width - 1, boxes.height - 1)[3], 0.0f);
  auto entryAt = [&](double v, double gm) {
    const int i =
        int(std::lround((v - boxes.valueLo) / (boxes.valueHi - boxes.valueLo) * (boxes.width - 1)));
    const int j = int(std::lround(gm / boxes.gradientHi * (boxes.height - 1)));
    return boxes.entry(i, j);
  };
  EXPECT_FLOAT_EQ(entryAt(0.25, 0.5)[3], 0.5f);
  EXPECT_FLOAT_EQ(entryAt(0.75, 1.5)[3], 1.0f);
  EXPECT_FLOAT_EQ(entryAt(0.75, 1.5)[0], 0.0f);
  EXPECT_FLOAT_EQ(entryAt(0.75, 0.5)[0], 1.0f);

  for (const char* bad :
       {"[]", "{}", R"({"boxes": []})", R"({"boxes": [{"value": [1, 0], "gradient": [0, 1],
        "opacity": 1}]})",
        R"({"boxes": [{"value": [0, 1], "gradient": [-1, 1], "opacity": 1}]})",
        R"({"boxes": [{"value": [0, 1], "gradient": [0, 1], "opacity": 2}]})",
        R"({"boxes": [{"value": [0, 1], "gradient": [0, 1]}]})",
        R"({"boxes": [{"value": [0, 1], "gradient": [0, 1], "opacity": 1, "color": [1]}]})",
        R"({"boxes": [{"value": [0, 1], "gradient": [0, 1], "opacity": 1}], "size": [2, 99999]})",
        "{\"boxes\": [{\"value\": [0, 1e999]"})
    EXPECT_THROW(parseTransferFunction2DJson(bad, "test"), Error) << bad;

  // An image: its bottom row is the low end of the gradient axis.
  Image8 image;
  image.width = 3;
  image.height = 2;
  image.channels = 4;
  image.data = {255, 0, 0,   255, 255, 0, 0,   255, 255, 0, 0,   255,  // top: red, opaque
                0,   0, 255, 0,   0,   0, 255, 0,   0,   0, 255, 0};   // bottom: blue, clear
  const TransferFunction2D fromImage = transferFunction2DFromImage(image, {0.0, 1.0, 0.0, 2.0});
  EXPECT_EQ(fromImage.entry(1, 0)[2], 1.0f);
  EXPECT_EQ(fromImage.entry(1, 0)[3], 0.0f);
  EXPECT_EQ(fromImage.entry(1, 1)[0], 1.0f);
  EXPECT_EQ(fromImage.entry(1, 1)[3], 1.0f);
  EXPECT_THROW(transferFunction2DFromImage(image, {1.0, 0.0, 0.0, 2.0}), Error);
  EXPECT_THROW(transferFunction2DFromImage(image, {0.0, 1.0, -1.0, 2.0}), Error);
}

TEST(GradientClassification, OtherBlendModesRefuseIt) {
  const StructuredGrid g = squareOfX();
  RenderSettings s = frontView(g, false);
  s.gradientOpacity = {{0.0, 0.0f}, {1.0, 1.0f}};
  s.blend = BlendMode::Maximum;
  EXPECT_THROW(s.validate(), Error);
  s.blend = BlendMode::Composite;
  EXPECT_NO_THROW(s.validate());
  s.gradientOpacity = {{1.0, 0.0f}, {0.5, 1.0f}};  // not sorted
  EXPECT_THROW(s.validate(), Error);
}

}  // namespace
}  // namespace mfadvr
