// The few vector operations geom/plain.h gives doubles, and the edge normal every stage
// shares.
#include "geom/plain.h"

#include <gtest/gtest.h>

namespace geom {
namespace {

TEST(Plain, VectorOperators) {
  const Vec2 a{1, 2}, b{4, -2};
  EXPECT_EQ(a + b, (Vec2{5, 0}));
  EXPECT_EQ(a - b, (Vec2{-3, 4}));
  EXPECT_EQ(a * 2, (Vec2{2, 4}));
  EXPECT_EQ(dot(a, b), 0);
  EXPECT_EQ(cross(a, b), -10);
}

TEST(Plain, UnitAndNormalOfAnEdge) {
  EXPECT_EQ(unit_along({1, 1}, {4, 5}), (Vec2{0.6, 0.8}));
  EXPECT_EQ(unit(Vec2{3, 4}), (Vec2{3 * (1.0 / 5), 4 * (1.0 / 5)}));
  // Into the inside of a counter-clockwise ring, on every edge of a square.
  const Ring square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const Vec2 inward[] = {{0, 1}, {-1, 0}, {0, -1}, {1, 0}};
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec2 n = left_normal(square[i], square[(i + 1) % 4]);
    EXPECT_EQ(n.x, inward[i].x) << i;
    EXPECT_EQ(n.y, inward[i].y) << i;
  }
  // An edge of no length has neither.
  EXPECT_EQ(unit_along({2, 3}, {2, 3}), (Vec2{0, 0}));
  EXPECT_EQ(left_normal({2, 3}, {2, 3}), (Vec2{0, 0}));
}

}  // namespace
}  // namespace geom
