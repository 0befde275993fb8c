// The robustness benchmark's judge: it accepts a small good output folder and rejects each
// way of breaking it, by kind.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "benchmarks/judge.h"
#include "tests/test_util.h"

namespace {

using nlohmann::json;

json box(double x0, double y0, double x1, double y1) {
  return {{"type", "Polygon"}, {"coordinates", {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}}}};
}
json line(std::vector<std::pair<double, double>> points) {
  json c = json::array();
  for (auto [x, y] : points) c.push_back({x, y});
  return {{"type", "LineString"}, {"coordinates", c}};
}
json feature(json geometry, json properties) { return {{"type", "Feature"}, {"properties", properties}, {"geometry", geometry}}; }

// A zone drawn as one square, written as two blocks either side of a road, a lot in each,
// a building in the first.
std::map<std::string, json> good_city() {
  auto collection = [](std::vector<json> features) { return json{{"type", "FeatureCollection"}, {"features", features}}; };
  return {
      {"sketch", collection({feature(box(0, 0, 100, 100), {{"zone", "residential"}})})},
      {"zones", collection({feature(box(0, 0, 45, 100), {{"id", 0}, {"zone", "residential"}}),
                            feature(box(55, 0, 100, 100), {{"id", 1}, {"zone", "residential"}})})},
      {"water", collection({})},
      {"road_areas", collection({feature(box(45, 0, 55, 100), {{"id", 0}, {"road", 0}})})},
      {"blocks", collection({feature(box(0, 0, 45, 100), {{"id", 0}}), feature(box(55, 0, 100, 100), {{"id", 1}})})},
      {"lots", collection({feature(box(0, 0, 45, 50), {{"id", 0}, {"block", 0}}),
                           feature(box(55, 0, 100, 50), {{"id", 1}, {"block", 1}})})},
      {"buildings", collection({feature(box(10, 10, 20, 20), {{"id", 0}, {"lot", 0}})})},
      {"roads", collection({feature(line({{50, 0}, {50, 50}}), {{"id", 0}}), feature(line({{50, 50}, {50, 100}}), {{"id", 1}})})},
  };
}

std::map<std::string, int> judged(const std::string& name, const std::function<void(std::map<std::string, json>&)>& edit) {
  auto city = good_city();
  edit(city);
  auto dir = testing_util::temp_dir("judge-" + name);
  std::filesystem::create_directories(dir / "vector");
  for (const auto& [layer, doc] : city)
    std::ofstream(layer == "sketch" ? dir / "sketch.geojson" : dir / "vector" / (layer + ".geojson")) << doc.dump();
  return exacity::bench::judge(dir).rejected;
}

using Kinds = std::map<std::string, int>;

}  // namespace

TEST(Judge, AcceptsAGoodCity) { EXPECT_EQ(judged("good", [](auto&) {}), Kinds{}); }

TEST(Judge, RejectsOverlappingLots) {
  EXPECT_EQ(judged("overlap", [](auto& c) { c["lots"]["features"].push_back(feature(box(0, 40, 45, 60), {{"id", 2}, {"block", 0}})); }),
            (Kinds{{"overlap", 1}}));
}

TEST(Judge, RejectsAGapInTheDrawnZones) {
  EXPECT_EQ(judged("gap", [](auto& c) { c["zones"]["features"].erase(1); }), (Kinds{{"gap", 1}}));
}

TEST(Judge, RejectsAnInvalidRing) {
  EXPECT_EQ(judged("invalid",
                   [](auto& c) {
                     c["lots"]["features"][0]["geometry"]["coordinates"] = {{{0, 0}, {45, 50}, {45, 0}, {0, 50}, {0, 0}}};
                   }),
            (Kinds{{"invalid", 1}}));
}

TEST(Judge, RejectsABuildingOutsideItsLot) {
  EXPECT_EQ(judged("outside", [](auto& c) { c["buildings"]["features"][0]["geometry"] = box(40, 40, 44, 60); }),
            (Kinds{{"outside", 1}}));
}

TEST(Judge, RejectsADisconnectedOrCrossingNetwork) {
  EXPECT_EQ(judged("apart", [](auto& c) { c["roads"]["features"].push_back(feature(line({{10, 90}, {20, 90}}), {{"id", 2}})); }),
            (Kinds{{"network", 1}}));
  // Roads the sketch drew need not meet: a second drawn road apart from the first is no fault.
  EXPECT_EQ(judged("drawn-apart",
                   [](auto& c) {
                     for (auto& f : c["roads"]["features"]) f["properties"]["level"] = nullptr;
                     c["roads"]["features"].push_back(feature(line({{10, 90}, {20, 90}}), {{"id", 2}, {"level", nullptr}}));
                   }),
            Kinds{});
  EXPECT_EQ(judged("cross", [](auto& c) { c["roads"]["features"].push_back(feature(line({{50, 50}, {60, 40}, {40, 30}}), {{"id", 2}})); }),
            (Kinds{{"network", 1}}));
}

// A vertex moved across an edge keeps the zones a tiling that covers the sketch: only the
// zones' types show that a face is on the wrong side.
TEST(Judge, RejectsAZoneWrittenOnTheWrongSideOfAnEdge) {
  auto split_zone = [](auto& c, double shared_y) {
    c["sketch"]["features"].push_back(feature(box(55, 50, 100, 100), {{"zone", "commercial"}}));
    c["zones"]["features"][1] = feature(json{{"type", "Polygon"}, {"coordinates", {{{55, 0}, {100, 0}, {100, 50}, {55, shared_y}, {55, 0}}}}},
                                        {{"id", 1}, {"zone", "residential"}});
    c["zones"]["features"].push_back(
        feature(json{{"type", "Polygon"}, {"coordinates", {{{55, shared_y}, {100, 50}, {100, 100}, {55, 100}, {55, shared_y}}}}},
                {{"id", 2}, {"zone", "commercial"}}));
  };
  EXPECT_EQ(judged("sides", [&](auto& c) { split_zone(c, 50); }), Kinds{});
  EXPECT_EQ(judged("vertex-across", [&](auto& c) { split_zone(c, 50.001); }), (Kinds{{"label", 1}}));
  EXPECT_EQ(judged("relabelled", [](auto& c) { c["zones"]["features"][1]["properties"]["zone"] = "commercial"; }),
            (Kinds{{"label", 1}}));
}
