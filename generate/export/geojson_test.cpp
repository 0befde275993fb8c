// Reading a layer back for validation: feature by feature, each malformed one named and
// skipped, a document that is no FeatureCollection refused whole.
#include "generate/export/geojson.h"
#include "generate/export/geojson_written.h"
#include "generate/export/read_lines.h"

#include <gtest/gtest.h>

#include <fstream>
#include <optional>

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

// The same layer as bytes: properties as dumped, coordinates as their bits (so "-0" read as
// 0 shows).
std::string bits(const Layer& layer) {
  std::string s = layer.name + (layer.lines ? " lines" : " areas");
  auto ring = [&](const std::vector<geom::Vec2>& r) {
    s += '|' + std::to_string(r.size()) + '|';
    s.append(reinterpret_cast<const char*>(r.data()), r.size() * sizeof(geom::Vec2));
  };
  for (const VectorFeature& f : layer.features) {
    s += '\n' + f.properties.dump();
    ring(f.polygon.outer);
    for (const geom::Ring& h : f.polygon.holes) ring(h);
    ring(f.line);
  }
  return s;
}

// Written layers are read by a scanner of their layout (geojson.cpp, WrittenLayout), any
// other text by nlohmann's parser: both give the same layer, number for number. The second
// text is the first with a space after every comma, which only the parser reads.
TEST(GeoJsonRead, TheWrittenLayoutReadsAsTheParserReadsIt) {
  const std::vector<std::pair<std::string, std::string>> layers{
      {"lots",
       "{\"type\":\"FeatureCollection\",\"name\":\"lots\",\"crs\":{\"type\":\"name\",\"properties\":{\"name\":\"EPSG:3067\"}},\"features\":[\n"
       R"({"type":"Feature","properties":{"zone":"residential","id":7,"name":"a \"}\" b","tags":[1,{"k":"]"}],"h":1.5e3},"geometry":{"type":"Polygon","coordinates":[[[-0,0],[4.25,-0.0],[18446744073709551615,3],[-9223372036854775809,1E2],[-0,0]],[[1,1],[2,1],[2,2],[1,1]]]}},)"
       "\n"
       R"({"type":"Feature","properties":{"id":8},"geometry":{"type":"Polygon","coordinates":[[[0.1,0.2],[123456789.123456789,0.30000000000000004],[5e-324,2.2250738585072014e-308],[0.1,0.2]]]}})"
       "\n]}\n"},
      {"roads",
       "{\"type\":\"FeatureCollection\",\"name\":\"roads\",\"features\":[\n"
       R"({"type":"Feature","properties":{"id":1,"region":null},"geometry":{"type":"LineString","coordinates":[[1,2],[3.5,-4],[9007199254740993,1]]}},)"
       "\n"
       R"({"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[]}},)"
       "\n"
       R"({"type":"Feature","properties":{"kind":"bench"},"geometry":{"type":"Point","coordinates":[-12.75,1e1]}})"
       "\n]}\n"},
      {"water", "{\"type\":\"FeatureCollection\",\"name\":\"water\",\"features\":[\n]}\n"}};
  for (const auto& [name, text] : layers) {
    std::string spaced;
    for (char c : text) spaced += c == ',' ? std::string(", ") : std::string(1, c);
    const std::filesystem::path as_written = testing_util::temp_dir("written") / (name + ".geojson"),
                                as_spaced = testing_util::temp_dir("spaced") / (name + ".geojson");
    std::ofstream(as_written) << text;
    std::ofstream(as_spaced) << spaced;
    EXPECT_TRUE(read_written_geojson(as_written)) << name << ": not read as written";
    // The first line is any JSON object: spaces there are read as written.
    EXPECT_EQ(read_written_geojson(as_spaced).has_value(), name == "water") << name;
    std::vector<std::string> problems;
    const Layer written = read_geojson(as_written, problems), parsed = read_geojson(as_spaced, problems);
    EXPECT_TRUE(problems.empty()) << problems.front();
    EXPECT_EQ(bits(written), bits(parsed)) << name;
    EXPECT_EQ(written.features.size(), name == "lots" ? 2u : name == "roads" ? 3u : 0u);
  }
}

// A line of the written layout that is not one (a ring left open, a trailing comma) is read
// by the parser, which names the problem.
TEST(GeoJsonRead, AWrittenLayoutWithAProblemIsReadByTheParser) {
  std::vector<std::string> problems;
  const Layer lots = read_text("lots",
                               "{\"type\":\"FeatureCollection\",\"name\":\"lots\",\"features\":[\n"
                               R"({"type":"Feature","properties":{"id":1},"geometry":{"type":"Polygon","coordinates":[[[0,0],[4,0],[4,3],[0,0]]]}},)"
                               "\n"
                               R"({"type":"Feature","properties":{"id":2},"geometry":{"type":"Polygon","coordinates":[[[0,0],[4,0],[4,3],[0,1]]]}})"
                               "\n]}\n",
                               problems);
  EXPECT_FALSE(read_written_geojson(testing_util::test_dir("geojson_read") / "lots.geojson"));
  ASSERT_EQ(lots.features.size(), 1u);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0], "lots.geojson: features[1]: a ring is not closed or has fewer than 4 positions");
  problems.clear();
  const Layer trailing = read_text("roads",
                                   "{\"type\":\"FeatureCollection\",\"name\":\"roads\",\"features\":[\n"
                                   R"({"type":"Feature","properties":{"id":1},"geometry":{"type":"Point","coordinates":[1,2]}},)"
                                   "\n]}\n",
                                   problems);
  EXPECT_TRUE(trailing.features.empty());
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("not a GeoJSON FeatureCollection"), std::string::npos) << problems[0];
}

// A feature's properties of plain values are built by the scanner itself (WrittenLayout::
// plain_object), any others by nlohmann's parser: each as the parser reads it, key order
// (sorted), values and their types (signed, unsigned, double) alike.
TEST(GeoJsonRead, PlainPropertiesReadAsTheParserReadsThem) {
  const std::vector<std::string> objects{
      R"({})",
      R"({"id":7,"zone":"residential","green":false,"block":-3})",
      R"({"zone":"a","id":1,"b":null,"a":true})",  // not in order
      R"({"h":1.0,"i":-0,"j":1e2,"k":1E-2,"l":0.30000000000000004,"m":-1.5e-3,"n":0})",
      R"({"big":18446744073709551615,"bigger":18446744073709551616,"low":-9223372036854775808,"lower":-9223372036854775809})",
      R"({"roads":[805053434,-1,2.5,"x",null,true],"none":[]})",
      R"({"name":"a \"quoted\" b","tags":[1,{"k":"]"}]})",  // an escape, a nested object
      R"({"name":"caf\u00e9","place":"café"})",
      R"({"a":1,"a":2})",  // a repeated key
      R"({"slabs":[[0,3],[3,6]],"height":12.5})",
      R"({"x":1.7976931348623157e308,"y":5e-324,"z":2.2250738585072014e-308})",
  };
  for (const std::string& object : objects) {
    const std::filesystem::path file = testing_util::temp_dir("plain") / "roads.geojson";
    std::ofstream(file) << "{\"type\":\"FeatureCollection\",\"name\":\"roads\",\"features\":[\n"
                        << R"({"type":"Feature","properties":)" << object
                        << R"(,"geometry":{"type":"Point","coordinates":[1,2]}})" << "\n]}\n";
    const std::optional<Layer> layer = read_written_geojson(file);
    ASSERT_TRUE(layer) << object;
    ASSERT_EQ(layer->features.size(), 1u) << object;
    const nlohmann::ordered_json& read = layer->features[0].properties;
    const nlohmann::ordered_json parsed = nlohmann::json::parse(object);
    EXPECT_EQ(read.dump(), parsed.dump()) << object;
    ASSERT_EQ(read.size(), parsed.size()) << object;
    for (auto a = read.begin(), b = parsed.begin(); a != read.end(); ++a, ++b) {
      EXPECT_EQ(a.key(), b.key()) << object;
      EXPECT_EQ(a->type(), b->type()) << object << ": " << a.key();
      if (a->is_array()) {
        for (std::size_t k = 0; k < a->size(); ++k) EXPECT_EQ((*a)[k].type(), (*b)[k].type()) << object << ": " << a.key();
      }
    }
  }
}

}  // namespace
}  // namespace exacity
