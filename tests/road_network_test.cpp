// The grown road network and its blocks, end to end through the stages.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include "generate/sketch/sketch.h"
#include "generate/parcels/blocks.h"
#include "generate/layout/road_network.h"
#include "generate/export/vector_layers.h"
#include "generate/city/city_map.h"
#include "tests/test_util.h"

using namespace exacity;

namespace {

std::string sketch_with(const std::string& zones, const std::string& settings = "{}") {
  return R"({"type": "FeatureCollection", "exacity": )" + settings + R"(, "features": [)" + zones + "]}";
}

std::string zone(const std::string& type, double x0, double y0, double x1, double y1) {
  auto p = [](double x, double y) { return "[" + std::to_string(x) + "," + std::to_string(y) + "]"; };
  return R"({"type": "Feature", "properties": {"zone": ")" + type + R"("}, "geometry": {"type": "Polygon", "coordinates": [[)" +
         p(x0, y0) + "," + p(x1, y0) + "," + p(x1, y1) + "," + p(x0, y1) + "," + p(x0, y0) + "]]}}";
}

struct City {
  Sketch sketch;
  RoadNetwork network;
  std::vector<Block> blocks;
};

City grow(const std::string& text) {
  City c;
  c.sketch = parse_sketch(text, "test.geojson");
  c.network = grow_road_network(build_city_map(c.sketch, c.sketch, nullptr), c.sketch, c.sketch.zones);
  c.blocks = cut_blocks(c.network.map, c.sketch, c.sketch.zones);
  return c;
}

std::vector<const MapRoad*> grown_roads(const City& c) {
  std::vector<const MapRoad*> r;
  for (const MapRoad& road : c.network.map.roads)
    if (road.level >= 0) r.push_back(&road);
  return r;
}

}  // namespace

TEST(RoadNetwork, ManhattanZonesHaveOnlyStraightRoads) {
  City c = grow(sketch_with(zone("commercial", 0, 0, 800, 600) + "," + zone("industrial", 800, 0, 1500, 600)));
  auto roads = grown_roads(c);
  ASSERT_GT(roads.size(), 10u);
  for (const MapRoad* r : roads) EXPECT_TRUE(r->lines[0].is_straight());
}

TEST(RoadNetwork, ResidentialRoadsBendAndStraightenWithDepth) {
  City c = grow(sketch_with(zone("residential", 0, 0, 1200, 900)));
  int bent_at_top = 0, bent_deep = 0;
  for (const MapRoad* r : grown_roads(c)) {
    bool bent = !r->lines[0].is_straight();
    if (r->level == 0) bent_at_top += bent;
    if (r->level >= 4) bent_deep += bent;  // Δsegm = max(8 - 2n, 0) is 0 from level 4 on
  }
  EXPECT_GT(bent_at_top, 0);
  EXPECT_EQ(bent_deep, 0);
  EXPECT_EQ(c.network.stats.regions, 1);
  EXPECT_GT(c.network.stats.levels, 1);
}

TEST(RoadNetwork, BlocksTileTheZoneWithTheRoads) {
  City c = grow(sketch_with(zone("residential", 0, 0, 600, 400)));
  CityLayers l = extract_layers(c.network.map, c.blocks, {}, {}, {}, c.sketch.zones);
  double blocks = 0, roads_inside = 0;
  for (const auto& f : l.blocks.features) blocks += testing_util::area(f.polygon);
  for (const auto& f : l.zones.features) roads_inside -= testing_util::area(f.polygon);
  // Blocks are exactly the zone less its road surface.
  EXPECT_NEAR(blocks, -roads_inside, 1e-6);
  EXPECT_LT(blocks, 600 * 400);
  EXPECT_GT(blocks, 0.6 * 600 * 400);
  for (const Block& b : c.blocks) EXPECT_FALSE(b.roads.empty() && !b.green) << "a block fronting no road";
  for (const Block& b : c.blocks)
    if (!b.green) {
      EXPECT_GE(testing_util::area(b.polygon), c.sketch.zone_settings.at(ZoneType::Residential).blocks.min_block_area);
    }
}

TEST(RoadNetwork, SmallZonesAreOneBlockAndTinyOnesGreen) {
  // Below block_area no roads grow; a highway cutting off a corner leaves a sliver that
  // becomes green space.
  std::string highway =
      R"({"type": "Feature", "properties": {"road": "highway", "width": 4}, "geometry": {"type": "LineString", "coordinates": [[-10, 15], [15, -10]]}})";
  City c = grow(sketch_with(zone("residential", 0, 0, 90, 90) + "," + highway));
  EXPECT_TRUE(grown_roads(c).empty());
  ASSERT_EQ(c.blocks.size(), 2u);
  int green = 0;
  for (const Block& b : c.blocks) {
    green += b.green;
    EXPECT_EQ(b.roads, std::vector<int>{0});  // both front the highway
  }
  EXPECT_EQ(green, 1);
}

TEST(RoadNetwork, ParksAndWaterGetNoRoads) {
  City c = grow(sketch_with(zone("park", 0, 0, 1000, 1000) + "," + zone("water", 1000, 0, 2000, 1000)));
  EXPECT_TRUE(grown_roads(c).empty());
  EXPECT_TRUE(c.blocks.empty());
}

TEST(RoadNetwork, GrownRoadsBridgeOnlyWhereTheZoneAllowsThem) {
  auto bridged = [&](bool allow) {
    TerrainSpec spec;
    spec.bounds = {0, 0, 1000, 1000};
    std::vector<float> v(100, 1.0f);
    for (int r = 0; r < 10; ++r) v[r * 10 + 5] = 0;  // a river down column 5
    Terrain t(spec, 10, 10, v);
    Sketch s = parse_sketch(
        sketch_with(zone("residential", 0, 0, 1000, 1000),
                    std::string(R"({"zones": {"residential": {"bridges": )") + (allow ? "true" : "false") + "}}}"),
        "test.geojson");
    RoadNetwork n = grow_road_network(build_city_map(s, s, &t), s, s.zones);
    std::pair<int, int> bridges;  // faces bridged by grown roads, by links
    for (const FaceLabel& l : n.map.labels)
      if (l.bridge) ++(n.map.roads[l.road].link ? bridges.second : bridges.first);
    EXPECT_EQ(n.stats.links, allow ? 0 : 1);
    return bridges;
  };
  // Without bridges the river parts two regions, and the one link joining them crosses it.
  EXPECT_EQ(bridged(false).first, 0);
  EXPECT_GT(bridged(false).second, 0);
  EXPECT_GT(bridged(true).first, 0);
  EXPECT_EQ(bridged(true).second, 0);
}

TEST(RoadNetwork, SameResultWithOneOrTwoThreads) {
  auto layers = [](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    City c = grow(sketch_with(zone("residential", 0, 0, 1500, 1000) + "," + zone("commercial", 1500, 0, 2500, 1000)));
    CityLayers l = extract_layers(c.network.map, c.blocks, {}, {}, {}, c.sketch.zones);
    std::string all;
    for (const Layer* layer : {&l.roads, &l.road_areas, &l.blocks})
      for (const auto& f : layer->features) {
        all += f.properties.dump();
        for (auto p : f.line) all += std::to_string(p.x) + "," + std::to_string(p.y) + ";";
        for (auto p : f.polygon.outer) all += std::to_string(p.x) + "," + std::to_string(p.y) + ";";
      }
    return all;
  };
  EXPECT_EQ(layers(1), layers(2));
}

TEST(RoadNetwork, UtmSizedCoordinatesGiveTheSameTopology) {
  auto run = [](double dx, double dy) {
    City c = grow(sketch_with(zone("residential", dx, dy, dx + 900, dy + 700) + "," +
                              zone("industrial", dx + 900, dy, dx + 1400, dy + 500)));
    auto counts = c.network.map.map.counts();
    return std::vector<std::size_t>{counts.vertices, counts.edges, counts.faces, c.network.map.roads.size(),
                                    c.blocks.size()};
  };
  EXPECT_EQ(run(0, 0), run(500000, 5000000));
}
