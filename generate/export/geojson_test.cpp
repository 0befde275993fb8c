// Reading a layer back for validation: feature by feature, each malformed one named and
// skipped, a document that is no FeatureCollection refused whole.
#include "generate/export/geojson.h"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/test_util.h"

namespace exacity {
namespace {

Layer read_text(const std::string& name, const std::string& text, std::vector<std::string>& problems) {
  const std::filesystem::path file = testing_util::temp_dir("geojson_read") / (name + ".geojson");
  std::ofstream(file) << text;
  return read_geojson(file, problems);
}

TEST(GeoJsonRead, MalformedFeaturesAreNamedAndSkippedTheRestKept) {
  std::vector<std::string> problems;
  const Layer lots = read_text("lots", R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "x"}},
    "features": [
      7,
      {"type": "Feature", "properties": {"id": 1, "zone": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [4, 0], [4, 3], [0, 0]]]}},
      {"type": "Feature", "properties": {"id": 2}, "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [4, 0], [4, 3]]]}},
      [1, 2],
      {"type": "Feature", "properties": {"id": 3}, "geometry": {"type": "Circle", "coordinates": []}},
      {"type": "Feature", "properties": {"id": 4}, "geometry": {"type": "Point", "coordinates": [5, 6]}}]})",
                               problems);
  ASSERT_EQ(lots.features.size(), 2u);
  EXPECT_EQ(lots.features[0].properties["id"], 1);
  EXPECT_EQ(lots.features[0].properties["zone"], "residential");
  EXPECT_EQ(lots.features[0].polygon.outer, (geom::Ring{{0, 0}, {4, 0}, {4, 3}}));
  EXPECT_EQ(lots.features[1].line, (geom::Polyline{{5, 6}}));
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_EQ(problems[0].rfind("lots.geojson: features[0]: malformed feature (", 0), 0u) << problems[0];
  EXPECT_EQ(problems[1], "lots.geojson: features[2]: a ring is not closed or has fewer than 4 positions");
  EXPECT_EQ(problems[2].rfind("lots.geojson: features[3]: malformed feature (", 0), 0u) << problems[2];
  EXPECT_EQ(problems[3], "lots.geojson: features[4]: unexpected geometry type Circle");
}

TEST(GeoJsonRead, ADocumentThatIsNoFeatureCollectionGivesOneProblemAndNoFeature) {
  for (const char* text : {R"({"features": [{"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [1, 2]}}, 7)",
                           R"({"features": {"a": {"properties": {}, "geometry": {"type": "Point", "coordinates": [1, 2]}}}})",
                           R"([{"properties": {}, "geometry": {"type": "Point", "coordinates": [1, 2]}}])"}) {
    std::vector<std::string> problems{"earlier"};
    const Layer layer = read_text("roads", text, problems);
    EXPECT_TRUE(layer.features.empty()) << text;
    ASSERT_EQ(problems.size(), 2u) << text;
    EXPECT_EQ(problems[0], "earlier");
    EXPECT_NE(problems[1].find("roads.geojson: not a GeoJSON FeatureCollection"), std::string::npos) << problems[1];
  }
}

}  // namespace
}  // namespace exacity
