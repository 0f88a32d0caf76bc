#include "core/util/PointList.h"

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

TEST(PointList, SeparatorsHeaderCommentsBlankLines) {
  const auto p = parsePointList("x, y, z\n1 2 3\n\n# c\n-1.5,2e-3,+4\r\n  7\t8 ,9\n");
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0], Vec3d(1, 2, 3));
  EXPECT_EQ(p[1], Vec3d(-1.5, 2e-3, 4));
  EXPECT_EQ(p[2], Vec3d(7, 8, 9));
}

TEST(PointList, ErrorsNameTheLine) {
  auto message = [](const char* text) {
    try {
      parsePointList(text, "pts");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message("1 2 3\n1 2\n").find("pts line 2"), std::string::npos);
  EXPECT_NE(message("1 2 3 4\n").find("line 1"), std::string::npos);
  EXPECT_NE(message("1 2 nan\n").find("line 1"), std::string::npos);
  EXPECT_NE(message("1 2 inf\n").find("line 1"), std::string::npos);
  EXPECT_NE(message("x y z\n1 a 3\n").find("line 2"), std::string::npos);
  EXPECT_NE(message("").find("no points"), std::string::npos);
  EXPECT_NE(message("x y z\n").find("no points"), std::string::npos);
}

TEST(PointValueList, ParsesLikeThePointList) {
  const ScatteredData d = parsePointValueList("a b c rho\n1 2 3 4\n-1.5,2e-3,+4,5\n", "s");
  EXPECT_EQ(d.source, "s");
  EXPECT_EQ(d.fieldName, "rho");
  ASSERT_EQ(d.points.size(), 2u);
  EXPECT_EQ(d.points[1], Vec3d(-1.5, 2e-3, 4));
  EXPECT_EQ(d.values, (std::vector<double>{4, 5}));
  test::expectError([] { parsePointValueList("1 2 3\n", "s"); }, {"s line 1"});
  test::expectError([] { parsePointValueList("1 2 3 4 5\n", "s"); }, {"s line 1"});
  test::expectError([] { parsePointValueList("1 2 3 inf\n", "s"); }, {"s line 1", "finite"});
  // A header only counts on the first content line.
  test::expectError([] { parsePointValueList("1 2 3 4\nx y z v\n", "s"); }, {"s line 2"});
}

}  // namespace
}  // namespace mfadvr
