// Bilinear magnification of interactive frames: exact on linear ramps, identity at equal size,
// no blocks (neighbouring output pixels differ where the source does).
#include "core/image/ImageResize.h"

#include <gtest/gtest.h>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

TEST(ImageResize, ReproducesALinearRampAtPixelCentres) {
  Image small(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 4; ++c) small.pixel(x, y)[c] = 0.1f * x + 0.2f * y + 0.01f * c;
  const Image big = resizeBilinear(small, 16, 12);
  // Output pixel x maps to source (x + 0.5) / 4 - 0.5; inside the source's span the ramp holds.
  for (int y = 2; y < 10; ++y)
    for (int x = 2; x < 14; ++x) {
      const double sx = (x + 0.5) / 4.0 - 0.5, sy = (y + 0.5) / 4.0 - 0.5;
      EXPECT_NEAR(big.pixel(x, y)[0], 0.1 * sx + 0.2 * sy, 1e-5);
    }
  // Borders clamp to the edge pixels.
  EXPECT_NEAR(big.pixel(0, 0)[0], small.pixel(0, 0)[0], 1e-6);
  EXPECT_NEAR(big.pixel(15, 11)[3], small.pixel(3, 2)[3], 1e-6);
  // Smooth, not blocky: a ramp along x changes between every pair of interior neighbours.
  for (int x = 2; x < 13; ++x) EXPECT_LT(big.pixel(x, 5)[0], big.pixel(x + 1, 5)[0]);
}

TEST(ImageResize, SameSizeIsACopyAndBadSourcesAreRefused) {
  Image a(5, 4);
  a.pixel(2, 3)[1] = 0.7f;
  EXPECT_EQ(resizeBilinear(a, 5, 4).rgba, a.rgba);
  EXPECT_THROW(resizeBilinear(Image(), 4, 4), Error);
  EXPECT_THROW(resizeBilinear(a, 0, 4), Error);
}

}  // namespace
}  // namespace mfadvr
