// The adaptive encoder's bound on real data (skipped when ../shared/data is absent).
#include <gtest/gtest.h>

#include <cmath>

#include "TestSupport.h"
#include "core/encode/AdaptiveEncoder.h"
#include "io/VolumeLoader.h"

namespace mfadvr {
namespace {

TEST(AdaptiveRealData, BoundHoldsOnFuel) {
  const auto path = test::dataFile("fuel_64x64x64_uint8.raw");
  if (path.empty()) GTEST_SKIP() << "fuel_64x64x64_uint8.raw not present";
  const StructuredGrid grid = loadStructuredVolume(path.string());
  std::int64_t previous = 0;
  for (double e : {5e-2, 1e-2}) {
    AdaptiveOptions o;
    o.maxRelativeError = e;
    FitReport r;
    const Model m = fitStructuredAdaptive(grid, StructuredFitOptions{}, o, &r);
    EXPECT_TRUE(r.reachedTarget) << r.stopReason;
    // Checked here at every sample, independently of the encoder's own report.
    double worst = 0.0;
    for (std::int64_t k = 0; k < grid.dims[2]; ++k)
      for (std::int64_t j = 0; j < grid.dims[1]; ++j)
        for (std::int64_t i = 0; i < grid.dims[0]; ++i)
          worst =
              std::max(worst, std::abs(double(m.value(grid.position(i, j, k))) - grid.at(i, j, k)));
    EXPECT_LE(worst, e * r.valueRange() * (1 + 1e-9)) << "E=" << e;
    const Index3 n = m.spline().counts();
    EXPECT_GT(n[0] * n[1] * n[2], previous) << "E=" << e;
    previous = n[0] * n[1] * n[2];
  }
}

}  // namespace
}  // namespace mfadvr
