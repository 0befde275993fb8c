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
