// The city map's counter ranges, the only source of its winding counters, and per_label.
#include "generate/city/city_map.h"

#include <gtest/gtest.h>

#include "generate/sketch/sketch.h"

namespace exacity {
namespace {

TEST(CounterRange, NamesItsCountersAndNoOthers) {
  const CounterRange r{7, 3};
  EXPECT_EQ(r.at(0), 7);
  EXPECT_EQ(r.at(2), 9);
  EXPECT_EQ(r.end(), 10);
  EXPECT_FALSE(r.holds(6));
  EXPECT_TRUE(r.holds(7));
  EXPECT_TRUE(r.holds(9));
  EXPECT_FALSE(r.holds(10));
  EXPECT_EQ(r.index_of(8), 1);
  EXPECT_FALSE(CounterRange{}.holds(0));  // an empty range holds nothing
}

TEST(CityMap, RangesFollowEachOtherWithoutOverlapAndRoadsFindTheirCounters) {
  const std::string text = R"({"type": "FeatureCollection", "exacity": {"roads": {"main": {"sidewalk": 2}}}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [100, 0], [100, 100], [0, 100], [0, 0]]]}},
    {"type": "Feature", "properties": {"road": "main", "width": 10},
     "geometry": {"type": "LineString", "coordinates": [[-20, 50], [120, 50]]}},
    {"type": "Feature", "properties": {"road": "main", "width": 10},
     "geometry": {"type": "LineString", "coordinates": [[50, -20], [50, 50]]}}]})";
  const Sketch sketch = parse_sketch(text, "ranges.geojson");
  const CityMap map = build_city_map(sketch, sketch, nullptr);
  EXPECT_EQ(map.heightmap_water.first, 0);
  EXPECT_EQ(map.sketch_carriageways.first, map.heightmap_water.end());
  EXPECT_EQ(map.sketch_carriageways.size, 2);
  EXPECT_GT(map.sidewalks.first, map.sketch_carriageways.end());  // the drawn zones' rings lie between
  EXPECT_EQ(map.sidewalks.size, 2);
  EXPECT_EQ(map.junctions.first, map.sidewalks.end());
  EXPECT_EQ(map.junctions.size, 1);  // the T where the two roads meet, mitred
  EXPECT_EQ(map.generated_roads.first, map.junctions.end());
  EXPECT_EQ(map.generated_roads.size, 0);
  for (int r = 0; r < 2; ++r) EXPECT_EQ(map.road_of_counter(map.road_counter(r)), r);
  EXPECT_EQ(map.road_of_counter(map.sidewalks.at(0)), -1);
  EXPECT_EQ(map.road_of_counter(map.junctions.at(0)), -1);
  // per_label: one value per face label, in label order.
  const std::vector<int> zone = map.per_label([](const FaceLabel& l) { return l.zone; });
  ASSERT_EQ(zone.size(), map.labels.size());
  for (std::size_t i = 0; i < zone.size(); ++i) EXPECT_EQ(zone[i], map.labels[i].zone);
}

}  // namespace
}  // namespace exacity
