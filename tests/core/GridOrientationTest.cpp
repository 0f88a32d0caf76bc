// orientToWorld: signed permutations reorder the samples exactly; anything else keeps the grid.
#include <gtest/gtest.h>

#include "core/grid/GridOrientation.h"

namespace mfadvr {
namespace {

StructuredGrid numbered(Index3 dims) {
  StructuredGrid g;
  g.dims = dims;
  g.spacing = Vec3d(1.0, 2.0, 3.0);
  g.values.resize(static_cast<size_t>(g.sampleCount()));
  for (size_t n = 0; n < g.values.size(); ++n) g.values[n] = double(n);
  return g;
}

TEST(GridOrientation, IdentityMovesOnlyTheOrigin) {
  StructuredGrid g = numbered({3, 4, 5});
  const StructuredGrid before = g;
  GridToWorld m;
  m.offset = Vec3d(1, 2, 3);
  const OrientationResult r = orientToWorld(g, m);
  EXPECT_TRUE(r.applied);
  EXPECT_EQ(r.axes, "+x,+y,+z");
  EXPECT_EQ(g.values, before.values);
  EXPECT_EQ(g.origin, Vec3d(1, 2, 3));
}

// Every sample keeps its world position: R * (index * spacing) + t before, origin + index' *
// spacing' after.
TEST(GridOrientation, SignedPermutationKeepsEveryWorldPosition) {
  StructuredGrid g = numbered({3, 4, 5});
  const StructuredGrid before = g;
  GridToWorld m;
  m.linear[0][0] = 0;
  m.linear[1][1] = 0;
  m.linear[2][2] = 0;
  m.linear[2][0] = -1.0;  // i -> -z
  m.linear[0][1] = 0.5;   // j -> +x, half as long
  m.linear[1][2] = 1.0;   // k -> +y
  m.offset = Vec3d(-1, 0, 4);
  const OrientationResult r = orientToWorld(g, m);
  ASSERT_TRUE(r.applied);
  EXPECT_EQ(r.axes, "-z,+x,+y");
  EXPECT_EQ(g.dims, (Index3{4, 5, 3}));
  EXPECT_EQ(g.spacing, Vec3d(1.0, 3.0, 1.0));
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 3; ++i) {
        const Vec3d local(1.0 * i, 2.0 * j, 3.0 * k);
        const Vec3d world(m.offset[0] + 0.5 * local[1], m.offset[1] + local[2],
                          m.offset[2] - local[0]);
        const Vec3d idx = (world - g.origin).cwiseQuotient(g.spacing);
        EXPECT_EQ(g.at(std::lround(idx[0]), std::lround(idx[1]), std::lround(idx[2])),
                  before.at(i, j, k));
      }
}

TEST(GridOrientation, ObliqueOrDegenerateMatricesAreNotApplied) {
  StructuredGrid g = numbered({2, 2, 2});
  const StructuredGrid before = g;
  GridToWorld oblique;
  oblique.linear[0][1] = 0.1;  // j leans towards x
  OrientationResult r = orientToWorld(g, oblique);
  EXPECT_FALSE(r.applied);
  EXPECT_NE(r.note.find("oblique"), std::string::npos);
  EXPECT_EQ(g.values, before.values);

  GridToWorld twice;  // two index axes along world x
  twice.linear[1][1] = 0;
  twice.linear[0][1] = 1;
  g = before;
  EXPECT_FALSE(orientToWorld(g, twice).applied);
}

}  // namespace
}  // namespace mfadvr
