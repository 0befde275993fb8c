// The junctions of the noded centre lines: which nodes are junctions, their arms in order,
// and which junctions get traffic lights and which stop signs.
#include "generate/placement/street_nodes.h"

#include <gtest/gtest.h>

namespace exacity {
namespace {

RoadLine line(RoadClass c, geom::Polyline points) {
  return {c, c == RoadClass::Local ? 8.0 : 12.0, -1, -1, false, std::move(points), -1, {}};
}

TEST(StreetNodes, ACrossingOfMainRoadsHasLightsAndALocalRoadMeetingOneHasSigns) {
  const std::vector<RoadLine> roads{
      line(RoadClass::Main, {{-100, 0}, {0, 0}, {50, 0}, {100, 0}}),  // passes the local road's end at (50, 0)
      line(RoadClass::Main, {{0, -100}, {0, 0}}),
      line(RoadClass::Highway, {{0, 0}, {0, 100}}),  // carries the north-south road on
      line(RoadClass::Local, {{50, 0}, {50, 80}}),
      line(RoadClass::Local, {{100, 0}, {100, 50}}),  // meets the main road's end: a bend, no junction
  };
  const std::vector<StreetJunction> junctions = street_junctions(roads);
  ASSERT_EQ(junctions.size(), 2u);
  const StreetJunction &cross = junctions[0], &tee = junctions[1];
  EXPECT_EQ(cross.at, (geom::Vec2{0, 0}));
  ASSERT_EQ(cross.arms.size(), 4u);
  EXPECT_TRUE(cross.of_major_roads());
  EXPECT_FALSE(cross.local_meets_major());
  EXPECT_DOUBLE_EQ(cross.reach(), 6);
  // Counter-clockwise by angle, from just past west (atan2 gives west +pi): south, east, north, west.
  EXPECT_EQ(cross.arms[0].toward, (geom::Vec2{0, -1}));
  EXPECT_EQ(cross.arms[1].toward, (geom::Vec2{1, 0}));
  EXPECT_EQ(cross.arms[2].road, 2);
  EXPECT_EQ(cross.arms[3].toward, (geom::Vec2{-1, 0}));
  EXPECT_EQ(tee.at, (geom::Vec2{50, 0}));
  EXPECT_EQ(tee.major_arms(), 2);
  EXPECT_FALSE(tee.of_major_roads());
  EXPECT_TRUE(tee.local_meets_major());
}

TEST(StreetNodes, LocalRoadsMeetingEachOtherGetNeither) {
  const std::vector<RoadLine> roads{line(RoadClass::Local, {{-50, 0}, {0, 0}, {50, 0}}),
                                    line(RoadClass::Local, {{0, 0}, {0, 40}})};
  const std::vector<StreetJunction> junctions = street_junctions(roads);
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_FALSE(junctions[0].of_major_roads());
  EXPECT_FALSE(junctions[0].local_meets_major());
}

}  // namespace
}  // namespace exacity
