// The slow end-to-end runs (label slow: the test preset runs them, the sanitizer run does
// not, since cli_test already takes every example through the program): every example twice
// for determinism, the CityJSON schemas on three examples, and renders.
#include <gtest/gtest.h>

#include "tests/cli_util.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace cli_util;

namespace {

// Every output file but report.json's timings, which are measurements.
std::map<std::string, std::string> outputs(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::string rel = fs::relative(e.path(), dir).string();
    std::string text = read(e.path());
    if (rel == "report.json") {
      auto j = nlohmann::ordered_json::parse(text);
      j.erase("timings_s");
      text = j.dump();
    }
    files[rel] = text;
  }
  return files;
}

}  // namespace

TEST(Cli, SameSketchGivesByteIdenticalOutputsWhateverTheThreadCount) {
  fs::path base = testing_util::temp_dir("cli-determinism");
  for (const fs::path& sketch : examples()) {
    ASSERT_EQ(run("generate " + sketch.string() + " -o " + (base / "a").string() + " -q --threads 1").code, 0);
    ASSERT_EQ(run("generate " + sketch.string() + " -o " + (base / "b").string() + " -q --threads 2").code, 0);
    auto a = outputs(base / "a"), b = outputs(base / "b");
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [name, text] : a) EXPECT_TRUE(text == b[name]) << sketch << ": " << name << " differs";
  }
}

// Schemas only: cli_test checks every example's solids, indices and templates without them.
TEST(Cli, CityJsonMatchesTheSchemas) {
  const fs::path schemas = cityjson_schemas();
  if (!fs::exists(schemas / "cityjson.schema.json")) GTEST_SKIP() << "no CityJSON schemas at " << schemas;
  for (const char* example : {"tangle", "valley", "hillside"}) {
    fs::path out = testing_util::temp_dir(std::string("cli-cityjson-") + example) / "out";
    ASSERT_EQ(run("generate " + (kSource / "examples" / (std::string(example) + ".geojson")).string() + " -o " +
                  out.string() + " -q").code, 0);
    std::string check = node_tool("check_cityjson.mjs") + " " + (out / "city.city.json").string() + " " + schemas.string();
    EXPECT_EQ(std::system((check + " > /dev/null").c_str()), 0) << check;
  }
}

TEST(Cli, RenderWritesStillOverviewAndMinimapTheSameWhateverTheThreadCount) {
  fs::path base = testing_util::temp_dir("cli-render");
  fs::path out = base / "out";
  Result g = run("generate " + (kSource / "examples" / "hillside.geojson").string() + " -o " + out.string() +
                 " -q --render --size 96x64 --spp 2");
  ASSERT_EQ(g.code, 0) << g.out;
  for (const char* f : {"render/still.png", "render/still.exr", "render/overview.png", "render/minimap.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  auto report = nlohmann::json::parse(read(out / "report.json"));
  ASSERT_TRUE(report.contains("render"));
  EXPECT_GT(report["render"]["tiles"]["count"].get<int>(), 0);
  EXPECT_GT(report["render"]["still"]["camera_rays"].get<long>(), 0);

  const std::string camera = " --camera orbit:target=400,600,40,azimuth=250,elevation=25,distance=500 --size 80x48 --spp 3 --minimap";
  for (int threads : {1, 2}) {
    Result r = run("render " + out.string() + camera + " -q --threads " + std::to_string(threads) + " -o " +
                   (base / ("still" + std::to_string(threads) + ".png")).string());
    ASSERT_EQ(r.code, 0) << r.out;
  }
  EXPECT_TRUE(read(base / "still1.png") == read(base / "still2.png"));
  EXPECT_TRUE(read(base / "still1.exr") == read(base / "still2.exr"));
  EXPECT_TRUE(fs::exists(base / "minimap.png"));
  auto stats = nlohmann::json::parse(read(base / "still1.json"));
  EXPECT_EQ(stats["size"][0], 80);
  EXPECT_GT(stats["tiles"]["culled"].get<int>(), 0) << "a close camera leaves tiles out";

  // Into the folder itself: report.json records the render.
  Result into = run("render " + out.string() + camera + " -q");
  ASSERT_EQ(into.code, 0) << into.out;
  EXPECT_TRUE(fs::exists(out / "render" / "still.json"));
  auto updated = nlohmann::json::parse(read(out / "report.json"));
  EXPECT_EQ(updated["render"]["size"][0], 80);
  EXPECT_EQ(updated["validation"]["ok"], true);

  Result bad = run("render " + out.string() + " --camera orbit:target=1,2 -q");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.out.find("--camera"), std::string::npos) << bad.out;
  EXPECT_EQ(std::count(bad.out.begin(), bad.out.end(), '\n'), 1) << bad.out;
  Result nowhere = run("render " + (base / "missing").string() + " -q");
  EXPECT_EQ(nowhere.code, 2);

  // A sketch's bad camera stops generate --render before anything is written.
  std::ofstream(base / "camera.geojson") << R"({"type": "FeatureCollection", "exacity": {"camera": "orbit:target=0,0"},
    "features": [{"type": "Feature", "properties": {"zone": "park"},
                  "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [50, 0], [50, 50], [0, 0]]]}}]})";
  Result camera_error = run("generate " + (base / "camera.geojson").string() + " -o " + (base / "camera-out").string() + " --render -q");
  EXPECT_EQ(camera_error.code, 2);
  EXPECT_NE(camera_error.out.find("\"exacity\".camera"), std::string::npos) << camera_error.out;
  EXPECT_FALSE(fs::exists(base / "camera-out"));
}
