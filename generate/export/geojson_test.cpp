// Reading a layer back for validation: feature by feature, each malformed one named and
// skipped, a document that is no FeatureCollection refused whole.
#include "generate/export/read_lines.h"

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

void expect_same(const Layer& a, const Layer& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.lines, b.lines);
  ASSERT_EQ(a.features.size(), b.features.size());
  for (std::size_t i = 0; i < a.features.size(); ++i) {
    EXPECT_EQ(a.features[i].properties, b.features[i].properties) << i;
    EXPECT_EQ(a.features[i].polygon.outer, b.features[i].polygon.outer) << i;
    EXPECT_EQ(a.features[i].polygon.holes, b.features[i].polygon.holes) << i;
    EXPECT_EQ(a.features[i].line, b.features[i].line) << i;
  }
}

Layer square_lots(double moved) {
  Layer lots{"lots", false, {}};
  for (int i = 0; i < 5; ++i) {
    const double x = 10.0 * i + (i == 3 ? moved : 0);
    lots.features.push_back({{{"id", i}, {"zone", "residential"}}, {{{x, 0}, {x + 4, 0}, {x + 4, 0.1}, {x, 3}}, {}}, {}});
  }
  return lots;
}

// After an edit a layer is read again parsing only the lines that changed, and reads as it
// reads whole.
TEST(GeoJsonRead, ByLineParsesOnlyTheLinesItHasNotRead) {
  const std::filesystem::path file = testing_util::temp_dir("geojson_lines") / "lots.geojson";
  ReadLines known;
  std::vector<std::string> problems, whole_problems;
  write_geojson(square_lots(0), nlohmann::ordered_json(), file);
  const Layer first = read_geojson(file, problems, known);
  EXPECT_EQ(known.parsed, 5);
  EXPECT_EQ(known.reused, 0);
  expect_same(first, read_geojson(file, whole_problems));
  write_geojson(square_lots(0.5), nlohmann::ordered_json(), file);
  const Layer edited = read_geojson(file, problems, known);
  EXPECT_EQ(known.parsed, 1);
  EXPECT_EQ(known.reused, 4);
  EXPECT_EQ(known.by_text.size(), 5u);  // this read's lines, the moved lot's old line gone
  expect_same(edited, read_geojson(file, whole_problems));
  EXPECT_EQ(edited.features[3].polygon.outer[0], (geom::Vec2{30.5, 0}));
  EXPECT_TRUE(problems.empty());
  EXPECT_TRUE(whole_problems.empty());

  Layer roads{"roads", true, {}};
  roads.features.push_back({{{"id", 1}}, {}, {{0, 0}, {5, 5}}});
  write_geojson(roads, nlohmann::ordered_json{{"type", "name"}}, file);
  expect_same(read_geojson(file, problems, known), read_geojson(file, whole_problems));
  EXPECT_EQ(known.parsed, 1);
}

// A file laid out otherwise, or with a feature line that has a problem, is read whole: the
// same features and problems, none taken from the lines known (here one planted with
// another reading, which a file laid out as written would take).
TEST(GeoJsonRead, ByLineReadsAnyOtherFileWhole) {
  const std::filesystem::path file = testing_util::temp_dir("geojson_lines_other") / "lots.geojson";
  const std::string feature = R"({"type":"Feature","properties":{"id":1},"geometry":{"type":"Point","coordinates":[1,2]}})";
  for (const std::string& text :
       {R"({"type":"FeatureCollection","features":[)" + feature + "]}\n",  // one line
        R"({"type":"FeatureCollection","features":[)" "\n" + feature + ",\n7,\n" + feature + "\n]}\n",  // a problem
        R"({"type":"FeatureCollection","features":[)" "\n" + feature + ",\n]}\n",                 // a trailing comma
        R"({"type":"FeatureCollection","features":[)" "\n" + feature + "\n" + feature + "\n]}\n",  // no comma
        R"({"a":{"features":[)" "\n" + feature + "\n]}\n"}) {       // not at the top
    std::ofstream(file, std::ios::binary) << text;
    ReadLines known;
    known.by_text.emplace(feature, ReadLines::Read{{{{"id", 9}}, {}, {{9, 9}}}, false});
    std::vector<std::string> problems, whole_problems;
    const Layer by_line = read_geojson(file, problems, known);
    expect_same(by_line, read_geojson(file, whole_problems));
    EXPECT_EQ(problems, whole_problems) << text;
    for (const VectorFeature& f : by_line.features) EXPECT_EQ(f.properties["id"], 1) << text;
  }
}

}  // namespace
}  // namespace exacity
