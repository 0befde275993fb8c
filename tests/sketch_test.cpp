// Sketch parsing: every bad input gets one clear line; degenerate but legal input parses.
#include <gtest/gtest.h>

#include "generate/errors.h"
#include "generate/sketch/sketch.h"
#include "generate/city/street_graph.h"
#include "generate/layout/road_settings.h"
#include "generate/placement/building_settings.h"
#include "generate/placement/grid_filling.h"

using namespace exacity;

namespace {

std::string with_features(const std::string& features, const std::string& settings = "{}") {
  return R"({"type": "FeatureCollection", "exacity": )" + settings + R"(, "features": [)" + features + "]}";
}

const std::string kSquare =
    R"({"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[10,0],[10,10],[0,10],[0,0]]]}})";

// The message of the UserError that parsing `text` throws, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_sketch(text, "city.geojson");
  } catch (const UserError& e) {
    std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
    EXPECT_EQ(m.rfind("city.geojson", 0), 0u) << "names the file first: " << m;
    return m;
  }
  return "";
}

void expect_error(const std::string& text, std::initializer_list<const char*> parts) {
  std::string m = error_of(text);
  ASSERT_FALSE(m.empty()) << "accepted: " << text;
  for (const char* p : parts) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' missing in: " << m;
}

}  // namespace

TEST(SketchErrors, MalformedJsonGivesLineAndColumn) {
  expect_error("{\"type\": \"FeatureCollection\",\n  \"features\": [,]}", {"city.geojson:2:", "malformed JSON"});
}

TEST(SketchErrors, MissingOrNullGeometry) {
  expect_error(with_features(R"({"type": "Feature", "properties": {"zone": "park"}})"), {"features[0]", "no geometry"});
  expect_error(with_features(R"({"type": "Feature", "properties": {"zone": "park"}, "geometry": null})"),
               {"features[0]", "no geometry"});
}

TEST(SketchErrors, UnknownZoneTypeSuggestsTheNearest) {
  expect_error(with_features(kSquare + "," + R"({"type": "Feature", "properties": {"zone": "residental"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,0],[1,1],[0,0]]]}})"),
               {"features[1]", "\"residental\"", "did you mean \"residential\""});
  expect_error(with_features(R"({"type": "Feature", "properties": {"road": "motorway"}, "geometry": {"type": "LineString", "coordinates": [[0,0],[1,0]]}})"),
               {"features[0]", "unknown road class"});
}

TEST(SketchErrors, SuggestionsIgnoreCase) {
  expect_error(with_features(R"({"type": "Feature", "properties": {"zone": "WATER"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,0],[1,1],[0,0]]]}})"),
               {"features[0]", "did you mean \"water\""});
}

TEST(SketchErrors, TypeThatIsNotAString) {
  for (const char* type : {"null", "0", "{}", "[]", "true"}) {
    expect_error(R"({"type": )" + std::string(type) + R"(, "features": []})", {"top level", "FeatureCollection"});
    expect_error(with_features(R"({"type": )" + std::string(type) + R"(, "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,0],[1,1],[0,0]]]}})"),
                 {"features[0]", "not a GeoJSON Feature"});
    expect_error(with_features(R"({"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": )" + std::string(type) + R"(, "coordinates": [[[0,0],[1,0],[1,1],[0,0]]]}})"),
                 {"features[0]", "a zone must be a Polygon or MultiPolygon"});
  }
}

TEST(SketchErrors, CoordinatesBeyondTheExactRange) {
  const std::string far = R"({"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,0],[1,X],[0,0]]]}})";
  for (const char* y : {"1.0000001e10", "-1e308", "4e12"}) {
    std::string f = far;
    f.replace(f.find('X'), 1, y);
    expect_error(with_features(f), {"features[0] outer ring position 2", "beyond 1e10 m"});
  }
  std::string edge = far;
  edge.replace(edge.find('X'), 1, "1e10");
  EXPECT_EQ(error_of(with_features(edge)), "") << "1e10 itself is in range";
}

TEST(SketchErrors, MoreBlocksThanOneRunBuilds) {
  const std::string big = R"({"type": "Feature", "properties": {"zone": "commercial"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[30000,0],[30000,30000],[0,30000],[0,0]]]}})";
  // 9e8 m2 over 15,000 m2 blocks: 60,000 blocks, and the small square one; with 20,000 m2
  // blocks, 45,000 fit.
  expect_error(with_features(kSquare + "," + big), {"features[1]", "about 60001 blocks", "\"block_area\""});
  EXPECT_EQ(error_of(with_features(big, R"({"zones": {"commercial": {"block_area": 20000}}})")), "");
}

// Every polygon is a block (or park or water face) at least: 60,001 triangles of half a
// square metre have the area of no block, but each is a face of the exact map.
TEST(SketchErrors, MorePolygonsThanBlocksOneRunBuilds) {
  std::string polygons;
  for (int i = 0; i <= 60000; ++i) {
    const std::string x = std::to_string(2 * i);
    polygons += (i ? ",[[[" : "[[[") + x + ",0],[" + std::to_string(2 * i + 1) + ",0],[" + x + ",1]]]";
  }
  const std::string many = R"({"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "MultiPolygon", "coordinates": [)" +
                           polygons + "]}}";
  expect_error(with_features(kSquare + "," + many), {"features[1]", "about 60002 blocks", "each polygon one at least", "fewer"});
}

TEST(SketchErrors, RingWithFewerThanThreeDistinctPoints) {
  expect_error(with_features(R"({"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,1],[0,0],[1,1],[0,0]]]}})"),
               {"features[0]", "2 distinct points", "at least 3"});
}

TEST(SketchErrors, NonFiniteCoordinate) {
  expect_error(with_features(R"({"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1e999,0],[1,1],[0,0]]]}})"),
               {"features[0]", "not a finite number"});
}

TEST(SketchErrors, UnknownKeyInSettingsIsNamed) {
  expect_error(with_features(kSquare, R"({"seed": 1, "sede": 2})"), {"\"exacity\"", "unknown key \"sede\""});
  expect_error(with_features(kSquare, R"({"terrain": {"heightmap": "a.png", "bounds": [0,0,1,1], "heigth": [0,1]}})"),
               {"terrain", "unknown key \"heigth\""});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"block_areaa": 1}}})"),
               {"unknown key \"block_areaa\""});
}

TEST(SketchErrors, HeightmapBoundsWithZeroArea) {
  expect_error(with_features(kSquare, R"({"terrain": {"heightmap": "a.png", "bounds": [0,0,0,100]}})"),
               {"bounds", "zero area"});
}

TEST(SketchErrors, OtherMistakes) {
  expect_error(R"({"type": "Feature"})", {"FeatureCollection"});
  expect_error(with_features(R"({"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [0,0]}})"),
               {"neither"});
  expect_error(with_features(R"({"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "LineString", "coordinates": [[0,0],[1,0]]}})"),
               {"Polygon or MultiPolygon"});
  expect_error(with_features(kSquare, R"({"seed": -3})"), {"seed"});
}

TEST(SketchErrors, LongitudeLatitudeIsRefused) {
  const std::string lonlat =
      R"({"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [[[24.94,60.16],[24.95,60.16],[24.95,60.17],[24.94,60.16]]]}})";
  expect_error(with_features(lonlat), {"longitude/latitude", "ogr2ogr"});
  expect_error(R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:OGC:1.3:CRS84"}}, "features": [)" +
                   kSquare + "]}",
               {"crs", "longitude/latitude"});
}

TEST(SketchParse, DegenerateButLegalInput) {
  // Repeated consecutive points, an unclosed ring, collinear edges, a zone drawn twice.
  std::string text = with_features(
      kSquare + "," + kSquare + "," +
      R"({"type": "Feature", "properties": {"zone": "commercial", "name": "x"}, "geometry": {"type": "Polygon", "coordinates": [[[0,0],[0,0],[5,0],[10,0],[10,10]]]}},
         {"type": "Feature", "properties": {"road": "highway"}, "geometry": {"type": "LineString", "coordinates": [[-5,0],[-5,0],[15,0]]}})",
      R"({"seed": 42, "zones": {"commercial": {"branches": 6, "road_widths": [14, 9, 6]}}})");
  Sketch s = parse_sketch(text, "city.geojson");
  EXPECT_EQ(s.seed, 42u);
  ASSERT_EQ(s.zones.size(), 3u);
  EXPECT_EQ(s.zones[2].polygons[0].outer.size(), 4u);  // the repeated point dropped
  EXPECT_EQ(s.zones[2].type, ZoneType::Commercial);
  EXPECT_EQ(s.zone_settings.at(ZoneType::Commercial).roads.growth.branches, 6);
  EXPECT_EQ(road_width(s.zone_settings.at(ZoneType::Commercial).roads, 0), 14);
  EXPECT_EQ(road_width(s.zone_settings.at(ZoneType::Commercial).roads, 2), 6);
  EXPECT_EQ(road_width(s.zone_settings.at(ZoneType::Commercial).roads, 7), 6);
  EXPECT_EQ(road_width(s.zone_settings.at(ZoneType::Residential).roads, 3), 8);
  ASSERT_EQ(s.roads.size(), 1u);
  EXPECT_EQ(s.roads[0].width, 24);  // a highway's default width
  EXPECT_EQ(s.roads[0].lines[0].size(), 2u);
  EXPECT_EQ(s.roads[0].index, 3);
}

TEST(SketchParse, CrsAndMultiGeometries) {
  std::string text = R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "EPSG:28992"}},
    "features": [
      {"type": "Feature", "properties": {"zone": "industrial"}, "geometry": {"type": "MultiPolygon", "coordinates": [
        [[[0,0],[4,0],[4,4],[0,4],[0,0]], [[1,1],[1,2],[2,2],[2,1],[1,1]]], [[[5,5],[6,5],[6,6],[5,5]]]]}},
      {"type": "Feature", "properties": {"road": "local", "width": 6}, "geometry": {"type": "MultiLineString", "coordinates": [[[0,0],[1,1]], [[2,2],[3,3]]]}}]})";
  Sketch s = parse_sketch(text, "city.geojson");
  EXPECT_EQ(s.crs["properties"]["name"], "EPSG:28992");
  EXPECT_EQ(s.crs.dump(), R"({"type":"name","properties":{"name":"EPSG:28992"}})");  // as written
  ASSERT_EQ(s.zones[0].polygons.size(), 2u);
  EXPECT_EQ(s.zones[0].polygons[0].holes.size(), 1u);
  EXPECT_EQ(s.roads[0].lines.size(), 2u);
  EXPECT_EQ(s.roads[0].width, 6);
}

TEST(SketchParse, MissingFileIsAUserError) {
  EXPECT_THROW(load_sketch("/nonexistent/city.geojson"), UserError);
}

TEST(Sketch, GridFillingSettingsAreReadAndChecked) {
  Sketch s = parse_sketch(with_features(kSquare, R"({"zones": {"commercial": {"placement": "grid", "grid_cell": 0.5,
                                                   "grid_passes": 3}}})"),
                          "city.geojson");
  const BuildingSettings& b = s.zone_settings.at(ZoneType::Commercial).buildings;
  ASSERT_EQ(b.placement->name(), "grid");
  const GridFillingSettings& grid = dynamic_cast<const GridFillingChoice&>(*b.placement).settings();
  EXPECT_EQ(grid.cell, 0.5);
  EXPECT_EQ(grid.passes, 3);
  EXPECT_FALSE(b.placement->nests());
  EXPECT_EQ(s.zone_settings.at(ZoneType::Residential).buildings.placement->name(), "rows");
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"placement": "hex"}}})"), {"placement", "\"grid\""});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"grid_cell": 0}}})"), {"grid_cell"});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"grid_passes": 1.5}}})"), {"grid_passes", "whole"});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"grid_passes": 17}}})"), {"grid_passes"});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"nesting": true}}})"), {"nesting", "\"placement\": \"grid\""});
}

TEST(Sketch, ChannelsAreReadAndChecked) {
  Sketch s = parse_sketch(with_features(kSquare, R"({"channels": {"wealth": {"image": "w.png", "bounds": [0, 0, 10, 20]},
      "downtown": {"image": "maps/d.png", "bounds": [-5, -5, 5, 5]}}, "channel_sharpness": 2,
      "zones": {"commercial": {"height_channel": "downtown"}}})"),
                          "dir/city.geojson");
  ASSERT_EQ(s.channels.size(), 2u);
  EXPECT_EQ(s.channels[0].name, "downtown");  // by name
  EXPECT_EQ(s.channels[0].image, std::filesystem::path("dir/maps/d.png"));
  EXPECT_EQ(s.channels[1].bounds.max_y, 20);
  EXPECT_EQ(s.channel_sharpness, 2);
  EXPECT_EQ(s.zone_settings.at(ZoneType::Commercial).buildings.height_channel, "downtown");
  expect_error(with_features(kSquare, R"({"channels": [1]})"), {"\"exacity\".channels", "by name"});
  expect_error(with_features(kSquare, R"({"channels": {"w": {"image": "w.png"}}})"), {"channels.w.bounds"});
  expect_error(with_features(kSquare, R"({"channels": {"w": {"image": "w.png", "bounds": [0, 0, 0, 5]}}})"),
               {"channels.w.bounds", "zero area"});
  expect_error(with_features(kSquare, R"({"channels": {"w": {"bounds": [0, 0, 1, 1]}}})"), {"channels.w.image"});
  expect_error(with_features(kSquare, R"({"channels": {"w": {"image": "w.png", "bounds": [0, 0, 1, 1], "gamma": 2}}})"),
               {"unknown key \"gamma\""});
  expect_error(with_features(kSquare, R"({"channel_sharpness": -1})"), {"channel_sharpness"});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"height_channel": "wealth"}}})"),
               {"height_channel", "\"wealth\" is not a channel"});
}

TEST(Sketch, CameraAndDensityAndModelsAreRead) {
  Sketch s = parse_sketch(with_features(kSquare, R"({"camera": "look:from=0,-50,30,to=5,5,0", "models": "lib/models.json",
                                                   "zones": {"residential": {"density": "sparse"}}})"),
                          "dir/city.geojson");
  EXPECT_EQ(s.camera, "look:from=0,-50,30,to=5,5,0");
  EXPECT_EQ(s.models, std::filesystem::path("dir/lib/models.json"));
  EXPECT_EQ(s.zone_settings.at(ZoneType::Residential).buildings.density, "sparse");
  expect_error(with_features(kSquare, R"({"camera": 3})"), {"camera", "orbit:"});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"density": "packed"}}})"), {"density", "\"dense\""});
}

namespace {

std::string street(const std::string& coordinates, const std::string& cls = "local") {
  return R"({"type": "Feature", "properties": {"road": ")" + cls +
         R"("}, "geometry": {"type": "LineString", "coordinates": )" + coordinates + "}}";
}

}  // namespace

TEST(SketchErrors, LayoutsAndStreetSettings) {
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"layout": "grid"}}})"),
               {"zones.residential.layout", "\"growth\"", "\"streets\""});
  expect_error(with_features(kSquare, R"({"roads": {"snap": -1}})"), {"roads.snap", "out of range"});
  expect_error(with_features(kSquare, R"({"roads": {"dead_ends": "warn"}})"), {"roads.dead_ends", "\"error\""});
  expect_error(with_features(kSquare, R"({"roads": {"local": {"sidewalks": 2}}})"), {"roads.local", "unknown key \"sidewalks\""});
  expect_error(with_features(kSquare, R"({"roads": {"lane": {}}})"), {"unknown key \"lane\""});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"layout": "voronoi", "cell_size": 40}}})"),
               {"zones.residential.cell_size", "under 4 road widths"});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"layout": "grammar"}}})"),
               {"zones.residential.layout", "needs \"grammar\""});
  expect_error(with_features(kSquare, R"({"zones": {"residential": {"grammar_depth": 2.5}}})"), {"grammar_depth", "whole number"});
}

TEST(SketchErrors, ADeadEndIsAnErrorWhenTheSketchSaysSo) {
  const std::string streets = street("[[0,0],[100,0]]") + "," + street("[[100,0],[100,100],[0,100],[0,0]]") + "," +
                              street("[[50,0],[50,100]]");
  EXPECT_EQ(error_of(with_features(streets, R"({"roads": {"dead_ends": "error"}})")), "");  // (50, 0) is on a street
  expect_error(with_features(streets + "," + street("[[50,100],[60,60]]"), R"({"roads": {"dead_ends": "error"}})"),
               {"features[3]", "[60.0,60.0]", "dead end", "\"report\""});
}

TEST(StreetGraph, NearEndsAreJoinedAndFarOnesReportedAsDeadEnds) {
  Sketch s = parse_sketch(with_features(street("[[0,0],[100,0]]") + "," +
                                        street("[[100.3,0.2],[100,100]]") +  // 0.36 m from (100, 0): joined
                                        "," + street("[[50,0.4],[50,-80]]") +  // 0.4 m above the first street's side
                                        "," + street("[[0,100.6],[0,0]]")),    // 0.6 m short of (0, 100): a dead end
                          "city.geojson");
  EXPECT_EQ(s.joined_ends, 2);
  EXPECT_EQ(s.roads[1].lines[0].front(), (geom::Vec2{100, 0}));
  EXPECT_EQ(s.roads[2].lines[0].front(), (geom::Vec2{50, 0}));
  EXPECT_EQ(s.roads[0].lines[0], (geom::Polyline{{0, 0}, {50, 0}, {100, 0}}));  // the T's node is a vertex of both
  ASSERT_EQ(s.dead_ends.size(), 3u);
  EXPECT_EQ(s.dead_ends[0].feature, 1);  // (100, 100)
  EXPECT_EQ(s.dead_ends[1].feature, 2);  // (50, -80)
  EXPECT_EQ(s.dead_ends[2].feature, 3);
  EXPECT_EQ(s.dead_ends[2].at, (geom::Vec2{0, 100.6}));

  Sketch exact = parse_sketch(with_features(street("[[0,0],[100,0]]") + "," + street("[[100.3,0.2],[100,100]]"),
                                            R"({"roads": {"snap": 0}})"),
                              "city.geojson");
  EXPECT_EQ(exact.joined_ends, 0);
  EXPECT_EQ(exact.dead_ends.size(), 4u);
}

TEST(StreetGraph, NodesAreWhereLinesMeetNotWhereOneBends) {
  Sketch s = parse_sketch(with_features(street("[[0,0],[100,0],[200,50]]") + "," + street("[[100,0],[100,100]]") + "," +
                                        street("[[200,50],[300,50]]")),
                          "city.geojson");
  auto nodes = street_nodes(s.roads);
  ASSERT_EQ(nodes.size(), 2u);
  EXPECT_EQ(nodes[0].at, (geom::Vec2{100, 0}));
  EXPECT_EQ(nodes[0].arms.size(), 3u);
  EXPECT_EQ(nodes[1].at, (geom::Vec2{200, 50}));
  EXPECT_EQ(nodes[1].arms.size(), 2u);
}
