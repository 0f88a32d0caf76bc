// MSE, PSNR and SSIM against hand-computed values, closed forms and a direct (non-separable)
// implementation of the SSIM definition.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "TestSupport.h"
#include "core/image/ImageMetrics.h"

namespace mfadvr {
namespace {

constexpr double kC1 = 6.5025;   // (0.01 * 255)^2
constexpr double kC2 = 58.5225;  // (0.03 * 255)^2

Image8 make(int w, int h, int channels, const std::vector<std::uint8_t>& data) {
  return Image8{w, h, channels, data};
}

Image8 constant(int w, int h, std::uint8_t v) {
  return make(w, h, 3, std::vector<std::uint8_t>(3 * static_cast<size_t>(w) * h, v));
}

// A smooth colour pattern with structure for SSIM to see.
Image8 pattern(int w, int h) {
  Image8 im = constant(w, h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        im.data[3 * (static_cast<size_t>(y) * w + x) + c] = static_cast<std::uint8_t>(
            127.5 + 100 * std::sin(0.3 * x + 0.7 * c) * std::cos(0.2 * y - 0.4 * c));
  return im;
}

Image8 withNoise(const Image8& im, int amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(-amplitude, amplitude);
  Image8 out = im;
  for (auto& v : out.data) v = static_cast<std::uint8_t>(std::clamp(v + d(rng), 0, 255));
  return out;
}

// SSIM of one channel straight from the definition: the 2-D 11x11 window (clipped to the image
// along short sides), weights exp(-(dx^2 + dy^2) / (2 * 1.5^2)) normalized, every valid position.
double directSsim(const Image8& a, const Image8& b, int c) {
  const int nx = std::min(11, a.width), ny = std::min(11, a.height);
  std::vector<double> w(nx * ny);
  double sum = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double dx = i - 0.5 * (nx - 1), dy = j - 0.5 * (ny - 1);
      sum += w[j * nx + i] = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
    }
  double total = 0;
  int count = 0;
  for (int y0 = 0; y0 + ny <= a.height; ++y0)
    for (int x0 = 0; x0 + nx <= a.width; ++x0) {
      double mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
          const size_t p = static_cast<size_t>(y0 + j) * a.width + x0 + i;
          const double wt = w[j * nx + i] / sum, x = a.data[p * a.channels + c],
                       y = b.data[p * b.channels + c];
          mx += wt * x, my += wt * y, sxx += wt * x * x, syy += wt * y * y, sxy += wt * x * y;
        }
      const double vx = sxx - mx * mx, vy = syy - my * my, cxy = sxy - mx * my;
      total +=
          (2 * mx * my + kC1) * (2 * cxy + kC2) / ((mx * mx + my * my + kC1) * (vx + vy + kC2));
      ++count;
    }
  return total / count;
}

TEST(ImageMetrics, ImageWithItselfIsPerfect) {
  const Image8 im = withNoise(pattern(40, 30), 30, 1);
  const ImageComparison r = compareImages(im, im);
  EXPECT_EQ(r.mse, 0.0);
  EXPECT_TRUE(std::isinf(r.psnr) && r.psnr > 0);
  EXPECT_NEAR(r.ssim, 1.0, 1e-12);
  for (const auto& c : r.channel) {
    EXPECT_EQ(c.mse, 0.0);
    EXPECT_TRUE(std::isinf(c.psnr));
    EXPECT_NEAR(c.ssim, 1.0, 1e-12);
  }
}

TEST(ImageMetrics, MseAndPsnrOfAHandComputedPair) {
  // Three pixels. Differences: R 0, 3, 5 -> MSE_R = (0 + 9 + 25) / 3 = 34/3;
  // G none -> 0; B 0, 4, 0 -> 16/3 (the alpha of b is ignored).
  // Mean MSE = (34/3 + 0 + 16/3) / 3 = 50/9; PSNR = 10 log10(255^2 * 9 / 50) = 40.683528659...
  // PSNR_R = 10 log10(65025 * 3 / 34) = 37.587226985..., PSNR_B = 10 log10(65025 * 3 / 16)
  // = 40.860816329...
  const Image8 a = make(3, 1, 3, {0, 0, 0, 10, 20, 30, 255, 255, 255});
  const Image8 b = make(3, 1, 4, {0, 0, 0, 9, 13, 20, 26, 99, 250, 255, 255, 0});
  const ImageComparison r = compareImages(a, b);
  EXPECT_DOUBLE_EQ(r.channel[0].mse, 34.0 / 3);
  EXPECT_EQ(r.channel[1].mse, 0.0);
  EXPECT_DOUBLE_EQ(r.channel[2].mse, 16.0 / 3);
  EXPECT_DOUBLE_EQ(r.mse, 50.0 / 9);
  EXPECT_NEAR(r.psnr, 40.68352865971217, 1e-12);
  EXPECT_NEAR(r.channel[0].psnr, 37.58722698545318, 1e-12);
  EXPECT_TRUE(std::isinf(r.channel[1].psnr));
  EXPECT_NEAR(r.channel[2].psnr, 40.86081632931648, 1e-12);
  EXPECT_NEAR(psnrFromMse(255.0 * 255.0), 0.0, 1e-15);
}

TEST(ImageMetrics, SsimOfConstantImagesHasTheClosedForm) {
  // All variances and the covariance vanish, leaving (2 mu1 mu2 + C1) / (mu1^2 + mu2^2 + C1).
  // 20x20 uses the full window; 7x4 the clipped one; 1x1 the degenerate single pixel.
  for (auto [w, h] : {std::pair{20, 20}, std::pair{7, 4}, std::pair{1, 1}})
    for (auto [m1, m2] : {std::pair{100, 130}, std::pair{0, 255}, std::pair{200, 201}}) {
      const double expected = (2.0 * m1 * m2 + kC1) / (1.0 * m1 * m1 + 1.0 * m2 * m2 + kC1);
      const ImageComparison r = compareImages(constant(w, h, m1), constant(w, h, m2));
      EXPECT_NEAR(r.ssim, expected, 1e-10) << w << "x" << h << " " << m1 << " " << m2;
      EXPECT_DOUBLE_EQ(r.mse, (m1 - m2) * (m1 - m2));
    }
  EXPECT_NEAR(compareImages(constant(20, 20, 100), constant(20, 20, 130)).ssim, 0.9665508365496407,
              1e-10);
}

TEST(ImageMetrics, SsimMatchesTheDirectDefinition) {
  const Image8 a = pattern(31, 26), b = withNoise(a, 40, 3);
  const ImageComparison r = compareImages(a, b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.channel[c].ssim, directSsim(a, b, c), 1e-12) << c;
  EXPECT_NEAR(r.ssim, (r.channel[0].ssim + r.channel[1].ssim + r.channel[2].ssim) / 3, 1e-15);
  // Small images: clipped window along one side or both.
  for (auto [w, h] : {std::pair{31, 6}, std::pair{5, 17}, std::pair{9, 3}}) {
    const Image8 sa = pattern(w, h), sb = withNoise(sa, 25, 4);
    const ImageComparison s = compareImages(sa, sb);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(s.channel[c].ssim, directSsim(sa, sb, c), 1e-12) << w << "x" << h;
  }
}

TEST(ImageMetrics, SsimIsSymmetricAndFallsWithNoise) {
  const Image8 clean = pattern(64, 48);
  double previous = 1.0;
  for (int amplitude : {2, 8, 20, 50, 100}) {
    const Image8 noisy = withNoise(clean, amplitude, 11);
    const ImageComparison ab = compareImages(clean, noisy), ba = compareImages(noisy, clean);
    EXPECT_NEAR(ab.ssim, ba.ssim, 1e-14);
    EXPECT_EQ(ab.mse, ba.mse);
    EXPECT_LT(ab.ssim, previous) << amplitude;
    EXPECT_GT(ab.ssim, -1.0);
    previous = ab.ssim;
  }
  EXPECT_LT(previous, 0.5);
}

TEST(ImageMetrics, SizeMismatchIsAnError) {
  test::expectError([] { compareImages(constant(4, 4, 0), constant(4, 5, 0)); },
                    {"differ in size", "4 x 4", "4 x 5"});
  test::expectError([] { differenceImage(constant(3, 4, 0), constant(4, 4, 0)); },
                    {"differ in size"});
}

TEST(ImageMetrics, DifferenceImageScalesAndClamps) {
  const Image8 a = make(2, 1, 4, {10, 20, 30, 0, 200, 0, 255, 255});
  const Image8 b = make(2, 1, 3, {13, 10, 30, 0, 100, 254});
  const Image8 d1 = differenceImage(a, b);
  EXPECT_EQ(d1.channels, 3);
  EXPECT_EQ(d1.data, (std::vector<std::uint8_t>{3, 10, 0, 200, 100, 1}));
  const Image8 d = differenceImage(a, b, 2.5);
  // 7.5 rounds to 8; 500 and 250 clamp or not.
  EXPECT_EQ(d.data, (std::vector<std::uint8_t>{8, 25, 0, 255, 250, 3}));
  test::expectError([&] { differenceImage(a, b, -1); }, {"gain"});
  test::expectError([&] { differenceImage(a, b, INFINITY); }, {"gain"});
}

TEST(ImageMetrics, OneMegapixelImagesCompare) {
  // Speed is measured by the benchmarks, not here; this checks a full-size comparison works.
  const Image8 a = pattern(1000, 1000), b = withNoise(a, 10, 5);
  const ImageComparison r = compareImages(a, b);
  EXPECT_GT(r.ssim, 0.5);
  EXPECT_LT(r.ssim, 1.0);
  EXPECT_GT(r.mse, 0.0);
}

}  // namespace
}  // namespace mfadvr
