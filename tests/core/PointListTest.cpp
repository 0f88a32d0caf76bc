#include "core/util/PointList.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace mfadvr
