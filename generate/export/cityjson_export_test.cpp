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

// Every vertex index of a geometry's boundaries, resolved to its [x, y, z].
json resolved(const json& b, const json& vertices) {
  if (b.is_number()) return vertices[b.get<std::size_t>()];
  json out = json::array();
  for (const json& x : b) out.push_back(resolved(x, vertices));
  return out;
}

// Each object's geometries with their indices resolved.
json resolved_object(json object, const json& vertices) {
  for (json& g : object["geometry"])
    if (g.contains("boundaries")) g["boundaries"] = resolved(g["boundaries"], vertices);
  return object;
}

// A row of 2,500 buildings wall to wall, more than one piece of objects holds: the pieces
// are made apart and their vertices numbered in each, and the document still stores each
// vertex once (those of the walls between pieces too), every object's surfaces where the
// sequence's feature has them.
TEST(CityJson, ObjectsMadeInPiecesShareOneVertexList) {
  Ground ground;
  ZoneArea zone;
  zone.type = ZoneType::Residential, zone.stable_id = 1;
  const int n = 2500;
  zone.polygon.outer = {{-1, -1}, {n + 1.0, -1}, {n + 1.0, 2}, {-1, 2}};
  ground.zones.push_back(zone);
  std::vector<Building> buildings(n);
  for (int k = 0; k < n; ++k) {
    Building& b = buildings[static_cast<std::size_t>(k)];
    b.id = k, b.stable_id = k + 1;
    b.polygon.outer = {{double(k), 0}, {k + 1.0, 0}, {k + 1.0, 1}, {double(k), 1}};
    b.height = b.eaves = 3 + k % 4;
  }
  const std::vector<Mesh> meshes = structure_meshes(buildings, {}, nullptr);
  const std::vector<GroundLayer> layers = ground_layers(ground, nullptr);
  const nlohmann::ordered_json crs = nlohmann::ordered_json::object();
  const auto dir = testing_util::temp_dir("cityjson_pieces");
  write_cityjson({ground, layers, buildings, {}, meshes, {}, nullptr, nullptr, crs}, dir / "city.city.json",
                 dir / "city.city.jsonl");
  const json city = json::parse(std::ifstream(dir / "city.city.json"));
  const json& vertices = city["vertices"];
  std::set<json> distinct(vertices.begin(), vertices.end());
  EXPECT_EQ(distinct.size(), vertices.size()) << "a vertex stored twice";

  std::ifstream lines(dir / "city.city.jsonl");
  std::string line;
  std::getline(lines, line);  // what the features share
  std::set<json> in_features;
  std::size_t features = 0;
  while (std::getline(lines, line)) {
    const json feature = json::parse(line);
    ++features;
    for (const json& v : feature["vertices"]) in_features.insert(v);
    for (const auto& [key, object] : feature["CityObjects"].items())
      ASSERT_EQ(resolved_object(object, feature["vertices"]), resolved_object(city["CityObjects"][key], vertices))
          << key;
  }
  EXPECT_EQ(features, city["CityObjects"].size());
  EXPECT_EQ(in_features, distinct);
  EXPECT_TRUE(city["CityObjects"].contains("building-2500"));
}

}  // namespace
}  // namespace exacity
