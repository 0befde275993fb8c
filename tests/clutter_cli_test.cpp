// Street clutter through the exacity program: the same bytes whatever the thread
// count, and the outputs that hold it pass the independent checks (GEOS on clutter.geojson,
// the Khronos glTF validator, the CityJSON checker), which also catch clutter misplaced;
// Exacity's own trees and lamps pass them too, and a bad "builtin_models" is refused.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/cityjson_seq.h"
#include "tests/cli_util.h"
#include "tests/clutter_sketch.h"

namespace fs = std::filesystem;
using namespace cli_util;
using namespace clutter_sketch;

TEST(ClutterCli, SameBytesWithOneThreadOrTwo) {
  const fs::path sketch =
      four_streets("cli-threads", R"(, "roads": {"local": {"sidewalk": 2.5}})", all_of_the_library());
  const fs::path dir = sketch.parent_path();
  ASSERT_EQ(run("generate " + sketch.string() + " -o " + (dir / "a").string() + " -q --threads 1").code, 0);
  ASSERT_EQ(run("generate " + sketch.string() + " -o " + (dir / "b").string() + " -q --threads 2").code, 0);
  for (const char* file : {"vector/clutter.geojson", "city.glb", "city.city.json"}) {
    const std::string a = read(dir / "a" / file);
    EXPECT_GT(a.size(), 100u) << file;
    EXPECT_TRUE(a == read(dir / "b" / file)) << file << " differs";
  }
  const auto report = nlohmann::json::parse(read(dir / "a" / "report.json"));
  EXPECT_GT(report["counts"]["clutter"].get<int>(), 20);
  // Four junctions: each has its light, or the report says why not (the lots' draw decides
  // whether a corner has a sidewalk or lot).
  int lights = report["clutter"]["placed"].value("traffic_light", 0);
  for (const auto& n : report["clutter"]["not_placed"])
    if (n["kind"] == "traffic_light") lights += n["spots"].get<int>();
  EXPECT_EQ(lights, 4) << report["clutter"];
  EXPECT_GT(report["clutter"]["placed"].value("traffic_light", 0), 0) << report["clutter"];
}

TEST(ClutterCli, TheIndependentCheckersPassTheClutterAndGeosCatchesItMisplaced) {
  const fs::path sketch = four_streets("cli-checkers", "", all_of_the_library());
  const fs::path out = sketch.parent_path() / "out";
  Result g = run("generate " + sketch.string() + " -o " + out.string() + " -q --cityjson-seq");
  ASSERT_EQ(g.code, 0) << g.out;
  // CityJSONSeq holds the same objects, placed models and clutter among them.
  cityjson_seq::expect_same_city_objects(out / "city.city.json", out / "city.city.jsonl");
  Result geos = shell(geos_check(out));
  EXPECT_EQ(geos.code, 0) << geos.out;
  Result glb = shell(node_tool("check_glb.mjs") + " " + (out / "city.glb").string());
  EXPECT_EQ(glb.code, 0) << glb.out;
  Result cityjson = shell(node_tool("check_cityjson.mjs") + " " + (out / "city.city.json").string());
  EXPECT_EQ(cityjson.code, 0) << cityjson.out;
  const auto doc = nlohmann::json::parse(read(out / "city.city.json"));
  int furniture = 0;
  for (const auto& [id, object] : doc["CityObjects"].items())
    if (id.rfind("clutter-", 0) == 0) {
      ++furniture;
      EXPECT_EQ(object["type"], "CityFurniture") << id;
      EXPECT_EQ(object["geometry"][0]["type"], "GeometryInstance") << id;
    }
  EXPECT_EQ(furniture, nlohmann::json::parse(read(out / "report.json"))["counts"]["clutter"].get<int>());

  // A lamp moved onto the east-west road's carriageway: GEOS and validate both object.
  const fs::path layer = out / "vector" / "clutter.geojson";
  auto clutter = nlohmann::ordered_json::parse(read(layer));
  clutter["features"][0]["geometry"]["coordinates"] = {-150.5, 0.25};
  std::ofstream(layer, std::ios::binary) << clutter.dump();
  geos = shell(geos_check(out));
  EXPECT_EQ(geos.code, 1) << geos.out;
  EXPECT_NE(geos.out.find("clutter[0]"), std::string::npos) << geos.out;
  Result v = run("validate " + out.string());
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("clutter.geojson features[0]"), std::string::npos) << v.out;
}

TEST(ClutterCli, TheRendersDrawEachPieceAsAnInstance) {
  // No building in the library: the lots get extruded buildings, so every instance in the
  // scene is a piece of clutter.
  const fs::path sketch = four_streets("cli-render", "", std::string(kLamp) + "," + kSign + "," + kLight);
  const fs::path out = sketch.parent_path() / "out";
  Result g = run("generate " + sketch.string() + " -o " + out.string() + " -q --render --size 32x20 --spp 1");
  ASSERT_EQ(g.code, 0) << g.out;
  const auto report = nlohmann::json::parse(read(out / "report.json"));
  const int clutter = report["counts"]["clutter"].get<int>();
  EXPECT_GT(clutter, 20);
  EXPECT_EQ(report["render"]["scene"]["instances"].get<int>(), clutter) << report["render"]["scene"];
}

TEST(ClutterCli, ExacitysOwnTreesAndLampsPassTheCheckersAndABadChoiceIsOneLine) {
  // No library: a residential square with a park, Exacity's own trees and lamps by default.
  const fs::path dir = testing_util::temp_dir("clutter-cli-builtin");
  const std::string features = R"("features": [
      {"type": "Feature", "properties": {"zone": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 260], [0, 260], [0, 0]]]}},
      {"type": "Feature", "properties": {"zone": "park"},
       "geometry": {"type": "Polygon", "coordinates": [[[100, 80], [190, 80], [190, 170], [100, 170], [100, 80]]]}}]})";
  write(dir / "park.geojson", R"({"type": "FeatureCollection", "exacity": {"seed": 4}, )" + features);
  Result g = run("generate " + (dir / "park.geojson").string() + " -o " + (dir / "out").string() + " -q");
  ASSERT_EQ(g.code, 0) << g.out;
  const auto clutter = nlohmann::json::parse(read(dir / "out" / "vector" / "clutter.geojson"))["features"];
  int park_trees = 0, lamps = 0;
  for (const auto& f : clutter) {
    park_trees += f["properties"]["road"].is_null();
    lamps += f["properties"]["kind"] == "lamp";
  }
  EXPECT_GT(park_trees, 5);
  EXPECT_GT(lamps, 5);
  const Result geos = shell(geos_check(dir / "out"));
  EXPECT_EQ(geos.code, 0) << geos.out;
  const Result glb = shell(node_tool("check_glb.mjs") + " " + (dir / "out" / "city.glb").string());
  EXPECT_EQ(glb.code, 0) << glb.out;

  // A kind Exacity has no model of: one line, exit 2, nothing written.
  write(dir / "bad.geojson",
        R"({"type": "FeatureCollection", "exacity": {"seed": 4, "builtin_models": ["tree", "bench"]}, )" + features);
  Result bad = run("generate " + (dir / "bad.geojson").string() + " -o " + (dir / "bad").string() + " -q");
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_EQ(std::count(bad.out.begin(), bad.out.end(), '\n'), 1) << bad.out;
  EXPECT_NE(bad.out.find("\"exacity\".builtin_models: \"bench\" is not a built-in model"), std::string::npos)
      << bad.out;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

TEST(ClutterCli, ParksWhoseTreesWouldBeMoreThanOneRunPlantsAreOneLineBeforeAnyIsPlaced) {
  // A park of 6 by 6 km would get about 111,000 of Exacity's own trees (one to a square of
  // 18 m): past the 100,000 one run plants. A strip 1 m wide from (0, 0) to (1000 km,
  // 1000 km) would plant only 3,000, but its box is three billion squares to walk.
  const fs::path dir = testing_util::temp_dir("clutter-cli-park-limit");
  auto park = [](const std::string& ring) {
    return R"({"type": "FeatureCollection", "exacity": {"seed": 4}, "features": [
      {"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [)" +
           ring + "]}}]}";
  };
  write(dir / "wide.geojson", park("[[0, 0], [6000, 0], [6000, 6000], [0, 6000], [0, 0]]"));
  write(dir / "strip.geojson", park("[[0, 0], [1, 0], [1000001, 1000000], [1000000, 1000000], [0, 0]]"));
  const std::pair<std::string, std::string> refusals[] = {
      {"wide", "would plant about 111111 trees, more than the 100000 one run plants"},
      {"strip", "span about 3086469136 squares of a tree in their boxes, more than the 100000000 one run walks"}};
  for (const auto& [sketch, what] : refusals) {
    const fs::path out = dir / (sketch + "-out");
    Result r = shell("timeout 60 " + std::string(EXACITY_BINARY) + " generate " + (dir / (sketch + ".geojson")).string() +
                     " -o " + out.string() + " -q --threads 1");
    EXPECT_EQ(r.code, 2) << sketch << ": " << r.out;
    EXPECT_NE(r.out.find("features[0] (park): the parks "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(what), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"spacing\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"exacity\".builtin_models"), std::string::npos) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_FALSE(fs::exists(out)) << sketch;
  }
}
