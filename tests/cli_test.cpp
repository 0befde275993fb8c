// End to end through the exacity binary, on a small sketch: validate catches tampered
// layers; stats measures; bad input exits 2 with one line and no output folder; output
// folders are never overwritten by mistake and an interrupt leaves no trace. Every example
// generated and checked, determinism, renders and the schemas are examples_test.cpp's.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <functional>

#include "tests/cli_util.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using namespace cli_util;

namespace {

// A sketch the size of a few streets, for the tests of the program around the city: two
// zones across a highway, so there are grown roads of two regions and a sketch road. Under
// the sanitizers it generates several times faster than the town.
fs::path small_sketch(const fs::path& dir) {
  std::ofstream(dir / "small.geojson") << R"({"type": "FeatureCollection", "exacity": {"seed": 3}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [400, 0], [400, 300], [0, 300], [0, 0]]]}},
    {"type": "Feature", "properties": {"zone": "commercial"},
     "geometry": {"type": "Polygon", "coordinates": [[[400, 0], [600, 0], [600, 300], [400, 300], [400, 0]]]}},
    {"type": "Feature", "properties": {"road": "highway", "width": 16},
     "geometry": {"type": "LineString", "coordinates": [[-50, 150], [650, 150]]}}]})";
  return dir / "small.geojson";
}

// Writes the sketch into `dir` and generates it into dir/out.
Result generate_in(const fs::path& dir, const std::string& sketch) {
  std::ofstream(dir / "in.geojson") << sketch;
  return run("generate " + (dir / "in.geojson").string() + " -o " + (dir / "out").string() + " -q");
}

}  // namespace

// Generates the small sketch, lets `tamper` edit one layer, and returns what validate says.
Result validate_tampered(const std::string& name, const std::string& layer,
                         const std::function<void(nlohmann::json&)>& tamper) {
  fs::path dir = testing_util::temp_dir("cli-tamper-" + name), out = dir / "out";
  EXPECT_EQ(run("generate " + small_sketch(dir).string() + " -o " + out.string() + " -q").code, 0);
  fs::path file = out / "vector" / (layer + ".geojson");
  auto doc = nlohmann::json::parse(read(file));
  tamper(doc);
  std::ofstream(file) << doc.dump();
  return run("validate " + out.string());
}

TEST(Cli, ValidateCatchesAMovedZoneVertex) {
  Result v = validate_tampered("zone", "zones", [](nlohmann::json& doc) {
    auto& ring = doc["features"][0]["geometry"]["coordinates"][0];
    // Off both its edges, whatever their direction: now it overlaps a neighbour or leaves a gap.
    ring[1][0] = ring[1][0].get<double>() + 3.0;
    ring[1][1] = ring[1][1].get<double>() + 1.7;
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("problem:"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesAMissingBlock) {
  Result v = validate_tampered("block", "blocks", [](nlohmann::json& doc) { doc["features"].erase(0); });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("holds no block"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesARoadEndingInTheOpen) {
  Result v = validate_tampered("end", "roads", [](nlohmann::json& doc) {
    for (auto& f : doc["features"])
      if (!f["properties"]["level"].is_null()) {
        auto& first = f["geometry"]["coordinates"][0];
        first[0] = first[0].get<double>() + 0.5;
        first[1] = first[1].get<double>() + 0.25;
        break;
      }
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("ends in the open"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesADisconnectedRegion) {
  Result v = validate_tampered("region", "roads", [](nlohmann::json& doc) {
    // Carry the last grown road far away from the rest of its region.
    for (auto it = doc["features"].rbegin(); it != doc["features"].rend(); ++it) {
      if ((*it)["properties"]["region"].is_null()) continue;
      for (auto& p : (*it)["geometry"]["coordinates"]) p[0] = p[0].get<double>() + 5000;
      break;
    }
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("are not connected"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesARegionWhoseStreetsAreAnIsland) {
  Result v = validate_tampered("island", "roads", [](nlohmann::json& doc) {
    // Carry all the roads of one region far away, together: connected, but to nothing else.
    const auto region = doc["features"].back()["properties"]["region"];
    for (auto& f : doc["features"])
      if (f["properties"]["region"] == region)
        for (auto& p : f["geometry"]["coordinates"]) p[0] = p[0].get<double>() + 5000;
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("reach no other road"), std::string::npos) << v.out;
  EXPECT_EQ(v.out.find("are not connected"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesAReferenceToNoFeature) {
  Result v = validate_tampered("reference", "buildings", [](nlohmann::json& doc) {
    doc["features"][0]["properties"]["lot"] = 999999;
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("\"lot\" 999999 names no feature of lots.geojson"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesCentreLinesThatMeetBetweenVertices) {
  Result v = validate_tampered("noded", "roads", [](nlohmann::json& doc) {
    // A new centre line across the middle of the first one's first segment, with no vertex there.
    auto line = doc["features"][0]["geometry"]["coordinates"];
    const double x0 = line[0][0], y0 = line[0][1], x1 = line[1][0], y1 = line[1][1];
    const double mx = (x0 + x1) / 2, my = (y0 + y1) / 2, len = std::hypot(x1 - x0, y1 - y0);
    const double nx = -(y1 - y0) / len * 5, ny = (x1 - x0) / len * 5;
    nlohmann::json crossing = doc["features"][0];
    crossing["properties"]["id"] = 999999;
    crossing["geometry"]["coordinates"] = {{mx - nx, my - ny}, {mx + nx, my + ny}};
    doc["features"].push_back(crossing);
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("meets another centre line between its vertices"), std::string::npos) << v.out;
}

TEST(Cli, ValidateCatchesCentreLinesThatRunAlongOneSegment) {
  Result v = validate_tampered("overlap", "roads", [](nlohmann::json& doc) {
    // A new centre line along the first one's first segment: they meet at vertices of both,
    // and along the segment between them.
    auto line = doc["features"][0]["geometry"]["coordinates"];
    nlohmann::json along = doc["features"][0];
    along["properties"]["id"] = 999999;
    along["geometry"]["coordinates"] = {line[1], line[0]};
    doc["features"].push_back(along);
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("runs along road"), std::string::npos) << v.out;
}

// A lot laid exactly over another, its ring starting at another vertex and running along
// the first's edges split at its midpoints (so no edge of the two is the same segment):
// validation's map answers shared ends, ends on edges and overlaps from orientations
// (geom/shared_ends.h), and still finds the two lots on one face.
TEST(Cli, ValidateCatchesALotLaidOverAnotherAlongSplitEdges) {
  Result v = validate_tampered("lot-over-lot", "lots", [](nlohmann::json& doc) {
    nlohmann::json over = doc["features"][0];
    over["properties"]["id"] = 999999;
    auto ring = over["geometry"]["coordinates"][0];  // closed: its last position is its first
    nlohmann::json split = nlohmann::json::array();
    for (std::size_t k = 1; k + 1 < ring.size(); ++k) {  // from the second vertex on
      split.push_back(ring[k]);
      split.push_back({(ring[k][0].get<double>() + ring[k + 1][0].get<double>()) / 2,
                       (ring[k][1].get<double>() + ring[k + 1][1].get<double>()) / 2});
    }
    split.push_back(ring[0]);
    split.push_back({(ring[0][0].get<double>() + ring[1][0].get<double>()) / 2,
                     (ring[0][1].get<double>() + ring[1][1].get<double>()) / 2});
    split.push_back(split[0]);
    over["geometry"]["coordinates"] = {split};
    doc["features"].push_back(over);
  });
  EXPECT_EQ(v.code, 1) << v.out;
  EXPECT_NE(v.out.find("lots.geojson features[0] and lots.geojson features["), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("overlap"), std::string::npos) << v.out;
}

// A zone the run leaves without a lot is named, with the reason, in report.json and in a
// note: here one drawn twice (the later copy takes all its land) and one no street reaches.
TEST(Cli, ZonesLeftEmptyAreNamedWithTheReason) {
  const fs::path dir = testing_util::temp_dir("cli-empty");
  Result g = generate_in(dir, R"({"type": "FeatureCollection", "exacity": {"seed": 3, "zones":
    {"commercial": {"layout": "streets"}}}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 200], [0, 200], [0, 0]]]}},
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 200], [0, 200], [0, 0]]]}},
    {"type": "Feature", "properties": {"zone": "commercial"},
     "geometry": {"type": "Polygon", "coordinates": [[[500, 0], [700, 0], [700, 200], [500, 200], [500, 0]]]}}]})");
  ASSERT_EQ(g.code, 0) << g.out;
  auto empty = nlohmann::json::parse(read(dir / "out" / "report.json"))["empty_zones"];
  ASSERT_EQ(empty.size(), 2u) << empty;
  EXPECT_EQ(empty[0]["feature"], 0);
  EXPECT_NE(empty[0]["why"].get<std::string>().find("no land of its own"), std::string::npos) << empty[0];
  EXPECT_EQ(empty[1]["feature"], 2);
  EXPECT_NE(empty[1]["why"].get<std::string>().find("no street reaches"), std::string::npos) << empty[1];
  EXPECT_NE(g.out.find("features[0] (residential) got no lots: no land of its own"), std::string::npos) << g.out;
  EXPECT_NE(g.out.find("features[2] (commercial) got no lots: no street reaches"), std::string::npos) << g.out;
}

// Many zones left empty (an OSM extract's land-use areas no street reaches) are not one
// line each: the first few are named, report.json lists all.
TEST(Cli, ManyEmptyZonesAreNamedFirstFewThenCounted) {
  const fs::path dir = testing_util::temp_dir("cli-many-empty");
  std::string features = R"({"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 200], [0, 200], [0, 0]]]}})";
  for (int i = 0; i < 12; ++i) {  // 12 small commercial squares far apart, no street to any
    const std::string x0 = std::to_string(1000 + 200 * i), x1 = std::to_string(1100 + 200 * i);
    features += R"(, {"type": "Feature", "properties": {"zone": "commercial"}, "geometry": {"type": "Polygon",
      "coordinates": [[[)" + x0 + ", 0], [" + x1 + ", 0], [" + x1 + ", 100], [" + x0 + ", 100], [" + x0 + ", 0]]]}}";
  }
  Result g = generate_in(dir, R"({"type": "FeatureCollection", "exacity": {"seed": 3, "zones":
    {"commercial": {"layout": "streets"}}}, "features": [)" + features + "]}");
  ASSERT_EQ(g.code, 0) << g.out;
  EXPECT_EQ(nlohmann::json::parse(read(dir / "out" / "report.json"))["empty_zones"].size(), 12u);
  std::size_t named = 0;
  for (std::size_t at = g.out.find(") got no lots:"); at != std::string::npos; at = g.out.find(") got no lots:", at + 1)) ++named;
  EXPECT_EQ(named, 5u) << g.out;
  EXPECT_NE(g.out.find("and 7 more zones got no lots (" + (dir / "out" / "report.json").string() +
                       " lists them all under \"empty_zones\")"),
            std::string::npos)
      << g.out;
}

// Grid filling places library models: a zone that asks for it without any is built in
// rows, and the run says so.
// perimeter_depth: a block that is one lot, with streets on every side, is one building
// round a courtyard, fronting each street behind its setback.
TEST(Cli, PerimeterBlocksRingTheBlockRoundACourtyard) {
  const fs::path dir = testing_util::temp_dir("cli-perimeter");
  std::string roads;
  for (int v : {0, 120})
    roads += R"(, {"type": "Feature", "properties": {"road": "local"}, "geometry": {"type": "LineString", "coordinates": [[)" +
             std::to_string(v) + ", -10], [" + std::to_string(v) + R"(, 130]]}},
      {"type": "Feature", "properties": {"road": "local"}, "geometry": {"type": "LineString", "coordinates": [[-10, )" +
             std::to_string(v) + "], [130, " + std::to_string(v) + "]]}}";
  Result g = generate_in(dir, R"({"type": "FeatureCollection", "exacity": {"seed": 3, "zones": {"residential":
    {"layout": "streets", "lots": "split", "lot_area": 100000, "perimeter_depth": 12, "setback": 2}}}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [120, 0], [120, 120], [0, 120], [0, 0]]]}})" + roads + "]}");
  ASSERT_EQ(g.code, 0) << g.out;
  const auto lots = nlohmann::json::parse(read(dir / "out" / "vector" / "lots.geojson"))["features"];
  ASSERT_EQ(lots.size(), 1u);
  const auto features = nlohmann::json::parse(read(dir / "out" / "vector" / "buildings.geojson"))["features"];
  std::vector<nlohmann::json> buildings;
  for (const auto& f : features)
    if (f["properties"]["kind"] == "building") buildings.push_back(f);
  ASSERT_EQ(buildings.size(), 1u);
  const auto& rings = buildings[0]["geometry"]["coordinates"];
  ASSERT_EQ(rings.size(), 2u) << "one courtyard";
  // The lot is the block inside the road areas, a square of side s; the building its ring
  // from 2 m (the setback, and half the building gap inside the lot's edges) to 14 m
  // behind each street.
  auto side = [](const nlohmann::json& ring) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& p : ring) lo = std::min(lo, p[0].get<double>()), hi = std::max(hi, p[0].get<double>());
    return hi - lo;
  };
  const double s = side(lots[0]["geometry"]["coordinates"][0]);
  EXPECT_NEAR(side(rings[0]), s - 4, 0.11);
  EXPECT_NEAR(side(rings[1]), s - 28, 0.11);
  EXPECT_EQ(run("validate " + (dir / "out").string()).code, 0);
}

TEST(Cli, GridFillingWithoutModelsIsNamedNotSilent) {
  const fs::path dir = testing_util::temp_dir("cli-grid-fallback");
  Result g = generate_in(dir, R"({"type": "FeatureCollection", "exacity": {"seed": 3, "zones":
    {"residential": {"placement": "grid"}}}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 200], [0, 200], [0, 0]]]}}]})");
  ASSERT_EQ(g.code, 0) << g.out;
  auto report = nlohmann::json::parse(read(dir / "out" / "report.json"));
  ASSERT_EQ(report["placement_fallbacks"].size(), 1u) << report["placement_fallbacks"];
  EXPECT_EQ(report["placement_fallbacks"][0]["zone"], "residential");
  EXPECT_GT(report["counts"]["buildings"].get<int>(), 0);
  EXPECT_NE(g.out.find("note: " + (dir / "in.geojson").string() + ": residential lots are filled on the grid only with library models"),
            std::string::npos)
      << g.out;
}

TEST(Cli, StatsMeasureTheCityAndRealData) {
  fs::path dir = testing_util::temp_dir("cli-stats");
  ASSERT_EQ(run("generate " + small_sketch(dir).string() + " -o " + (dir / "out").string() + " -q").code, 0);
  // Real data in lon/lat: a 0.001 degree square footprint at 60 degrees north (55.8 x 111.4 m
  // on the ellipsoid, measured in UTM zone 35N, whose scale 2 degrees off its meridian is 0.99975).
  std::ofstream(dir / "real.geojson") << R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "MultiPolygon", "coordinates":
      [[[[25, 60], [25.001, 60], [25.001, 60.001], [25, 60.001], [25, 60]]]]}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [[[25, 60], [25.001, 60], [25, 60]]]}}]})";
  Result s = run("stats " + (dir / "out").string() + " --real " + (dir / "real.geojson").string());
  EXPECT_EQ(s.code, 0) << s.out;
  EXPECT_NE(s.out.find("share of lots touching a road area: 1.0"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("dead ends 0"), std::string::npos) << s.out;
  EXPECT_NE(s.out.find("footprints: 1, area m2 median 6213.6"), std::string::npos) << s.out;
  // A ring of two points (ogr2ogr writes 26 such from Kotka's extract) is left out and counted.
  EXPECT_NE(s.out.find("features left out: 1 "), std::string::npos) << s.out;
  Result bad = run("stats " + (dir / "nowhere").string());
  EXPECT_EQ(bad.code, 2) << bad.out;
  EXPECT_NE(bad.out.find("not an output folder"), std::string::npos) << bad.out;
}

// A number option out of its range says the range as the option means it (CLI11's checks
// of any non-negative number printed the largest double, 309 digits).
TEST(Cli, ANumberOutOfItsRangeSaysTheRange) {
  for (const auto& [args, expect] : std::vector<std::pair<std::string, std::string>>{
           {"plan-task plan --task 1e400 --step roads", "--task: Value 1e400 not in range 0 to 99999"},
           {"plan-task plan --task 100000 --step roads", "--task: Value 100000 not in range 0 to 99999"},
           {"serve sketch.geojson --max-render -5", "--max-render: Value -5 not in range 1 to 1099511627776"}}) {
    const Result r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')), expect) << args;
  }
}

TEST(Cli, BadInputExitsTwoWithOneLineAndNoOutput) {
  fs::path dir = testing_util::temp_dir("cli-bad");
  struct Case {
    std::string name, text, expect;
  };
  const std::string zone = R"({"type":"Feature","properties":{"zone":"park"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[9,0],[9,9],[0,0]]]}})";
  std::vector<Case> cases = {
      {"syntax", "{\"type\": \"FeatureCollection\",\n \"features\": [}", "malformed JSON"},
      {"nogeom", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"park"},"geometry":null}]})", "no geometry"},
      {"zone", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"parc"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}}]})", "did you mean \"park\""},
      {"heightmap", R"({"type":"FeatureCollection","exacity":{"terrain":{"heightmap":"missing.png","bounds":[0,0,10,10]}},"features":[)" + zone + "]}", "not found"},
      {"key", R"({"type":"FeatureCollection","exacity":{"colour":1},"features":[)" + zone + "]}", "unknown key \"colour\""},
      {"typenull", R"({"type":null,"features":[]})", "GeoJSON FeatureCollection"},
      {"typezero", R"({"type":0,"features":[]})", "GeoJSON FeatureCollection"},
      {"typeobject", R"({"type":{},"features":[]})", "GeoJSON FeatureCollection"},
      {"huge", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"park"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[9,0],[9,-1e308],[0,0]]]}}]})", "beyond 1e10 m"},
      {"far", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"residential"},"geometry":{"type":"Polygon","coordinates":[[[4e12,4e12],[4.000000001e12,4e12],[4.000000001e12,4.000000001e12],[4e12,4e12]]]}}]})", "beyond 1e10 m"},
      {"vast", R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"zone":"residential"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1e6,0],[1e6,1e6],[0,0]]]}}]})", "more than the 60000 one run builds"},
      {"library", R"({"type":"FeatureCollection","exacity":{"models":"missing.json"},"features":[)" + zone + "]}", "cannot read the model library"},
      {"model", R"({"type":"FeatureCollection","exacity":{"models":"bad-library.json"},"features":[)" + zone + "]}", "line 2: vertex index 2 points to none"},
      {"grammar", R"({"type":"FeatureCollection","exacity":{"zones":{"park":{"layout":"grammar","grammar":"bad.grammar"}}},"features":[)" + zone + "]}", "bad.grammar:2: the corner count \"5\""},
      {"deadend", R"({"type":"FeatureCollection","exacity":{"roads":{"dead_ends":"error"}},"features":[)" + zone + R"(,{"type":"Feature","properties":{"road":"local"},"geometry":{"type":"LineString","coordinates":[[0,0],[9,9]]}}]})", "meeting no other road"},
  };
  std::ofstream(dir / "bad-library.json") << R"({"models": [{"file": "bad.obj", "zones": ["residential"]}]})";
  std::ofstream(dir / "bad.obj") << "v 0 0 0\nf 1 2 5\n";
  std::ofstream(dir / "bad.grammar") << "1 Town 4 Park,0,0,1,0,1,1,0,1\n1 Park 5 Park,0,0,1,0,1,1,0,1\n";
  for (const Case& c : cases) {
    fs::path sketch = dir / (c.name + ".geojson");
    std::ofstream(sketch) << c.text;
    fs::path out = dir / ("out-" + c.name);
    Result r = run("generate " + sketch.string() + " -o " + out.string() + " --quiet");
    EXPECT_EQ(r.code, 2) << c.name << ": " << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.name << ": " << r.out;
    std::string file = c.name == "heightmap" ? (dir / "missing.png").string()
                       : c.name == "library" ? (dir / "missing.json").string()
                       : c.name == "model"   ? (dir / "bad.obj").string()
                       : c.name == "grammar" ? (dir / "bad.grammar").string()
                                             : sketch.string();
    EXPECT_NE(r.out.find(file), std::string::npos) << "names the file: " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << "one line: " << r.out;
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  // No staging folder left behind either.
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string().find(".out-"), std::string::npos);
}

TEST(Cli, OutputPathsThatMustNotBeOverwritten) {
  fs::path dir = testing_util::temp_dir("cli-paths");
  const std::string sketch = small_sketch(dir).string();
  std::ofstream(dir / "a-file") << "mine";
  Result r = run("generate " + sketch + " -o " + (dir / "a-file").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("is a file"), std::string::npos) << r.out;
  EXPECT_EQ(read(dir / "a-file"), "mine");

  fs::create_directories(dir / "notes");
  std::ofstream(dir / "notes" / "todo.txt") << "keep me";
  r = run("generate " + sketch + " -o " + (dir / "notes").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(read(dir / "notes" / "todo.txt"), "keep me");

  // An earlier exacity output is replaced whole.
  ASSERT_EQ(run("generate " + sketch + " -o " + (dir / "out").string() + " -q").code, 0);
  std::ofstream(dir / "out" / "stale.txt") << "old";
  ASSERT_EQ(run("generate " + sketch + " -o " + (dir / "out").string() + " -q").code, 0);
  EXPECT_FALSE(fs::exists(dir / "out" / "stale.txt"));
}

TEST(Cli, StagingFoldersOfDeadRunsAreRemovedAndAnInterruptLeavesNoTrace) {
  fs::path dir = testing_util::temp_dir("cli-staging");
  const std::string sketch = small_sketch(dir).string();
  // What a crashed or killed run leaves: its process is gone (pids stop below 2^22 on Linux).
  fs::create_directories(dir / ".out.partial-4999999" / "inside");
  fs::create_directories(dir / ".out.old-4999998");
  fs::create_directories(dir / ".other.partial-4999999");
  ASSERT_EQ(run("generate " + sketch + " -o " + (dir / "out").string() + " -q").code, 0);
  EXPECT_FALSE(fs::exists(dir / ".out.partial-4999999"));
  EXPECT_FALSE(fs::exists(dir / ".out.old-4999998"));
  EXPECT_TRUE(fs::exists(dir / ".other.partial-4999999")) << "another output's folder is not this run's to remove";
  const std::string before = read(dir / "out" / "report.json");

  // SIGTERM while a long run writes into the same place: the earlier output stays whole.
  std::string big = (kSource / "benchmarks" / "city_10km.geojson").string();
  std::string cmd = std::string(EXACITY_BINARY) + " generate " + big + " -o " + (dir / "out").string() +
                    " -q > /dev/null 2>&1 & echo $!";
  FILE* pipe = popen(cmd.c_str(), "r");
  int pid = 0;
  ASSERT_EQ(fscanf(pipe, "%d", &pid), 1);
  pclose(pipe);
  const fs::path staging = dir / (".out.partial-" + std::to_string(pid));
  for (int i = 0; i < 600 && !fs::exists(staging); ++i) usleep(100000);
  ASSERT_TRUE(fs::exists(staging));
  kill(pid, SIGTERM);
  for (int i = 0; i < 600 && kill(pid, 0) == 0; ++i) usleep(100000);
  EXPECT_NE(kill(pid, 0), 0) << "still running";
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_EQ(read(dir / "out" / "report.json"), before);
}

TEST(Cli, HelpAndVersion) {
  Result h = run("--help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("generate"), std::string::npos);
  EXPECT_NE(h.out.find("validate"), std::string::npos);
  EXPECT_EQ(run("generate --help").code, 0);
  Result v = run("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.out.find("exacity 0."), std::string::npos);
  EXPECT_EQ(run("frobnicate").code, 2);
  EXPECT_EQ(run("generate").code, 2);  // no sketch
}


TEST(Cli, AGridMapWithModelsGeneratesValidatesAndRendersTheSameCity) {
  fs::path dir = testing_util::temp_dir("cli-grid");
  std::ofstream(dir / "city.grid") << "; a few blocks\ncell 10\n"
                                      "rrrrr=ccccc\n"
                                      "rrrrr=ccccc\n"
                                      "rrrrr=ccccc\n"
                                      "rrrrr=ccccc\n"
                                      "===========\n"
                                      "rrrrr=\"\"\"\"\"\n"
                                      "rrrrr=\"~~~\"\n"
                                      "rrrrr=\"\"\"\"\"\n";
  const fs::path out = dir / "out", library = kSource / "examples" / "models" / "library.json";
  Result r = run("generate " + (dir / "city.grid").string() + " -o " + out.string() + " -q --models " + library.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(run("validate " + out.string()).code, 0);
  const auto report = nlohmann::json::parse(read(out / "report.json"));
  EXPECT_TRUE(report["validation"]["ok"].get<bool>());
  EXPECT_GT(report["counts"]["gltf"]["instances"].get<int>(), 0) << "the library's models stand in the city";
  EXPECT_NE(read(out / "sketch.geojson").find(library.filename().string()), std::string::npos);
  // render rebuilds the city from the copy: the same models.
  r = run("render " + out.string() + " --size 48x32 --spp 1 -q");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto still = nlohmann::json::parse(read(out / "render" / "still.json"));
  EXPECT_GT(still["scene"]["instances"].get<int>(), 0) << still["scene"];

  // A mistake in the map: one line naming the file, line and column; no output.
  std::ofstream(dir / "bad.grid") << "cell 10\nrrr\nrqr\n";
  r = run("generate " + (dir / "bad.grid").string() + " -o " + (dir / "bad-out").string() + " -q");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find((dir / "bad.grid").string() + ":3:2: 'q' is not a cell"), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_FALSE(fs::exists(dir / "bad-out"));
  r = run("generate " + (dir / "city.grid").string() + " -o " + (dir / "bad-out").string() + " -q --models " +
          (dir / "none.json").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find((dir / "none.json").string() + ": cannot read the model library"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--models"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "bad-out"));
}

namespace {

// A residential block of 160 m by 120 m generated into `out`, for the render tests.
Result generate_one_street_block(const fs::path& dir, const fs::path& out) {
  std::ofstream(dir / "city.geojson") << R"({"type": "FeatureCollection", "exacity": {"seed": 5}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [160, 0], [160, 120], [0, 120], [0, 0]]]}}]})";
  return run("generate " + (dir / "city.geojson").string() + " -o " + out.string() + " -q");
}

}  // namespace

// A camera path's frames, rendered whole, in ranges, in shares and through
// scripts/render_path.sbatch's tasks (Slurm's environment by hand), are the same files; a bad path file is one line naming it and its key; --time records
// its passes; --denoise, --exposure and --white-balance are taken and recorded.
TEST(Cli, CameraPathFramesInRangesEqualOneRunAndBadPathsAreOneLine) {
  fs::path dir = testing_util::temp_dir("cli-path");
  const fs::path out = dir / "out";
  Result r = generate_one_street_block(dir, out);
  ASSERT_EQ(r.code, 0) << r.out;
  std::ofstream(dir / "path.json") << R"({"fps": 2, "keys": [
    {"t": 0, "camera": "orbit:target=80,60,0,azimuth=200,elevation=35,distance=200"},
    {"t": 1.5, "camera": "look:from=-50,-80,60,to=80,60,0"}]})";
  const std::string common = "render " + out.string() + " --path " + (dir / "path.json").string() +
                             " --size 32x24 --spp 2 -q -o ";
  r = run(common + (dir / "whole").string());
  ASSERT_EQ(r.code, 0) << r.out;
  // scripts/render_path.sbatch's two tasks of an array begun at 4, without Slurm: its
  // environment by hand.
  for (int task : {4, 5}) {
    const Result job = shell("SLURM_ARRAY_TASK_ID=" + std::to_string(task) +
                             " SLURM_ARRAY_TASK_MIN=4 SLURM_ARRAY_TASK_MAX=5 SLURM_CPUS_PER_TASK=1 EXACITY=" +
                             EXACITY_BINARY + " bash " + (kSource / "scripts" / "render_path.sbatch").string() + " " +
                             out.string() + " " + (dir / "path.json").string() + " " + (dir / "array").string() +
                             " --size 32x24 --spp 2");
    ASSERT_EQ(job.code, 0) << job.out;
  }
  ASSERT_EQ(run(common + (dir / "parts").string() + " --frames 2:3").code, 0);
  ASSERT_EQ(run(common + (dir / "parts").string() + " --frames 0:1").code, 0);
  for (int n = 0; n < 4; ++n) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", n);
    const std::string whole = read(dir / "whole" / name);
    ASSERT_FALSE(whole.empty()) << name;
    EXPECT_TRUE(whole == read(dir / "parts" / name)) << name;
    EXPECT_TRUE(whole == read(dir / "array" / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "whole" / "frame_0004.png")) << "1.5 s at 2 fps is frames 0 to 3";

  r = run(common + (dir / "bad").string() + " --frames 3:9");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("--frames 3:9"), std::string::npos) << r.out;
  std::ofstream(dir / "bad.json") << R"({"fps": 2, "keys": [{"t": 0, "camera": "look:from=0,0,50,to=1,1,0"},
    {"t": 1, "camera": "orbit:target=0,0,0,azimuth=20"}]})";
  r = run("render " + out.string() + " --path " + (dir / "bad.json").string() + " -q -o " + (dir / "bad").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find((dir / "bad.json").string() + ": keys[1]: camera"), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_FALSE(fs::exists(dir / "bad" / "frame_0000.png"));

  r = run("render " + out.string() + " --size 32x24 --spp 1 --time 0.3 --denoise off --exposure 1 --white-balance 4000 -q -o " +
          (dir / "still.png").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const auto still = nlohmann::json::parse(read(dir / "still.json"));
  EXPECT_GE(still["passes"].get<int>(), 1);
  EXPECT_EQ(still["samples_per_pixel"].get<int>(), still["passes"].get<int>());
  EXPECT_FALSE(still["denoised"].get<bool>());
  EXPECT_EQ(still["exposure_ev"].get<double>(), 1);
  EXPECT_EQ(still["white_balance_k"].get<double>(), 4000);
  // --landscape-trees off: the land beyond the city without its woods' and hedgerows' trees,
  // as city.glb has it (the Cycles comparison's scene); the same view has them by default.
  EXPECT_TRUE(still["landscape_trees"].get<bool>());
  EXPECT_GT(still["scene"]["landscape_instances"].get<int>(), 0);
  r = run("render " + out.string() + " --size 32x24 --spp 1 --denoise off --landscape-trees off -q -o " +
          (dir / "bare.png").string());
  ASSERT_EQ(r.code, 0) << r.out;
  const auto bare = nlohmann::json::parse(read(dir / "bare.json"));
  EXPECT_FALSE(bare["landscape_trees"].get<bool>());
  EXPECT_EQ(bare["scene"]["landscape_instances"].get<int>(), 0);
  EXPECT_EQ(run("render " + out.string() + " --landscape-trees some -q").code, 2);
  EXPECT_EQ(run("render " + out.string() + " --denoise maybe -q").code, 2);
}

// The pedestrian and the flyer as stills and in a path, depth of field's flags
// recorded; a bad camera (its syntax, or a road the city does not have) is one line and
// exit 2, with nothing written.
TEST(Cli, PedestrianAndFlyerCamerasAndTheirMistakes) {
  fs::path dir = testing_util::temp_dir("cli-cameras");
  const fs::path out = dir / "out";
  Result r = generate_one_street_block(dir, out);
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string render = "render " + out.string() + " --size 32x24 --spp 1 -q ";
  r = run(render + "--camera pedestrian:road=0,along=10 --aperture 0.05 --focus-tilt 10 -o " + (dir / "walk.png").string());
  ASSERT_EQ(r.code, 0) << r.out;
  auto walk = nlohmann::json::parse(read(dir / "walk.json"));
  EXPECT_NEAR(walk["camera"]["from"][2].get<double>(), 1.7, 1e-5) << "flat: the eye 1.7 m over z = 0";
  EXPECT_NEAR(walk["camera"]["aperture"].get<double>(), 0.05, 1e-6);
  EXPECT_EQ(walk["camera"]["focus_tilt"].get<double>(), 10);
  r = run(render + "--camera flyer:at=80,60,height=50,heading=45,pitch=-30 -o " + (dir / "fly.png").string());
  ASSERT_EQ(r.code, 0) << r.out;
  auto fly = nlohmann::json::parse(read(dir / "fly.json"));
  EXPECT_NEAR(fly["camera"]["from"][2].get<double>(), 50, 1e-5);
  EXPECT_NEAR(fly["camera"]["from"][0].get<double>(), 80, 1e-5);
  r = run(render + "--time-of-day 12:00 --date 2024-03-01 -o " + (dir / "leap.png").string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(nlohmann::json::parse(read(dir / "leap.json"))["day_of_year"].get<int>(), 31 + 29 + 1);

  const std::pair<std::string, std::string> bad[] = {
      {"--camera pedestrian:road=999,along=0", "--camera \"pedestrian:road=999,along=0\": the city has no road 999"},
      {"--camera flyer:at=0,0,height=10", "--camera \"flyer:at=0,0,height=10\": missing heading="},
      {"--camera pedestrian:at=0,0,heading=0,eye=-1", "eye=-1 is outside 0.1 to 100"},
      {"--time-of-day 24:10", "--time-of-day 24:10: expected HH:MM from 00:00 to 23:59"},
      {"--time-of-day 9h30", "--time-of-day 9h30: expected HH:MM"},
      {"--night --date 02-30", "--date 02-30: expected MM-DD or YYYY-MM-DD, such as 06-21 or 2024-12-21 (no such day)"},
      {"--night --date 2023-02-29", "--date 2023-02-29: expected MM-DD or YYYY-MM-DD"},
      {"--night --date 21.6.", "--date 21.6.: expected MM-DD or YYYY-MM-DD"},
      {"--date 06-21", "--date 06-21: a date sets the hour's sun; give --time-of-day HH:MM or --night with it"},
  };
  for (const auto& [args, expected] : bad) {
    r = run(render + args + " -o " + (dir / "bad" / "still.png").string());
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_NE(r.out.find(expected), std::string::npos) << args << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_FALSE(fs::exists(dir / "bad")) << args;
  }
  for (const char* args : {"--aperture -1", "--focus-tilt 90"}) {  // CLI11's own checks
    r = run(render + args + " -o " + (dir / "bad" / "still.png").string());
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_FALSE(fs::exists(dir / "bad")) << args;
  }
  // A walk in a path file: every frame's eye 1.7 m over the flat ground.
  std::ofstream(dir / "stroll.json") << R"({"fps": 2, "keys": [{"t": 0, "camera": "pedestrian:road=0,along=0"},
    {"t": 1, "camera": "pedestrian:road=0,along=30"}]})";
  r = run(render + "--path " + (dir / "stroll.json").string() + " -o " + (dir / "stroll").string());
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* frame : {"frame_0000.json", "frame_0001.json", "frame_0002.json"})
    EXPECT_NEAR(nlohmann::json::parse(read(dir / "stroll" / frame))["camera"]["from"][2].get<double>(), 1.7, 1e-5)
        << frame;
  // In a path: the key that names a road the city lacks, before any frame is written.
  std::ofstream(dir / "walk.json") << R"({"fps": 2, "keys": [{"t": 0, "camera": "pedestrian:road=0,along=0"},
    {"t": 1, "camera": "pedestrian:road=4000,along=30"}]})";
  r = run(render + "--path " + (dir / "walk.json").string() + " -o " + (dir / "frames").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find((dir / "walk.json").string() + ": keys[1]: camera \"pedestrian:road=4000,along=30\": the city has no road 4000"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_FALSE(fs::exists(dir / "frames"));
  // A sketch's own camera is checked before any work.
  std::ofstream(dir / "flyer.geojson") << R"({"type": "FeatureCollection", "exacity": {"camera": "flyer:at=1,2"},
    "features": [{"type": "Feature", "properties": {"zone": "park"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [50, 0], [50, 50], [0, 0]]]}}]})";
  r = run("generate " + (dir / "flyer.geojson").string() + " --render -q -o " + (dir / "flyer-out").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("\"exacity\".camera \"flyer:at=1,2\": missing heading="), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "flyer-out"));
}

// A grid map 1e10 m from the origin generates and validates, but its floats there are a
// kilometre apart: a pedestrian's eye and the point 20 m ahead are one point, a ray with no
// direction that Embree aborts on. The camera is refused with one line instead.
TEST(Cli, AGroundCameraTooFarFromTheOriginForTheRenderersFloatsIsOneLine) {
  fs::path dir = testing_util::temp_dir("cli-far-camera");
  std::ofstream(dir / "far.grid") << "cell 10\norigin -1e10 -1e10\nrr=rr\n=====\nrr=rr\n";
  const fs::path out = dir / "out";
  Result r = run("generate " + (dir / "far.grid").string() + " -o " + out.string() + " -q --threads 1");
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* camera : {"pedestrian:road=0,along=0", "pedestrian:road=1,along=5,ahead=-30"}) {
    r = run("render " + out.string() + " --size 32x24 --spp 1 -q --camera " + camera + " -o " +
            (dir / "bad" / "still.png").string());
    EXPECT_EQ(r.code, 2) << camera << ": " << r.out;
    EXPECT_NE(r.out.find("--camera \"" + std::string(camera) + "\": the eye at (-1e+10"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("generate the city nearer the origin"), std::string::npos) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_FALSE(fs::exists(dir / "bad")) << camera;
  }
}

// A highway from -1e10 to 1e10 m, the whole coordinate range, through a small town: its
// clutter was sought a station every few metres all the way, a run of years. Where no zone
// is near the road there is nothing to dress, and the stations there are passed over.
TEST(Cli, AHighwayAcrossTheWholeCoordinateRangeIsDressedOnlyWhereZonesAre) {
  fs::path dir = testing_util::temp_dir("cli-long-highway");
  std::ofstream(dir / "alone.geojson") << R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"road": "highway"},
     "geometry": {"type": "LineString", "coordinates": [[-1e10, 0], [1e10, 0]]}}]})";
  std::ofstream(dir / "town.geojson") << R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, -100], [200, -100], [200, 100], [0, 100], [0, -100]]]}},
    {"type": "Feature", "properties": {"road": "highway"},
     "geometry": {"type": "LineString", "coordinates": [[-1e10, 0], [1e10, 0]]}}]})";
  for (const char* sketch : {"alone", "town"}) {
    const fs::path out = dir / (std::string(sketch) + "-out");
    Result r = shell("timeout 60 " + std::string(EXACITY_BINARY) + " generate " + (dir / (std::string(sketch) + ".geojson")).string() +
                     " -o " + out.string() + " -q --threads 1");
    ASSERT_EQ(r.code, 0) << sketch << ": " << r.out;
    const auto clutter = nlohmann::json::parse(read(out / "vector" / "clutter.geojson"))["features"];
    if (std::string(sketch) == "alone") {
      EXPECT_TRUE(clutter.empty());
      continue;
    }
    // The town's stretch of the highway has its lamps, and only there.
    int lamps = 0;
    for (const auto& f : clutter) {
      const auto& p = f["geometry"]["coordinates"];
      EXPECT_GT(p[0].get<double>(), -20) << f.dump();
      EXPECT_LT(p[0].get<double>(), 220) << f.dump();
      lamps += f["properties"]["kind"] == "lamp";
    }
    EXPECT_GE(lamps, 4);
  }
}

namespace {

// The program under a time limit: a hang fails the test (exit 124) instead of stalling it.
Result run_within_a_minute(const std::string& args) { return shell("timeout 60 " + std::string(EXACITY_BINARY) + " " + args); }

}  // namespace

// Every file a sketch names is read only when it is a regular file: a device such as
// /dev/zero hung the run or took memory without end, and a folder read as an empty file.
TEST(Cli, InputsThatAreNotRegularFilesAreOneLineAndExitTwo) {
  fs::path dir = testing_util::temp_dir("cli-not-files");
  const std::string zone =
      R"({"type":"Feature","properties":{"zone":"residential"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[300,0],[300,200],[0,200],[0,0]]]}})";
  const std::string device = " (it is not a regular file but a device, pipe or socket); ";
  struct Case {
    std::string name, settings, expect;
  };
  const std::vector<Case> cases = {
      {"heightmap", R"({"terrain":{"heightmap":"/dev/zero","bounds":[0,0,300,200]}})",
       "/dev/zero: heightmap cannot be read" + device},
      {"grammar", R"({"zones":{"residential":{"layout":"grammar","grammar":"/dev/zero"}}})",
       "/dev/zero: cannot read the grammar" + device},
      {"grammar-folder", R"({"zones":{"residential":{"layout":"grammar","grammar":"."}}})",
       (dir / ".").string() + ": cannot read the grammar (it is a folder); "},
      {"grid", R"({"grid":"/dev/zero"})", "cannot read the grid map /dev/zero" + device},
      {"models", R"({"models":"/dev/zero"})", "/dev/zero: cannot read the model library" + device},
  };
  for (const Case& c : cases) {
    const fs::path sketch = dir / (c.name + ".geojson"), out = dir / ("out-" + c.name);
    std::ofstream(sketch) << R"({"type":"FeatureCollection","exacity":)" + c.settings + R"(,"features":[)" + zone + "]}";
    const Result r = run_within_a_minute("generate " + sketch.string() + " -o " + out.string() + " -q --threads 1");
    EXPECT_EQ(r.code, 2) << c.name << ": " << r.out;
    EXPECT_EQ(r.out.rfind("exacity: error: ", 0), 0u) << c.name << ": " << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.name << ": " << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << c.name << ": " << r.out;
    EXPECT_FALSE(fs::exists(out)) << c.name;
  }
  // A model library's OBJ file that is a device: refused before it is read.
  std::ofstream(dir / "library.json") << R"({"models": [{"file": "/dev/zero", "zones": ["residential"]}]})";
  Result r = run_within_a_minute("generate " + small_sketch(dir).string() + " --models " + (dir / "library.json").string() +
                                 " -o " + (dir / "out-obj").string() + " -q --threads 1");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out, "exacity: error: /dev/zero: cannot read the model file" + device + "name an .obj file in the model library\n");
  r = run_within_a_minute("generate /dev/zero -o " + (dir / "out-sketch").string() + " -q");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out.rfind("exacity: error: /dev/zero: cannot read the sketch" + device, 0), 0u) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
}

// A render's -o that is a file, where a folder must go, is the user's to fix (exit 2, one
// line, before the city is built), as generate's is; so is a camera path that is a device.
TEST(Cli, RenderOutputsThatAreFilesAndPathsThatAreDevicesAreOneLine) {
  fs::path dir = testing_util::temp_dir("cli-render-paths");
  const fs::path out = dir / "out";
  Result r = generate_one_street_block(dir, out);
  ASSERT_EQ(r.code, 0) << r.out;
  std::ofstream(dir / "path.json") << R"({"fps": 1, "keys": [{"t": 0, "camera": "look:from=-50,-80,60,to=80,60,0"},
    {"t": 1, "camera": "look:from=-40,-80,60,to=80,60,0"}]})";
  std::ofstream(dir / "a-file") << "mine";
  const std::string render = "render " + out.string() + " --size 16x16 --spp 1 -q ";
  r = run_within_a_minute(render + "--path " + (dir / "path.json").string() + " --frames 0:0 -o " + (dir / "a-file").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out, "exacity: error: " + (dir / "a-file").string() +
                       ": is a file, so the frames cannot be written there; choose a folder path with -o\n");
  r = run_within_a_minute(render + "-o " + (dir / "a-file" / "still.png").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out, "exacity: error: " + (dir / "a-file").string() +
                       ": is a file, so the still cannot be written there; choose a folder path with -o\n");
  fs::create_directories(dir / "folder.png");
  r = run_within_a_minute(render + "-o " + (dir / "folder.png").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_EQ(read(dir / "a-file"), "mine");
  r = run_within_a_minute(render + "--path /dev/zero -o " + (dir / "frames").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out, "exacity: error: /dev/zero: cannot read the camera path (it is not a regular file but a device, pipe or "
                   "socket); give a camera path's JSON file to --path\n");
  EXPECT_FALSE(fs::exists(dir / "frames"));
}

// A city without roads has no road to stand on: said so, not "its roads are 0 to -1".
TEST(Cli, APedestrianOnARoadOfACityWithoutRoadsIsOneLine) {
  fs::path dir = testing_util::temp_dir("cli-no-roads");
  std::ofstream(dir / "park.geojson") << R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"zone": "park"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [50, 0], [50, 50], [0, 0]]]}}]})";
  Result r = run("generate " + (dir / "park.geojson").string() + " -q -o " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.out;
  r = run("render " + (dir / "out").string() + " --camera pedestrian:road=0,along=0 --size 16x16 --spp 1 -q");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out, "exacity: error: --camera \"pedestrian:road=0,along=0\": the city has no roads to stand on; use "
                   "pedestrian:at=X,Y,heading=DEG instead\n");
}

// PROJ's own complaint ("ERROR 1: PROJ: proj_create_from_database: crs not found") went to
// stderr before Exacity's line: a CRS PROJ does not know is one line.
TEST(Cli, AnUnknownCrsIsOneLineWithoutProjsOwn) {
  fs::path dir = testing_util::temp_dir("cli-unknown-crs");
  std::ofstream(dir / "crs.geojson") << R"({"type": "FeatureCollection",
    "crs": {"type": "name", "properties": {"name": "EPSG:999999"}}, "features": [
    {"type": "Feature", "properties": {"zone": "park"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [50, 0], [50, 50], [0, 0]]]}}]})";
  const Result r = run("generate " + (dir / "crs.geojson").string() + " -q -o " + (dir / "out").string());
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out.rfind("exacity: error: " + (dir / "crs.geojson").string() + ": crs: ", 0), 0u) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
}

namespace {

// An OSM way of `nodes` nodes alternating between two parallel lines 110 m apart, each
// node at a scrambled place along them, so the road runs back and forth across itself.
std::string zig_zag_osm(int nodes) {
  std::ostringstream s;
  s.precision(10);
  for (int i = 0; i < nodes; ++i)
    s << "  <node id=\"" << 900000 + i << "\" version=\"1\" lat=\"" << (i % 2 ? 48.002 : 48.001) << "\" lon=\""
      << 10 + 0.003 * ((i * 7919) % nodes) / nodes << "\"/>\n";
  s << "  <way id=\"900000\" version=\"1\">\n";
  for (int i = 0; i < nodes; ++i) s << "    <nd ref=\"" << 900000 + i << "\"/>\n";
  s << "    <tag k=\"highway\" v=\"residential\"/>\n  </way>\n";
  return s.str();
}

}  // namespace

// A way zig-zagging across itself: every crossing of its strokes is vertices of the exact
// map, quadratic in its nodes (400 nodes made gigabytes and ran for hours; alone, or with
// 2,000 in the village example). The crossings are counted first and the sketch refused.
TEST(Cli, AWayRunningAcrossItselfHundredsOfTimesIsRefusedBeforeTheMap) {
  fs::path dir = testing_util::temp_dir("cli-zig-zag");
  std::ofstream(dir / "zigzag.osm") << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<osm version=\"0.6\">\n"
                                    << zig_zag_osm(400) << "</osm>\n";
  std::string village = read(kSource / "examples" / "osm" / "village.osm");
  village.insert(village.rfind("</osm>"), zig_zag_osm(2000));
  std::ofstream(dir / "village.osm") << village;
  for (const char* sketch : {"zigzag.osm", "village.osm"}) {
    const fs::path out = dir / (std::string(sketch) + "-out");
    Result r = shell("timeout 60 " + std::string(EXACITY_BINARY) + " generate " + (dir / sketch).string() + " -o " +
                     out.string() + " -q --threads 1");
    EXPECT_EQ(r.code, 2) << sketch << ": " << r.out;
    EXPECT_NE(r.out.find("way 900000"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("cross or overlap one another more than"), std::string::npos) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_FALSE(fs::exists(out)) << sketch;
  }
  // The village itself, real towns and a few dozen nodes of zig-zag are far under the limit.
  std::ofstream(dir / "few.osm") << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<osm version=\"0.6\">\n"
                                 << zig_zag_osm(40) << "</osm>\n";
  Result r = run("generate " + (dir / "few.osm").string() + " -o " + (dir / "few-out").string() + " -q --threads 1");
  EXPECT_EQ(r.code, 0) << r.out;
}


// The village with 5,000 tiny triangles of land use (1.7 MB) over its streets: OSM land use
// reaches 8 m further where streets come with it, so each 2 m triangle becomes a rounded
// area overlapping hundreds of the others, and the exact map of their crossings grew past
// 6 GB. Their edges' crossings are counted first and the sketch refused.
TEST(Cli, ThousandsOfTinyLandUseAreasOverTheVillageAreRefusedBeforeTheMap) {
  fs::path dir = testing_util::temp_dir("cli-land-use-triangles");
  std::ostringstream areas;
  areas.precision(10);
  const char* const uses[] = {"residential", "commercial", "industrial", "retail", "grass", "forest"};
  for (int i = 0; i < 5000; ++i) {
    // Scattered over 110 x 75 m at the village's middle, 2 m a side.
    const double lat = 48.0013 + 0.001 * ((i * 7919) % 5000) / 5000, lon = 10.0035 + 0.001 * ((i * 104729) % 4999) / 4999;
    for (int k = 0; k < 3; ++k)
      areas << "  <node id=\"" << 700000 + 3 * i + k << "\" version=\"1\" lat=\"" << lat + (k == 1 ? 0.00002 : 0)
            << "\" lon=\"" << lon + (k == 2 ? 0.00003 : 0) << "\"/>\n";
    areas << "  <way id=\"" << 800000 + i << "\" version=\"1\">";
    for (int k : {0, 1, 2, 0}) areas << "<nd ref=\"" << 700000 + 3 * i + k << "\"/>";
    areas << "<tag k=\"landuse\" v=\"" << uses[i % 6] << "\"/></way>\n";
  }
  std::string village = read(kSource / "examples" / "osm" / "village.osm");
  village.insert(village.rfind("</osm>"), areas.str());
  std::ofstream(dir / "village.osm") << village;
  const fs::path out = dir / "out";
  const Result r = shell("timeout 60 " + std::string(EXACITY_BINARY) + " generate " + (dir / "village.osm").string() +
                         " -o " + out.string() + " -q --threads 1");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out.rfind("exacity: error: " + (dir / "village.osm").string() + " way ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("cross or overlap one another more than"), std::string::npos) << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

// An industrial L and a 60 m residential L inside its bend: growth started cells of the
// narrow arm a centimetre inside their edge and left roads of 2 to 40 cm there, one ending
// alone on the zone's edge (road 372, 10 cm); and two narrow zones, 40 m and 30 m wide,
// touching at a corner. Then a 60 m commercial spiral (straight roads), a 45 m L 10 m off the
// industrial L's bend (another seed), and a comb of 50 m teeth: started a centimetre inside an
// edge, growth left stubs of centimetres in each. No generated road is shorter than its zone's
// min_block_width, and none ends in the open: every dead end is a sketch road's.
TEST(Cli, GrowthLeavesNoRoadShorterThanABlockIsWideNorADeadEnd) {
  std::ostringstream spiral;  // 60 m wide, over a turn, straight roads (commercial)
  spiral.precision(10);
  spiral << R"({"type": "FeatureCollection", "exacity": {"seed": 23}, "features": [{"type": "Feature", )"
         << R"("properties": {"zone": "commercial"}, "geometry": {"type": "Polygon", "coordinates": [[)";
  for (int k = 0; k <= 240; ++k) {  // out along the inner side, back along the outer, closed
    const int i = k < 120 ? k : k < 240 ? 239 - k : 0;
    const double a = i * 0.06, r = 120 + a * 50 + (k >= 120 && k < 240 ? 60 : 0);
    spiral << (k ? ", " : "") << "[" << r * std::cos(a) << ", " << r * std::sin(a) << "]";
  }
  spiral << "]]}}]}";
  // The industrial L of the sketch that had the stubs, and a residential zone (its ring) in its bend.
  auto beside_industrial_l = [](int seed, const std::string& residential) {
    return R"({"type": "FeatureCollection", "exacity": {"seed": )" + std::to_string(seed) + R"(}, "features": [
    {"type": "Feature", "properties": {"zone": "industrial"}, "geometry": {"type": "Polygon",
     "coordinates": [[[0, 0], [3000, 0], [3000, 600], [600, 600], [600, 2500], [0, 2500], [0, 0]]]}},
    {"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon",
     "coordinates": [)" +
           residential + "]}}]}";
  };
  const std::vector<std::pair<std::string, std::string>> sketches{
      {"two-ls", beside_industrial_l(
                     23, "[[700, 700], [3000, 700], [3000, 760], [760, 760], [760, 2500], [700, 2500], [700, 700]]")},
      {"corner", R"({"type": "FeatureCollection", "exacity": {"seed": 7}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon",
     "coordinates": [[[0, 0], [40, 0], [40, 800], [0, 800], [0, 0]]]}},
    {"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon",
     "coordinates": [[[40, 800], [840, 800], [840, 830], [40, 830], [40, 800]]]}}]})"},
      {"spiral", spiral.str()},
      {"ten-off", beside_industrial_l(
                      4, "[[610, 610], [3000, 610], [3000, 655], [655, 655], [655, 2500], [610, 2500], [610, 610]]")},
      {"comb", R"({"type": "FeatureCollection", "exacity": {"seed": 23}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"}, "geometry": {"type": "Polygon", "coordinates": [[[0, 0],
     [1000, 0], [1000, 500], [950, 500], [950, 100], [850, 100], [850, 500], [800, 500], [800, 100], [700, 100],
     [700, 500], [650, 500], [650, 100], [550, 100], [550, 500], [500, 500], [500, 100], [400, 100], [400, 500],
     [350, 500], [350, 100], [250, 100], [250, 500], [200, 500], [200, 100], [100, 100], [100, 500], [0, 500], [0, 0]]]}}]})"}};
  const double least = 6;  // the zones' min_block_width
  for (const auto& [name, sketch] : sketches) {
    SCOPED_TRACE(name);
    fs::path dir = testing_util::temp_dir("cli-stubs-" + name);
    const Result g = generate_in(dir, sketch);
    ASSERT_EQ(g.code, 0) << g.out;
    const auto roads = nlohmann::json::parse(read(dir / "out" / "vector" / "roads.geojson"))["features"];
    ASSERT_GT(roads.size(), 10u);
    for (const auto& f : roads) {
      const auto& c = f["geometry"]["coordinates"];
      double length = 0;
      for (std::size_t i = 1; i < c.size(); ++i)
        length += std::hypot(c[i][0].get<double>() - c[i - 1][0].get<double>(), c[i][1].get<double>() - c[i - 1][1].get<double>());
      EXPECT_GE(length, least) << "road " << f["properties"]["id"] << " from " << c.front().dump() << " to " << c.back().dump();
    }
    const auto report = nlohmann::json::parse(read(dir / "out" / "report.json"));
    EXPECT_EQ(report["statistics"]["streets"]["dead_ends"].get<int>(), 0);
    const Result v = run("validate " + (dir / "out").string());
    EXPECT_EQ(v.code, 0) << v.out;  // every generated road's end meets a road or a drawn edge
  }
}

TEST(Cli, AGrammarOfThousandsOfPiecesGeneratesAndValidates) {
  // Each Town splits into four Towns and two Roads, six deep: 4,096 blocks and 2,730 road
  // pieces. Settling the roads compared each with every other and the clutter walked the map
  // from its edge for every spot (seven deep took 111 s in the release build, 26 s now; the
  // figures are in docs/limits.md, timings stay out of the tests).
  const fs::path dir = testing_util::temp_dir("cli-deep-grammar");
  std::ofstream(dir / "split.grammar")
      << "1 Town 4 Town,0,0,0.5,0,0.5,0.5,0,0.5 Town,0.5,0,1,0,1,0.5,0.5,0.5 Town,0.5,0.5,1,0.5,1,1,0.5,1 "
         "Town,0,0.5,0.5,0.5,0.5,1,0,1 Road,0.45,0,0.55,0,0.55,1,0.45,1 Road,0,0.45,1,0.45,1,0.55,0,0.55\n";
  std::ofstream(dir / "deep.geojson") << R"({"type": "FeatureCollection", "exacity": {"zones": {"residential":
      {"layout": "grammar", "grammar": "split.grammar", "grammar_depth": 6, "min_block_area": 0.0001}}}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [600, 0], [600, 600], [0, 600], [0, 0]]]}}]})";
  const fs::path out = dir / "out";
  Result r = shell(std::string(EXACITY_BINARY) + " generate " + (dir / "deep.geojson").string() + " -o " + out.string() +
                   " -q --threads 1");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto report = nlohmann::json::parse(read(out / "report.json"));
  EXPECT_GT(report["road_network"]["roads"]["local"].get<int>(), 1000) << report["road_network"];
  EXPECT_TRUE(report["validation"]["ok"].get<bool>()) << report["validation"];
}
