// `exacity bench scale`: the tiled sketches and the run that measures them.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "benchmarks/scale.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

using nlohmann::json;

namespace {

const char* kSketch = R"({"type": "FeatureCollection", "exacity": {"seed": 5}, "features": [
  {"type": "Feature", "properties": {"zone": "residential", "name": "square"},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [160, 0], [160, 120], [0, 120], [0, 0]]]}},
  {"type": "Feature", "properties": {"road": "main"},
   "geometry": {"type": "LineString", "coordinates": [[-20, 60], [180, 60]]}}]})";

std::filesystem::path write_sketch(const std::string& name) {
  const std::filesystem::path dir = testing_util::temp_dir(name);
  std::ofstream(dir / "sketch.geojson") << kSketch;
  return dir;
}

}  // namespace

// Size 4 is the sketch 2 x 2: each copy moved by the bounding box (200 x 120 m) and a 60 m gap.
TEST(ScaleBenchmark, TilesTheSketchSideBySide) {
  const std::filesystem::path dir = write_sketch("scale_tiles");
  const json tiled = json::parse(exacity::bench::tiled_sketch(dir / "sketch.geojson", 4));
  ASSERT_EQ(tiled["features"].size(), 8u);
  const json& last_zone = tiled["features"][6];
  EXPECT_EQ(last_zone["properties"]["name"], "square (1,1)");
  EXPECT_EQ(last_zone["geometry"]["coordinates"][0][2], json::array({160.0 + 260, 120.0 + 180}));
  EXPECT_EQ(tiled["features"][7]["geometry"]["coordinates"][0], json::array({-20.0 + 260, 60.0 + 180}));
  EXPECT_EQ(tiled["exacity"]["seed"], 5);
  EXPECT_EQ(json::parse(exacity::bench::tiled_sketch(dir / "sketch.geojson", 1)), json::parse(kSketch));
  EXPECT_THROW(exacity::bench::tiled_sketch(dir / "sketch.geojson", 3), std::runtime_error);
}

TEST(ScaleBenchmark, MeasuresEachSizeAndEveryStage) {
  const std::filesystem::path dir = write_sketch("scale_run");
  const cli_util::Result r = cli_util::run("bench scale " + (dir / "sketch.geojson").string() +
                                           " --sizes 1,4 --threads 1 -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream in(dir / "out" / "scale.json");
  const json scale = json::parse(in);
  ASSERT_EQ(scale["sizes"].size(), 2u);
  const json &one = scale["sizes"][0], &four = scale["sizes"][1];
  EXPECT_GT(one["buildings"].get<double>(), 0);
  EXPECT_GT(four["buildings"].get<double>(), 2 * one["buildings"].get<double>());
  EXPECT_GE(four["peak_mib"].get<double>(), four["stage_peak_mib"]["validation"].get<double>());
  for (const char* stage : {"road network", "lots", "buildings", "3d export", "validation"}) {
    EXPECT_TRUE(four["stage_s"].contains(stage)) << stage;
    EXPECT_GT(four["stage_peak_mib"].value(stage, 0.0), 0) << stage;
  }
  EXPECT_NE(r.out.find("| 4 |"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "scale.svg"));
  EXPECT_EQ(cli_util::run("bench scale " + (dir / "sketch.geojson").string() + " --sizes 2").code, 2);
}

// A size the sketch reader refuses stops the benchmark with the reader's own line.
TEST(ScaleBenchmark, ASizeTheReaderRefusesSaysWhy) {
  const std::filesystem::path dir = testing_util::temp_dir("scale_refused");
  std::ofstream(dir / "vast.geojson")
      << R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"zone": "residential"},
           "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1e6, 0], [1e6, 1e6], [0, 0]]]}}]})";
  const cli_util::Result r = cli_util::run("bench scale " + (dir / "vast.geojson").string() + " --sizes 1 -o " +
                                           (dir / "out").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("more than the 60000 one run builds"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("failed (" + (dir / "out" / "sketch-1.geojson").string() +
                       ": features[0]: the zones would make about 41666666 blocks"), std::string::npos) << r.out;
}
