// city_statistics measured on layers small enough to count by hand.
#include "generate/export/statistics.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace exacity;
using nlohmann::ordered_json;

TEST(Statistics, MeasureFootprintsAndStreetsByHand) {
  CityLayers layers;
  Layer &buildings = layers.buildings, &roads = layers.roads;
  // A 10 x 4 rectangle (4 m across) and a triangle with a 20 degree corner.
  buildings.features.push_back({{{"zone", "residential"}}, {{{0, 0}, {10, 0}, {10, 4}, {0, 4}}, {}}, {}});
  const double t = std::tan(20 * M_PI / 180);
  buildings.features.push_back({{{"zone", "residential"}}, {{{0, 0}, {100, 0}, {100, 100 * t}}, {}}, {}});
  // A T junction of three lines, one of which ends in the open.
  roads.features.push_back({{}, {}, {{0, 0}, {100, 0}}});
  roads.features.push_back({{}, {}, {{100, 0}, {200, 0}}});
  roads.features.push_back({{}, {}, {{100, 0}, {100, 100}}});
  ordered_json s = city_statistics(layers, nullptr);
  const auto& f = s["zones"]["residential"]["footprints"];
  EXPECT_EQ(f["share_under_5m_across"].get<double>(), 0.5);
  EXPECT_EQ(f["share_sharp_angle"].get<double>(), 0.5);
  EXPECT_EQ(f["area_m2"]["max"].get<double>(), std::round(100 * 100 * t / 2 * 10) / 10);
  const auto& streets = s["streets"];
  EXPECT_EQ(streets["junctions_by_degree"]["3"].get<int>(), 1);
  EXPECT_EQ(streets["junctions_by_degree"]["1"].get<int>(), 3);
  EXPECT_EQ(streets["length_km"].get<double>(), 0.3);
  // With no drawn zones every end lies outside the city, so none is a dead end.
  EXPECT_EQ(streets["dead_ends"].get<int>(), 0);
}

// Each zone counts its own blocks, lots and footprints, and "all" counts every one once:
// green blocks are left out, a lot is built on when a building names it, and a lot fronts a
// road where one of its edges is a road area's.
TEST(Statistics, CountEachZonesBlocksLotsAndFootprintsAndAllOnce) {
  CityLayers layers;
  auto square = [](double x, double y, double side) {
    return geom::Polygon{{{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}}, {}};
  };
  layers.blocks.features.push_back({{{"zone", "residential"}}, square(0, 0, 10), {}});
  layers.blocks.features.push_back({{{"zone", "commercial"}}, square(20, 0, 20), {}});
  layers.blocks.features.push_back({{{"zone", "residential"}, {"green", true}}, square(0, 20, 30), {}});
  layers.lots.features.push_back({{{"zone", "residential"}, {"id", 1}}, square(0, 0, 5), {}});
  layers.lots.features.push_back({{{"zone", "residential"}, {"id", 2}}, square(5, 0, 5), {}});
  layers.lots.features.push_back({{{"zone", "commercial"}, {"id", 3}}, square(20, 0, 20), {}});
  layers.buildings.features.push_back({{{"zone", "residential"}, {"lot", 2}}, square(6, 1, 3), {}});
  layers.buildings.features.push_back({{{"zone", "residential"}, {"lot", 1}, {"kind", "tree"}}, square(1, 1, 1), {}});
  layers.buildings.features.push_back({{{"zone", "commercial"}, {"lot", 3}}, square(22, 2, 10), {}});
  // A road area whose edge is the first lot's bottom edge (drawn the other way).
  layers.road_areas.features.push_back({{}, {{{5, 0}, {0, 0}, {0, -4}, {5, -4}}, {}}, {}});
  const ordered_json s = city_statistics(layers, nullptr);
  const auto& zones = s["zones"];
  ASSERT_EQ(zones.size(), 3u);
  const auto& residential = zones["residential"];
  EXPECT_EQ(residential["blocks"]["area_m2"]["count"].get<int>(), 1);
  EXPECT_EQ(residential["blocks"]["area_m2"]["max"].get<double>(), 100);
  EXPECT_EQ(residential["lots"]["area_m2"]["count"].get<int>(), 2);
  EXPECT_EQ(residential["lots"]["share_without_building"].get<double>(), 0.5);  // the tree builds nothing
  EXPECT_EQ(residential["lots"]["share_touching_road"].get<double>(), 0.5);
  EXPECT_EQ(residential["footprints"]["area_m2"]["count"].get<int>(), 1);
  EXPECT_EQ(zones["commercial"]["lots"]["share_without_building"].get<double>(), 0);
  EXPECT_EQ(zones["commercial"]["footprints"]["area_m2"]["max"].get<double>(), 100);
  const auto& all = zones["all"];
  EXPECT_EQ(all["blocks"]["area_m2"]["count"].get<int>(), 2);
  EXPECT_EQ(all["blocks"]["area_m2"]["max"].get<double>(), 400);
  EXPECT_EQ(all["lots"]["area_m2"]["count"].get<int>(), 3);
  EXPECT_EQ(all["lots"]["share_without_building"].get<double>(), std::round(1e4 / 3) / 1e4);
  EXPECT_EQ(all["lots"]["share_touching_road"].get<double>(), std::round(1e4 / 3) / 1e4);
  EXPECT_EQ(all["footprints"]["area_m2"]["count"].get<int>(), 2);
  EXPECT_EQ(all["footprints"]["area_m2"]["median"].get<double>(), 9);
}
