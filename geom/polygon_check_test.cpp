// point_side: where a point lies against a ring or a polygon with holes, decided exactly on
// the doubles as written (what validate checks street clutter with).
#include <gtest/gtest.h>

#include "geom/polygon_check.h"

namespace geom {
namespace {

TEST(PointSide, InsideOnAndOutsideARingExactly) {
  const Ring square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  EXPECT_EQ(point_side(square, {5, 5}), 1);
  EXPECT_EQ(point_side(square, {10, 5}), 0);
  EXPECT_EQ(point_side(square, {0, 0}), 0);
  EXPECT_EQ(point_side(square, {-1e-300, 5}), -1);  // a hair outside the edge still counts
  EXPECT_EQ(point_side(square, {1e-300, 5}), 1);
  // Near a slanted edge: the doubles 0.1 and 0.3 are not a tenth and three tenths, and three
  // times the double 0.1 is a little more than the double 0.3, so (0.1, 0.3) lies just right
  // of the edge from the origin to (1, 3): outside.
  const Ring slanted{{0, 0}, {1, 3}, {-5, 3}};
  EXPECT_EQ(point_side(slanted, {0.1, 0.3}), -1);
  EXPECT_EQ(point_side(slanted, {0.5, 1.5}), 0);  // exactly on it
}

TEST(PointSide, AHoleIsOutsideItsPolygonAndItsEdgeOnTheBoundary) {
  const Polygon frame{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{3, 3}, {3, 7}, {7, 7}, {7, 3}}}};
  EXPECT_EQ(point_side(frame, {1, 1}), 1);
  EXPECT_EQ(point_side(frame, {5, 5}), -1);
  EXPECT_EQ(point_side(frame, {3, 5}), 0);
  EXPECT_EQ(point_side(frame, {11, 5}), -1);
}

}  // namespace
}  // namespace geom
