#include "generate/export/cityjson_export.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "tests/test_util.h"

namespace exacity {
namespace {

using nlohmann::json;

// Every ring of every geometry, as vertex indices.
void collect_rings(const json& b, std::vector<std::vector<int>>& out) {
  if (b.is_array() && !b.empty() && b[0].is_number())
    out.push_back(b.get<std::vector<int>>());
  else if (b.is_array())
    for (const json& x : b) collect_rings(x, out);
}

// A land use polygon of two squares joined by a neck 0.4 mm wide, and a road area of two
// triangles whose tips are 0.3 mm apart: on the millimetre grid the first runs along one
// edge both ways and the second touches itself at a point. CityJSON's rings must be simple:
// each is cut into simple rings that cover what it covered, none passing a vertex twice.
TEST(CityJson, RingsThatQuantisingMakesTouchAreCutIntoSimpleOnes) {
  Ground ground;
  ZoneArea zone;
  zone.type = ZoneType::Commercial, zone.stable_id = 1;
  zone.polygon.outer = {{0, 0},   {10, 0},  {10, 4.9998}, {20, 4.9998}, {20, 0},  {30, 0},
                        {30, 10}, {20, 10}, {20, 5.0002}, {10, 5.0002}, {10, 10}, {0, 10}};
  ground.zones.push_back(zone);
  RoadArea road;
  road.polygon.outer = {{40, 0}, {50, 10}, {60, 0}, {60, 20}, {50, 10.0003}, {40, 20}};
  ground.road_areas.push_back(road);
  const auto file = testing_util::temp_dir("cityjson_pinch") / "city.city.json";
  const std::vector<GroundLayer> layers = ground_layers(ground, nullptr);
  const nlohmann::ordered_json crs = nlohmann::ordered_json::object();
  write_cityjson({ground, layers, {}, {}, {}, {}, nullptr, nullptr, crs}, file);
  const json city = json::parse(std::ifstream(file));
  const json& vertices = city["vertices"];
  std::map<std::string, double> area2;  // twice each object's area, in square millimetres
  for (const auto& [key, object] : city["CityObjects"].items()) {
    std::vector<std::vector<int>> rings;
    for (const json& g : object["geometry"]) collect_rings(g["boundaries"], rings);
    ASSERT_FALSE(rings.empty()) << key;
    for (const auto& r : rings) {
      EXPECT_GE(r.size(), 3u) << key;
      std::set<std::vector<long long>> points;
      for (int i : r) points.insert(vertices[i].get<std::vector<long long>>());
      EXPECT_EQ(points.size(), r.size()) << key << ": a ring passes a vertex twice";
      for (std::size_t k = 0; key != "terrain" && k < r.size(); ++k) {
        const json &a = vertices[r[k]], &b = vertices[r[(k + 1) % r.size()]];
        area2[key] += a[0].get<double>() * b[1].get<double>() - b[0].get<double>() * a[1].get<double>();
      }
    }
  }
  // Two squares of 10 m, and two triangles of 100 m²: the neck has gone.
  EXPECT_EQ(area2, (std::map<std::string, double>{{"landuse-0", 4e8}, {"road-null", 4e8}}));
}

}  // namespace
}  // namespace exacity
