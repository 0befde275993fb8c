// Regenerating after an edit (generate/regenerate.h): the city built with the cache of the
// city before is the city a full build of the edited sketch makes, byte for byte.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "generate/export/geojson.h"
#include "generate/export/svg_map.h"
#include "generate/export/clutter_layer.h"
#include "generate/errors.h"
#include "generate/pipeline.h"
#include "generate/regenerate.h"
#include "tests/test_util.h"

using namespace exacity;
using nlohmann::json;

namespace {

json ring(double x0, double y0, double x1, double y1) {
  return json::array({json::array({x0, y0}), json::array({x1, y0}), json::array({x1, y1}), json::array({x0, y1}),
                      json::array({x0, y0})});
}

json zone(const std::string& type, json outer) {
  return {{"type", "Feature"},
          {"properties", {{"zone", type}}},
          {"geometry", {{"type", "Polygon"}, {"coordinates", json::array({std::move(outer)})}}}};
}

// Three columns of zones in two rows between main roads, so that most regions are apart:
// an edit of one zone leaves the others' regions as they were. The middle of the lower row
// is two zones side by side (one region of growth), and there is a park and a pond.
json town() {
  json features = json::array();
  const char* types[2][3] = {{"residential", "commercial", "industrial"}, {"industrial", "residential", "commercial"}};
  for (int row = 0; row < 2; ++row)
    for (int column = 0; column < 3; ++column) {
      const double x = column * 260.0, y = row * 220.0;
      if (row == 0 && column == 1) {
        features.push_back(zone("residential", ring(x, y, x + 110, y + 200)));
        features.push_back(zone("commercial", ring(x + 110, y, x + 240, y + 200)));
      } else {
        features.push_back(zone(types[row][column], ring(x, y, x + 240, y + 200)));
      }
    }
  features.push_back(zone("park", ring(540, 260, 600, 320)));
  features.push_back(zone("water", ring(40, 40, 90, 80)));
  auto road = [](double x0, double y0, double x1, double y1) {
    return json{{"type", "Feature"},
                {"properties", {{"road", "main"}, {"width", 12}}},
                {"geometry", {{"type", "LineString"}, {"coordinates", json::array({json::array({x0, y0}), json::array({x1, y1})})}}}};
  };
  features.push_back(road(-30, 210, 800, 210));
  features.push_back(road(250, -30, 250, 450));
  features.push_back(road(510, -30, 510, 450));
  return {{"type", "FeatureCollection"},
          {"exacity", {{"seed", 3}, {"zones", {{"residential", {{"block_area", 6000}}}, {"commercial", {{"block_area", 6000}}},
                                              {"industrial", {{"block_area", 8000}}}}}}},
          {"features", features}};
}

// A random edit of one zone: a corner moved, its type changed, a zone added, or one removed
// (while more than five are left).
json edited(json sketch, std::mt19937& random) {
  json& features = sketch["features"];
  std::vector<std::size_t> zones;
  for (std::size_t i = 0; i < features.size(); ++i)
    if (features[i]["properties"].contains("zone")) zones.push_back(i);
  json& chosen = features[zones[random() % zones.size()]];
  const char* types[] = {"residential", "commercial", "industrial", "park"};
  switch (random() % (zones.size() > 5 ? 4 : 3)) {
    case 0: {  // a corner moved; the ring's first and last points stay one
      json& outer = chosen["geometry"]["coordinates"][0];
      const std::size_t corner = random() % (outer.size() - 1);
      std::uniform_real_distribution<double> step(-25, 25);
      for (int axis : {0, 1}) outer[corner][axis] = outer[corner][axis].get<double>() + std::round(step(random));
      if (corner == 0) outer[outer.size() - 1] = outer[0];
      break;
    }
    case 1: {
      const std::string now = chosen["properties"]["zone"];
      std::string next = now;
      while (next == now) next = types[random() % 4];
      chosen["properties"]["zone"] = next;
      break;
    }
    case 2: {
      std::uniform_real_distribution<double> at(0, 700);
      const double x = std::round(at(random)), y = std::round(at(random) * 0.55);
      features.push_back(zone(types[random() % 4], ring(x, y, x + 90, y + 70)));
      break;
    }
    default:
      features.erase(zones[random() % zones.size()]);
  }
  return sketch;
}

// The city's layers, clutter and map as written, one text.
std::string written(const City& city, const std::string& name) {
  const auto dir = testing_util::temp_dir(name);
  std::string all;
  auto read = [&](const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    all += file.filename().string() + "\n" + text.str();
  };
  for (const Layer* l : {&city.layers.zones, &city.layers.water, &city.layers.roads, &city.layers.road_areas,
                         &city.layers.blocks, &city.layers.lots, &city.layers.buildings}) {
    write_geojson(*l, city.settings.crs, dir / (l->name + ".geojson"));
    read(dir / (l->name + ".geojson"));
  }
  write_point_geojson(clutter_layer(city.clutter.items, city.model_library()), city.settings.crs, dir / "clutter.geojson");
  read(dir / "clutter.geojson");
  write_svg_map(city.ground, city.buildings, city.models, dir / "map.svg", city.clutter.items);
  read(dir / "map.svg");
  return all;
}

City build(const json& sketch, std::shared_ptr<RegionCache> cache = {}) {
  StageClock clock(nullptr, kCityStages);
  return build_city(parse_sketch(sketch.dump(), "town.geojson"), clock, std::move(cache));
}

City regenerated(const City& previous, const json& sketch) {
  StageClock clock(nullptr, kCityStages);
  return regenerate(previous, parse_sketch(sketch.dump(), "town.geojson"), clock);
}

}  // namespace

TEST(Regenerate, UnchangedSketchReusesEveryRegionBlockAndLot) {
  const City first = build(town(), std::make_shared<RegionCache>());
  const City again = regenerated(first, town());
  EXPECT_GT(again.regions->road_plans.hits(), 0);
  EXPECT_EQ(again.regions->road_plans.misses(), 0);
  EXPECT_EQ(again.regions->lot_plans.misses(), 0);
  EXPECT_EQ(again.regions->placements.misses(), 0);
  EXPECT_EQ(written(again, "again"), written(first, "first"));
}

TEST(Regenerate, RandomEditsGiveTheFullBuildsCity) {
  std::mt19937 random(11);
  json sketch = town();
  City previous = build(sketch, std::make_shared<RegionCache>());
  int reused = 0;
  for (int edit = 0; edit < 12; ++edit) {
    json next = edited(sketch, random);
    City city;
    try {
      city = regenerated(previous, next);
    } catch (const UserError&) {
      EXPECT_THROW(build(next), UserError);  // an edit the reader refuses is refused by a full build too
      continue;
    }
    reused += city.regions->hits();
    EXPECT_EQ(written(city, "regenerated"), written(build(next), "full")) << "edit " << edit << ": " << next.dump();
    sketch = std::move(next);
    previous = std::move(city);
  }
  // Not every edit reaches every region: some were reused.
  EXPECT_GT(reused, 0);
}
