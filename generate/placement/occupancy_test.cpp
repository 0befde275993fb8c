// Occupancy: the exact "is this place free" test every placer shares, and the frontage
// rows run along.
#include "generate/placement/occupancy.h"

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace exacity {
namespace {

// A 40 x 20 lot whose south edge (edge 0) fronts a road: kind 1 there, 0 elsewhere.
geom::Cell fronted_lot() { return testing_util::fronted_cell({{0, 0}, {40, 0}, {40, 20}, {0, 20}}, {0}); }

geom::Ring square(double x, double y, double side) { return {{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}}; }

TEST(Occupancy, TakesAFreePlaceOnceAndRefusesWhatOverlapsIt) {
  const geom::Cell lot = fronted_lot();
  Occupancy occupancy(lot, 1);
  EXPECT_TRUE(occupancy.take(square(5, 5, 8)));
  EXPECT_FALSE(occupancy.free(square(5, 5, 8)));     // taken
  EXPECT_FALSE(occupancy.take(square(10, 10, 8)));   // overlaps it
  EXPECT_FALSE(occupancy.take(square(13, 5, 8)));    // shares its east edge
  EXPECT_TRUE(occupancy.take(square(13.5, 5, 8)));   // half a metre apart
  EXPECT_TRUE(occupancy.inside(square(10, 10, 8)));  // inside the lot, whatever stands there
}

TEST(Occupancy, RefusesRingsOutsideTouchingTheEdgeOrClockwise) {
  const geom::Cell lot = fronted_lot();
  Occupancy occupancy(lot, 1);
  EXPECT_FALSE(occupancy.free(square(35, 5, 8)));  // past the east edge
  EXPECT_FALSE(occupancy.free(square(0, 5, 8)));   // on the west edge: touching leaves it
  geom::Ring clockwise = square(5, 5, 8);
  std::swap(clockwise[1], clockwise[3]);
  EXPECT_FALSE(occupancy.free(clockwise));
  EXPECT_FALSE(occupancy.take(clockwise));
  EXPECT_TRUE(occupancy.take(square(5, 5, 8)));  // nothing was taken by the refusals
}

TEST(Occupancy, FrontageRunsAlongTheRoadEdgeWithTheLotOnItsLeft) {
  const geom::Cell lot = fronted_lot();
  const Occupancy on_road(lot, 1);
  const Frontage& f = on_road.frontage();
  EXPECT_TRUE(f.on_road);
  EXPECT_EQ(f.u.x, 1);
  EXPECT_EQ(f.u.y, 0);
  EXPECT_EQ(f.n.x, 0);
  EXPECT_EQ(f.n.y, 1);
  EXPECT_EQ(f.t1 - f.t0, 40);
  EXPECT_EQ(f.depth, 20);
  // With no road edge of that kind: the longest edge, and on_road false.
  const Occupancy off_road(lot, 7);
  const Frontage& none = off_road.frontage();
  EXPECT_FALSE(none.on_road);
  EXPECT_EQ(none.t1 - none.t0, 40);
}

}  // namespace
}  // namespace exacity
