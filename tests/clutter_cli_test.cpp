// Seed 004's street clutter through the exacity program: the same bytes whatever the thread
// count, and the outputs that hold it pass the independent checks (GEOS on clutter.geojson,
// the Khronos glTF validator, the CityJSON checker), which also catch clutter misplaced.
#include <gtest/gtest.h>

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
  EXPECT_EQ(report["clutter"]["placed"]["traffic_light"], 4) << report["clutter"];
}

TEST(ClutterCli, TheIndependentCheckersPassTheClutterAndGeosCatchesItMisplaced) {
  const fs::path sketch = four_streets("cli-checkers", "", all_of_the_library());
  const fs::path out = sketch.parent_path() / "out";
  Result g = run("generate " + sketch.string() + " -o " + out.string() + " -q");
  ASSERT_EQ(g.code, 0) << g.out;
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
