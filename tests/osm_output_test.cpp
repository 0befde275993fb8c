// OpenStreetMap in and out as OSM tools expect it (docs/gis.md): city.osm
// read back with libosmium and GDAL's OSM driver (classes and names as read, negative ids
// apart between cities), extracts the edge cut, coordinates out of range, and real
// footprints measured whichever way their rings wind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <iomanip>
#include <set>
#include <sstream>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <osmium/handler.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/visitor.hpp>

#include "generate/sketch/sketch.h"
#include "generate/errors.h"
#include "generate/export/statistics.h"
#include "generate/gis/osm_tags.h"
#include "generate/gis/projection.h"
#include "generate/gis/sketch_sources.h"
#include "generate/pipeline.h"
#include "geom/measure.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

using namespace exacity;
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

const fs::path kVillage = cli_util::kSource / "examples" / "osm" / "village.osm";

void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

GenerateResult generate(const fs::path& sketch, const fs::path& out) {
  fs::remove_all(out);
  fs::create_directories(out);
  StageClock clock(nullptr, kCityStages + kWriteStages);
  const Sketch loaded = load_sketch(sketch);
  return write_city(loaded, build_city(loaded, clock), out, clock, {});
}

// city.osm as libosmium reads it: every id, and each way's tags.
struct OsmFile : osmium::handler::Handler {
  std::set<osmium::object_id_type> node_ids, way_ids;
  std::vector<std::map<std::string, std::string>> ways;
  void node(const osmium::Node& n) { node_ids.insert(n.id()); }
  void way(const osmium::Way& w) {
    way_ids.insert(w.id());
    std::map<std::string, std::string> tags;
    for (const osmium::Tag& t : w.tags()) tags[t.key()] = t.value();
    ways.push_back(std::move(tags));
  }
};

OsmFile read_osm(const fs::path& file) {
  OsmFile osm;
  osmium::io::Reader reader{file.string()};
  osmium::apply(reader, osm);
  reader.close();
  return osm;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(OsmOutput, RealFootprintsHaveTheirAreaWhicheverWayTheirRingsWind) {
  const fs::path dir = testing_util::temp_dir("osm-stats");
  // A 20 x 10 m footprint with a 2 x 2 m court, its outer ring clockwise and its hole
  // counter-clockwise (as ogr2ogr writes OSM's), and the same wound the other way.
  write(dir / "real.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [
      [[1000, 1000], [1000, 1010], [1020, 1010], [1020, 1000], [1000, 1000]],
      [[1004, 1004], [1006, 1004], [1006, 1006], [1004, 1006], [1004, 1004]]]}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [
      [[1100, 1000], [1120, 1000], [1120, 1010], [1100, 1010], [1100, 1000]],
      [[1104, 1004], [1104, 1006], [1106, 1006], [1106, 1004], [1104, 1004]]]}}]})");
  const ordered_json s = real_statistics(dir / "real.geojson");
  const ordered_json& areas = s["zones"]["all"]["footprints"]["area_m2"];
  EXPECT_EQ(areas["count"].get<int>(), 2);
  EXPECT_EQ(areas["median"].get<double>(), 196);
  EXPECT_EQ(areas["max"].get<double>(), 196);
}

TEST(OsmOutput, RealFootprintsAreMeasuredInGroundMetresWhateverTheirCrs) {
  const fs::path dir = testing_util::temp_dir("osm-stats-crs");
  // A 100 by 50 m footprint in Helsinki (UTM zone 35N), in Web Mercator (whose metres are
  // twice the ground's there) and in lon/lat without a crs: 5000 m2 on the ground in each.
  OGRSpatialReference utm, mercator, wgs84;
  utm.importFromEPSG(32635), mercator.importFromEPSG(3857), wgs84.importFromEPSG(4326);
  for (OGRSpatialReference* srs : {&utm, &mercator, &wgs84}) srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  for (const auto& [name, target, crs] : {std::tuple{"mercator.geojson", &mercator, crs_member(3857)},
                                          std::tuple{"lonlat.geojson", &wgs84, ordered_json()}}) {
    SCOPED_TRACE(name);
    std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&utm, target));
    ASSERT_TRUE(t);
    ordered_json ring = ordered_json::array();
    for (auto [x, y] : {std::pair{385000.0, 6672000.0}, {385100.0, 6672000.0}, {385100.0, 6672050.0}, {385000.0, 6672050.0},
                        {385000.0, 6672000.0}}) {
      ASSERT_TRUE(t->Transform(1, &x, &y));
      ring.push_back({x, y});
    }
    ordered_json doc = {{"type", "FeatureCollection"},
                        {"features", {{{"type", "Feature"}, {"properties", ordered_json::object()},
                                       {"geometry", {{"type", "Polygon"}, {"coordinates", {ring}}}}}}}};
    if (!crs.is_null()) doc["crs"] = crs;
    write(dir / name, doc.dump());
    const ordered_json s = real_statistics(dir / name);
    EXPECT_NEAR(s["zones"]["all"]["footprints"]["area_m2"]["median"].get<double>(), 5000, 0.1);
  }
}

TEST(OsmOutput, CityOsmKeepsTheClassesAndNamesItReadAndNewObjectsHaveNegativeIdsApartBetweenCities) {
  const fs::path dir = testing_util::temp_dir("osm-out");
  const GenerateResult village = generate(kVillage, dir / "village");
  ASSERT_TRUE(village.valid);
  const OsmFile osm = read_osm(dir / "village" / "city.osm");
  // Hauptstrasse is highway=primary with 4 lanes in the extract; its residential streets
  // are 7 m wide; the grown streets are tagged as a mapper would (no motorway).
  std::set<std::string> main_street, classes;
  int named = 0;
  for (const auto& tags : osm.ways) {
    if (!tags.count("highway")) continue;
    classes.insert(tags.at("highway"));
    if (tags.count("name") && tags.at("name") == "Hauptstrasse") {
      ++named;
      main_street.insert(tags.at("highway") + " lanes " + (tags.count("lanes") ? tags.at("lanes") : "none"));
    }
  }
  EXPECT_GT(named, 0);
  EXPECT_EQ(main_street, std::set<std::string>{"primary lanes 4"});
  for (const std::string& c : classes) EXPECT_TRUE(c == "primary" || c == "secondary" || c == "residential") << c;
  EXPECT_TRUE(classes.count("residential"));
  // New objects: negative ids.
  ASSERT_FALSE(osm.node_ids.empty());
  EXPECT_LT(*osm.node_ids.rbegin(), 0);
  EXPECT_LT(*osm.way_ids.rbegin(), 0);

  // Another city: `osmium merge` keeps both only if no id is in both.
  ordered_json other = ordered_json::parse(cli_util::read(kVillage.parent_path() / "village.exacity.json"));
  other["seed"] = other.value("seed", 1) + 1;
  fs::copy_file(kVillage, dir / "other.osm", fs::copy_options::overwrite_existing);
  write(dir / "other.exacity.json", other.dump());
  ASSERT_TRUE(generate(dir / "other.osm", dir / "other").valid);
  const OsmFile second = read_osm(dir / "other" / "city.osm");
  for (osmium::object_id_type id : second.node_ids) ASSERT_FALSE(osm.node_ids.count(id)) << "node " << id;
  for (osmium::object_id_type id : second.way_ids) ASSERT_FALSE(osm.way_ids.count(id)) << "way " << id;
  // The same city twice has the same ids: merged, it is one city.
  ASSERT_TRUE(generate(kVillage, dir / "again").valid);
  EXPECT_EQ(read_osm(dir / "again" / "city.osm").way_ids, osm.way_ids);

  // GDAL's OSM driver reads the streets with their classes and names (negative ids, as in
  // any file of new objects, need its SQLite node index).
  start_gdal();
  const CPLConfigOptionSetter indexing("OSM_USE_CUSTOM_INDEXING", "NO", false);
  GDALDatasetUniquePtr ds(GDALDataset::Open((dir / "village" / "city.osm").string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  ASSERT_TRUE(ds);
  OGRLayer* lines = ds->GetLayerByName("lines");
  ASSERT_NE(lines, nullptr);
  int streets = 0, primary = 0;
  for (OGRFeatureUniquePtr f(lines->GetNextFeature()); f; f.reset(lines->GetNextFeature())) {
    streets += std::string(f->GetFieldAsString("highway")) != "";
    primary += std::string(f->GetFieldAsString("name")) == "Hauptstrasse" && std::string(f->GetFieldAsString("highway")) == "primary";
  }
  EXPECT_EQ(streets, village.report["counts"]["roads"].get<int>());
  EXPECT_EQ(primary, named);
}

namespace {

// `osmium fileinfo -e`'s counts of a file's nodes, ways and relations (osmium-tool, which
// scripts/install-deps.sh installs).
std::map<std::string, int> osmium_counts(const fs::path& file) {
  const cli_util::Result info = cli_util::shell("osmium fileinfo -e -j " + file.string() + " 2>&1");
  EXPECT_EQ(info.code, 0) << info.out;
  const nlohmann::json doc = nlohmann::json::parse(info.out, nullptr, false);
  if (doc.is_discarded()) return {};
  const nlohmann::json& count = doc["data"]["count"];
  return {{"nodes", count.value("nodes", -1)}, {"ways", count.value("ways", -1)}, {"relations", count.value("relations", -1)}};
}

// How many lines GDAL's OSM driver reads from a file as streets (highway set); -1 when it
// cannot open it.
int gdal_streets(const fs::path& file) {
  start_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(file.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  OGRLayer* lines = ds ? ds->GetLayerByName("lines") : nullptr;
  if (!lines) return -1;
  int streets = 0;
  for (OGRFeatureUniquePtr f(lines->GetNextFeature()); f; f.reset(lines->GetNextFeature()))
    streets += std::string(f->GetFieldAsString("highway")) != "";
  return streets;
}

}  // namespace

TEST(OsmOutput, TwoCitiesMergedWithOsmiumLoseNoObject) {
  const fs::path dir = testing_util::temp_dir("osm-merge");
  ordered_json other = ordered_json::parse(cli_util::read(kVillage.parent_path() / "village.exacity.json"));
  other["seed"] = other.value("seed", 1) + 1;
  fs::copy_file(kVillage, dir / "other.osm", fs::copy_options::overwrite_existing);
  write(dir / "other.exacity.json", other.dump());
  for (const auto& [sketch, out] : {std::pair{kVillage, dir / "a"}, std::pair{dir / "other.osm", dir / "b"}}) {
    const cli_util::Result r = cli_util::run("generate " + sketch.string() + " -o " + out.string() + " -q");
    ASSERT_EQ(r.code, 0) << r.out;
  }
  const std::map<std::string, int> a = osmium_counts(dir / "a" / "city.osm"), b = osmium_counts(dir / "b" / "city.osm");
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_GT(a.at("nodes"), 100);
  EXPECT_GT(a.at("ways"), 10);
  const cli_util::Result merge = cli_util::shell("osmium merge " + (dir / "a" / "city.osm").string() + " " +
                                                 (dir / "b" / "city.osm").string() + " -o " + (dir / "both.osm").string() +
                                                 " --overwrite 2>&1");
  ASSERT_EQ(merge.code, 0) << merge.out;
  const std::map<std::string, int> both = osmium_counts(dir / "both.osm");
  for (const char* kind : {"nodes", "ways", "relations"}) EXPECT_EQ(both.at(kind), a.at(kind) + b.at(kind)) << kind;
  // GDAL's OSM driver reads the merged file's streets: both cities'.
  const CPLConfigOptionSetter indexing("OSM_USE_CUSTOM_INDEXING", "NO", false);
  const int streets = gdal_streets(dir / "both.osm");
  const auto roads = [&](const char* out) {
    return nlohmann::json::parse(cli_util::read(dir / out / "report.json"))["counts"]["roads"].get<int>();
  };
  EXPECT_EQ(streets, roads("a") + roads("b"));
}

TEST(OsmOutput, PedestrianStreetsAndAlleysAreNarrowLocalStreets) {
  auto meaning = [](std::map<std::string, std::string> tags) {
    return osm_line_meaning([&](const std::string& key) -> std::optional<std::string> {
      if (auto it = tags.find(key); it != tags.end()) return it->second;
      return std::nullopt;
    });
  };
  const OsmMeaning pedestrian = meaning({{"highway", "pedestrian"}});
  EXPECT_EQ(pedestrian.kind, OsmMeaning::Road);
  EXPECT_EQ(pedestrian.type, "local");
  EXPECT_EQ(pedestrian.width, 6);
  const OsmMeaning alley = meaning({{"highway", "service"}, {"service", "alley"}});
  EXPECT_EQ(alley.kind, OsmMeaning::Road);
  EXPECT_EQ(alley.type, "local");
  EXPECT_EQ(alley.width, 4);
  EXPECT_EQ(meaning({{"highway", "service"}, {"service", "driveway"}}).why, "service=driveway");
}

namespace {

// An extract cut at its bounds: a residential relation whose outer way the cut left open
// (north from (10.005, 48.001), then east to (10.008, 48.005)), and a street.
std::string cut_extract(const std::string& lat_of_node_7 = "48.005") {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6" generator="test">
  <bounds minlat="48.0" minlon="10.0" maxlat="48.01" maxlon="10.01"/>
  <node id="1" version="1" lat="48.001" lon="10.005"/>
  <node id="2" version="1" lat="48.005" lon="10.005"/>
  <node id="3" version="1" lat="48.005" lon="10.008"/>
  <node id="4" version="1" lat="48.002" lon="10.0055"/>
  <node id="5" version="1" lat="48.002" lon="10.0095"/>
  <node id="7" version="1" lat=")" + lat_of_node_7 + R"(" lon="10.007"/>
  <way id="10" version="1"><nd ref="1"/><nd ref="2"/><nd ref="3"/></way>
  <way id="11" version="1"><nd ref="4"/><nd ref="5"/><tag k="highway" v="residential"/></way>
  <way id="12" version="1"><nd ref="7"/><nd ref="3"/><tag k="highway" v="residential"/></way>
  <relation id="20" version="1">
    <member type="way" ref="10" role="outer"/>
    <tag k="type" v="multipolygon"/>
    <tag k="landuse" v="residential"/>
  </relation>
</osm>
)";
}

}  // namespace

TEST(OsmOutput, AMultipolygonTheExtractCutIsClosedAlongItsBoundsAndNamed) {
  const fs::path dir = testing_util::temp_dir("osm-cut");
  write(dir / "cut.osm", cut_extract());
  const ordered_json doc = osm_sketch_document(dir / "cut.osm");
  const ordered_json* zone = nullptr;
  for (const ordered_json& f : doc["features"])
    if (f["properties"].value("landuse", "") == "residential") zone = &f;
  ASSERT_NE(zone, nullptr) << doc.dump();
  // Each end goes on to the bounds (south from the first node, east from the last) and the
  // bounds close the ring round the side that holds less: the south-east corner.
  EXPECT_EQ((*zone)["geometry"]["coordinates"], ordered_json::parse(R"([[[[10.005, 48.001], [10.005, 48.005], [10.008, 48.005],
      [10.01, 48.005], [10.01, 48.0], [10.005, 48.0], [10.005, 48.001]]]])"));
  EXPECT_EQ((*zone)["properties"]["source"], (dir / "cut.osm").string() + " relation 20");
  EXPECT_EQ(doc["osm"]["repaired"], ordered_json::parse(R"(["relation 20 (landuse=residential): its outer ring, cut by the extract's edge, closed along the edge"])"));
}

// A village's residential land and the forest beside it, both relations the extract cut
// open along one shared way (north along longitude 10.007): the houses stand west of it, on
// the larger side, so the residential land is the west and the forest the east, whichever
// side encloses less.
TEST(OsmOutput, CutLandUseLiesOnTheSideItsMappedBuildingsSay) {
  const fs::path dir = testing_util::temp_dir("osm-cut-sides");
  write(dir / "cut.osm", R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6" generator="test">
  <bounds minlat="48.0" minlon="10.0" maxlat="48.01" maxlon="10.01"/>
  <node id="1" version="1" lat="48.001" lon="10.007"/>
  <node id="2" version="1" lat="48.009" lon="10.007"/>
  <node id="3" version="1" lat="48.005" lon="10.002"/>
  <node id="4" version="1" lat="48.005" lon="10.0022"/>
  <node id="5" version="1" lat="48.0052" lon="10.0022"/>
  <node id="6" version="1" lat="48.0052" lon="10.002"/>
  <node id="8" version="1" lat="48.002" lon="10.001"/>
  <node id="9" version="1" lat="48.002" lon="10.006"/>
  <way id="10" version="1"><nd ref="1"/><nd ref="2"/></way>
  <way id="11" version="1"><nd ref="3"/><nd ref="4"/><nd ref="5"/><nd ref="6"/><nd ref="3"/><tag k="building" v="house"/></way>
  <way id="12" version="1"><nd ref="8"/><nd ref="9"/><tag k="highway" v="residential"/></way>
  <relation id="20" version="1">
    <member type="way" ref="10" role="outer"/>
    <tag k="type" v="multipolygon"/>
    <tag k="landuse" v="residential"/>
  </relation>
  <relation id="21" version="1">
    <member type="way" ref="10" role="outer"/>
    <tag k="type" v="multipolygon"/>
    <tag k="landuse" v="forest"/>
  </relation>
</osm>
)");
  const ordered_json doc = osm_sketch_document(dir / "cut.osm");
  std::map<std::string, ordered_json> zones;
  for (const ordered_json& f : doc["features"])
    if (f["properties"].contains("landuse")) zones[f["properties"]["landuse"]] = f["geometry"]["coordinates"];
  EXPECT_EQ(zones["residential"], ordered_json::parse(R"([[[[10.007, 48.001], [10.007, 48.009], [10.007, 48.01],
      [10.0, 48.01], [10.0, 48.0], [10.007, 48.0], [10.007, 48.001]]]])")) << doc.dump();
  EXPECT_EQ(zones["forest"], ordered_json::parse(R"([[[[10.007, 48.001], [10.007, 48.009], [10.007, 48.01],
      [10.01, 48.01], [10.01, 48.0], [10.007, 48.0], [10.007, 48.001]]]])")) << doc.dump();
}

TEST(OsmOutput, ANodeOutsideLonLatRangesIsRefusedByItsId) {
  const fs::path dir = testing_util::temp_dir("osm-range");
  write(dir / "far.osm", cut_extract("1e308"));
  EXPECT_EQ(error_of([&] { osm_sketch_document(dir / "far.osm"); }),
            (dir / "far.osm").string() + ": node 7 has lat=\"1e308\", outside -90 to 90; correct or delete the node");
  write(dir / "north.osm", cut_extract("91"));
  EXPECT_EQ(error_of([&] { osm_sketch_document(dir / "north.osm"); }),
            (dir / "north.osm").string() + ": node 7 has lat=\"91\", outside -90 to 90; correct or delete the node");
}

namespace {

// Streets crossing at many angles over a park: where strokes' sides nearly meet, rounding
// leaves slivers of one road's surface between the others'.
const char* kCrossingStreets = R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [[[-100, -100], [500, -100], [500, 500], [-100, 500], [-100, -100]]]}}, {"type": "Feature", "properties": {"road": "main", "width": 10.5}, "geometry": {"type": "LineString", "coordinates": [[36.6, 144.4], [67.6, 323.6]]}}, {"type": "Feature", "properties": {"road": "main", "width": 12}, "geometry": {"type": "LineString", "coordinates": [[84.9, 14.3], [272.5, 399.9], [255.4, 321.5], [344.1, 203.6]]}}, {"type": "Feature", "properties": {"road": "local", "width": 8}, "geometry": {"type": "LineString", "coordinates": [[107.3, 14.4], [11.0, 186.0], [127.4, 152.0], [356.7, 210.3]]}}, {"type": "Feature", "properties": {"road": "local", "width": 12}, "geometry": {"type": "LineString", "coordinates": [[9.5, 130.1], [54.7, 204.1]]}}, {"type": "Feature", "properties": {"road": "main", "width": 8}, "geometry": {"type": "LineString", "coordinates": [[293.8, 362.6], [305.2, 315.9], [141.5, 392.4]]}}, {"type": "Feature", "properties": {"road": "main", "width": 12}, "geometry": {"type": "LineString", "coordinates": [[286.1, 184.6], [212.1, 196.0], [369.9, 200.3]]}}, {"type": "Feature", "properties": {"road": "local", "width": 10.5}, "geometry": {"type": "LineString", "coordinates": [[140.3, 290.4], [223.0, 182.6], [263.6, 376.2]]}}, {"type": "Feature", "properties": {"road": "main", "width": 10.5}, "geometry": {"type": "LineString", "coordinates": [[123.8, 382.9], [282.5, 201.7], [207.1, 260.6]]}}]})";

// A sketch written into a folder of its own and read, and its city.
struct BuiltSketch {
  Sketch sketch;
  City city;
};
BuiltSketch build(const std::string& name, const char* text) {
  const fs::path file = testing_util::temp_dir(name) / "sketch.geojson";
  write(file, text);
  BuiltSketch out{load_sketch(file), {}};
  StageClock clock(nullptr, kCityStages);
  out.city = build_city(out.sketch, clock);
  return out;
}

// The ground of the map as the road network leaves it, before road areas change hands.
Ground ground_before_giving(const Sketch& sketch) {
  const RoadNetwork network = grow_road_network(build_city_map(sketch, sketch, nullptr), sketch, sketch.zones);
  return extract_ground(network.map, {}, {}, sketch.zones);
}

std::set<int> roads_with_areas(const Ground& ground) {
  std::set<int> out;
  for (const RoadArea& a : ground.road_areas) out.insert(a.road);
  return out;
}

}  // namespace

TEST(OsmOutput, NoRoadAreaIsASliverAndEveryRoadKeepsASurface) {
  const auto [sketch, city] = build("osm-slivers", kCrossingStreets);
  for (const RoadArea& a : city.ground.road_areas) EXPECT_GE(geom::area(a.polygon), 0.009) << "road " << a.road;
  // The same map as the road network leaves it, before anything is given away: the same
  // roads have surfaces, and it did hold a sliver.
  const Ground unmerged = ground_before_giving(sketch);
  EXPECT_TRUE(std::any_of(unmerged.road_areas.begin(), unmerged.road_areas.end(),
                          [](const RoadArea& a) { return geom::area(a.polygon) < 0.01; }));
  EXPECT_EQ(roads_with_areas(city.ground), roads_with_areas(unmerged));
  EXPECT_EQ(city.ground.roads.size(), unmerged.roads.size());
}

namespace {

// Two stubs a few metres long lying wholly on others' surfaces, as short OSM ways at a
// junction do: one across a highway's carriageway, one inside the junction of two highways.
const char* kCoveredStubs = R"({"type": "FeatureCollection", "features": [
  {"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [[[-100, -100], [300, -100], [300, 300], [-100, 300], [-100, -100]]]}},
  {"type": "Feature", "properties": {"road": "main", "width": 12}, "geometry": {"type": "LineString", "coordinates": [[0, 0], [200, 0]]}},
  {"type": "Feature", "properties": {"road": "local", "width": 6}, "geometry": {"type": "LineString", "coordinates": [[60, -2], [64, 2]]}},
  {"type": "Feature", "properties": {"road": "main", "width": 12}, "geometry": {"type": "LineString", "coordinates": [[100, 0], [100, 200]]}},
  {"type": "Feature", "properties": {"road": "local", "width": 6}, "geometry": {"type": "LineString", "coordinates": [[100, 0], [101, 3]]}}]})";

std::map<int, double> road_area_by_road(const Ground& ground) {
  std::map<int, double> out;
  for (const RoadArea& a : ground.road_areas) out[a.road] += geom::area(a.polygon);
  return out;
}

}  // namespace

TEST(OsmOutput, AStubOnOtherRoadsSurfacesTakesWhatItsCarriagewayCovers) {
  const auto [sketch, city] = build("osm-stubs", kCoveredStubs);
  ASSERT_EQ(city.ground.roads.size(), 4u);
  const std::map<int, double> area = road_area_by_road(city.ground);
  // Before: roads 1 and 3 had no area (the highway and the junction owned all they cover).
  EXPECT_EQ(area.size(), 4u);
  EXPECT_TRUE(city.ground.roads_without_area.empty());
  // The stub across the highway has all its carriageway, 6 m by its length (its sides on the
  // grid-line rule's points, within 1 cm2 of it); the highway
  // gave it that and nothing moved: the surfaces cover what they covered.
  ASSERT_TRUE(area.count(1));
  EXPECT_NEAR(area.at(1), 6 * std::sqrt(32.0), 0.01);  // its sides on the grid-line rule's points
  EXPECT_GT(area.count(3) ? area.at(3) : 0.0, 1.0);
  const Ground before = ground_before_giving(sketch);
  double total = 0, total_before = 0;
  for (const auto& [road, a] : area) total += a;
  for (const auto& [road, a] : road_area_by_road(before)) total_before += a;
  EXPECT_NEAR(total, total_before, 1e-6);
}

TEST(OsmOutput, AStubOnOtherRoadsSurfacesIsARoadObjectInCityJson) {
  const fs::path dir = testing_util::temp_dir("osm-stubs-cli");
  write(dir / "stubs.geojson", kCoveredStubs);
  const cli_util::Result r = cli_util::run("generate " + (dir / "stubs.geojson").string() + " -o " + (dir / "out").string() + " -q");
  ASSERT_EQ(r.code, 0) << r.out;
  const nlohmann::json city = nlohmann::json::parse(cli_util::read(dir / "out" / "city.city.json"));
  std::set<int> roads, centre_lines;
  for (const auto& [id, o] : city["CityObjects"].items())
    if (o["type"] == "Road") roads.insert(o["attributes"]["road"].get<int>());
  const nlohmann::json layer = nlohmann::json::parse(cli_util::read(dir / "out" / "vector" / "roads.geojson"));
  for (const auto& f : layer["features"]) centre_lines.insert(f["properties"]["id"].get<int>());
  EXPECT_EQ(centre_lines.size(), 4u);
  EXPECT_EQ(roads, centre_lines);
  const nlohmann::json report = nlohmann::json::parse(cli_util::read(dir / "out" / "report.json"));
  EXPECT_EQ(report["roads_without_area"], nlohmann::json::array());
}

TEST(OsmOutput, TheSummaryLineCountsBuildingsWithoutTrees) {
  const fs::path out = testing_util::temp_dir("osm-summary") / "out";
  const fs::path library = cli_util::kSource / "examples" / "models" / "library.json";
  const cli_util::Result r =
      cli_util::run("generate " + kVillage.string() + " --models " + library.string() + " -o " + out.string() + " -q");
  ASSERT_EQ(r.code, 0) << r.out;
  int buildings = 0, others = 0;
  const nlohmann::json layer = nlohmann::json::parse(cli_util::read(out / "vector" / "buildings.geojson"));
  for (const auto& f : layer["features"])
    (f["properties"]["kind"] == "building" ? buildings : others) += 1;
  EXPECT_GT(others, 0);  // trees stand among the buildings in the layer
  EXPECT_NE(r.out.find(", buildings " + std::to_string(buildings) + ","), std::string::npos) << r.out;
}

// New objects in OSM files (JOSM's, and city.osm's own) carry negative ids: their ways find
// their nodes as positive ones do, and Exacity reads its own city.osm back.
TEST(OsmOutput, NegativeIdsAreReadAsAnyOthersAndCityOsmReadsBack) {
  const fs::path dir = testing_util::temp_dir("osm-negative");
  write(dir / "new.osm", R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <node id="-1" lat="-33.8600" lon="151.2000"/>
  <node id="-2" lat="-33.8600" lon="151.2030"/>
  <node id="-3" lat="-33.8580" lon="151.2030"/>
  <node id="-4" lat="-33.8580" lon="151.2000"/>
  <node id="-5" lat="-33.8590" lon="151.1995"/>
  <way id="-10"><nd ref="-1"/><nd ref="-2"/><nd ref="-3"/><nd ref="-4"/><nd ref="-1"/><tag k="landuse" v="industrial"/></way>
  <way id="-12"><nd ref="-5"/><nd ref="-3"/><tag k="highway" v="tertiary"/></way>
</osm>
)");
  const Sketch sketch = load_sketch(dir / "new.osm");
  EXPECT_EQ(sketch.zones.size(), 1u);
  EXPECT_EQ(sketch.roads.size(), 1u);

  const GenerateResult village = generate(kVillage, dir / "village");
  ASSERT_TRUE(village.valid);
  const Sketch again = load_sketch(dir / "village" / "city.osm");
  // city.osm holds streets, buildings and clutter, no land use. Before: "Way IDs out of order"
  // (its negative ids count up), then "the extract has no highways" (no negative node found).
  EXPECT_EQ(again.roads.size(), 7u);
}

TEST(OsmOutput, IdsFromAGivenRangeAreReadByGdalsOsmDriverAsItIs) {
  const fs::path dir = testing_util::temp_dir("osm-ids-from");
  const cli_util::Result r =
      cli_util::run("generate " + kVillage.string() + " -o " + (dir / "v").string() + " -q --osm-ids-from 7000000000");
  ASSERT_EQ(r.code, 0) << r.out;
  const OsmFile osm = read_osm(dir / "v" / "city.osm");
  ASSERT_FALSE(osm.node_ids.empty());
  EXPECT_EQ(*osm.node_ids.begin(), 7000000000);
  EXPECT_EQ(*osm.node_ids.rbegin(), 7000000000 + static_cast<std::int64_t>(osm.node_ids.size()) - 1);
  EXPECT_EQ(*osm.way_ids.begin(), 7000000000);
  // GDAL's default node index (no OSM_USE_CUSTOM_INDEXING=NO) reads every street.
  EXPECT_EQ(gdal_streets(dir / "v" / "city.osm"), nlohmann::json::parse(cli_util::read(dir / "v" / "report.json"))["counts"]["roads"].get<int>());
  // Zero and negative first ids are refused.
  const cli_util::Result zero = cli_util::run("generate " + kVillage.string() + " -o " + (dir / "z").string() + " -q --osm-ids-from 0");
  EXPECT_EQ(zero.code, 2) << zero.out;
  EXPECT_FALSE(fs::exists(dir / "z" / "city.osm"));
}

namespace {

// Two residential areas side by side between four streets, each way with the tags a mapper
// gives a street (names, lanes, one way, speed, sidewalks, a bridge, a building passage), a
// footway along the edge the two areas share, a footway mapped as a street's sidewalk and
// one across an area. South: Broad Street (two ways, the east one a bridge), north: Narrow
// Lane drawn east to west (its left is south), west: an alley, east: a residential street
// without a sidewalk tag.
const char* kTaggedStreets = R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6" generator="test">
  <node id="1" version="1" lat="48.000" lon="9.999"/>
  <node id="2" version="1" lat="48.000" lon="10.000"/>
  <node id="3" version="1" lat="48.000" lon="10.004"/>
  <node id="4" version="1" lat="48.000" lon="10.008"/>
  <node id="5" version="1" lat="48.000" lon="10.009"/>
  <node id="6" version="1" lat="48.003" lon="10.000"/>
  <node id="7" version="1" lat="48.003" lon="10.004"/>
  <node id="8" version="1" lat="48.003" lon="10.008"/>
  <node id="9" version="1" lat="48.0003" lon="10.0005"/>
  <node id="10" version="1" lat="48.0003" lon="10.0075"/>
  <node id="11" version="1" lat="48.001" lon="10.001"/>
  <node id="12" version="1" lat="48.002" lon="10.003"/>
  <way id="100" version="1"><nd ref="1"/><nd ref="2"/><nd ref="3"/>
    <tag k="highway" v="primary"/><tag k="name" v="Broad Street"/><tag k="lanes" v="4"/><tag k="oneway" v="yes"/>
    <tag k="maxspeed" v="50"/><tag k="sidewalk" v="both"/></way>
  <way id="101" version="1"><nd ref="3"/><nd ref="4"/><nd ref="5"/>
    <tag k="highway" v="primary"/><tag k="name" v="Broad Street"/><tag k="lanes" v="4"/><tag k="oneway" v="yes"/>
    <tag k="maxspeed" v="50"/><tag k="sidewalk" v="both"/><tag k="bridge" v="yes"/><tag k="layer" v="1"/></way>
  <way id="102" version="1"><nd ref="8"/><nd ref="7"/><nd ref="6"/>
    <tag k="highway" v="residential"/><tag k="name" v="Narrow Lane"/><tag k="lanes" v="2"/><tag k="maxspeed" v="30"/>
    <tag k="sidewalk" v="left"/></way>
  <way id="103" version="1"><nd ref="2"/><nd ref="6"/>
    <tag k="highway" v="service"/><tag k="service" v="alley"/><tag k="tunnel" v="building_passage"/><tag k="sidewalk" v="no"/></way>
  <way id="104" version="1"><nd ref="4"/><nd ref="8"/><tag k="highway" v="residential"/></way>
  <way id="105" version="1"><nd ref="3"/><nd ref="7"/><tag k="highway" v="footway"/></way>
  <way id="106" version="1"><nd ref="9"/><nd ref="10"/><tag k="highway" v="footway"/><tag k="footway" v="sidewalk"/></way>
  <way id="107" version="1"><nd ref="11"/><nd ref="12"/><tag k="highway" v="footway"/></way>
  <way id="200" version="1"><nd ref="2"/><nd ref="3"/><nd ref="7"/><nd ref="6"/><nd ref="2"/><tag k="landuse" v="residential"/></way>
  <way id="201" version="1"><nd ref="3"/><nd ref="4"/><nd ref="8"/><nd ref="7"/><nd ref="3"/><tag k="landuse" v="residential"/></way>
</osm>
)";

// The streets' own layout, and local streets with sidewalks of 1.5 m where their ways say
// nothing.
const char* kTaggedStreetsSettings =
    R"({"roads": {"local": {"sidewalk": 1.5}}, "zones": {"residential": {"layout": "streets"}}})";

struct TaggedStreetsCity {
  fs::path out;
  nlohmann::json roads, road_areas, blocks;
  // roads.geojson's ids by the way they came from.
  std::map<std::string, std::set<int>> ids_of_way;
};

const TaggedStreetsCity& tagged_streets_city() {
  static const TaggedStreetsCity city = [] {
    TaggedStreetsCity c;
    const fs::path dir = testing_util::temp_dir("osm-tagged-streets");
    write(dir / "streets.osm", kTaggedStreets);
    write(dir / "streets.exacity.json", kTaggedStreetsSettings);
    c.out = dir / "out";
    EXPECT_TRUE(generate(dir / "streets.osm", c.out).valid);
    c.roads = nlohmann::json::parse(cli_util::read(c.out / "vector" / "roads.geojson"));
    c.road_areas = nlohmann::json::parse(cli_util::read(c.out / "vector" / "road_areas.geojson"));
    c.blocks = nlohmann::json::parse(cli_util::read(c.out / "vector" / "blocks.geojson"));
    for (const auto& f : c.roads["features"])
      if (f["properties"].contains("osm_id")) c.ids_of_way[f["properties"]["osm_id"]].insert(f["properties"]["id"].get<int>());
    return c;
  }();
  return city;
}

// The area of a road's sidewalks north and south of the line y = `y` (by each polygon's
// outer ring's centroid).
std::pair<double, double> sidewalk_area_north_and_south(const nlohmann::json& road_areas, const std::set<int>& roads, double y) {
  double north = 0, south = 0;
  for (const auto& f : road_areas["features"]) {
    if (f["properties"]["surface"] != "sidewalk" || !f["properties"]["road"].is_number() ||
        !roads.count(f["properties"]["road"].get<int>()))
      continue;
    const auto& ring = f["geometry"]["coordinates"][0];
    double a = 0, cy = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
      const double x0 = ring[i][0], y0 = ring[i][1], x1 = ring[i + 1][0], y1 = ring[i + 1][1];
      const double cross = x0 * y1 - x1 * y0;
      a += cross / 2;
      cy += (y0 + y1) * cross / 6;
    }
    (cy / a > y ? north : south) += std::abs(a);
  }
  return {north, south};
}

// Streets in a grid of 2 x 3 faces (lon 10.000 to 10.006, lat 48.000 to 48.003), land use
// on one face, and in the others: three houses; a warehouse; an untagged building of 900
// m2; a small untagged one; none. `settings` beside it.
std::string streets_and_buildings() {
  std::string nodes, ways;
  int node = 1, way = 100;
  auto add_node = [&](double lon, double lat) {
    std::ostringstream n;
    n << std::setprecision(10) << "  <node id=\"" << node << "\" version=\"1\" lat=\"" << lat << "\" lon=\"" << lon << "\"/>\n";
    nodes += n.str();
    return node++;
  };
  auto add_way = [&](const std::vector<int>& refs, const std::string& tags) {
    ways += "  <way id=\"" + std::to_string(way++) + "\" version=\"1\">";
    for (int r : refs) ways += "<nd ref=\"" + std::to_string(r) + "\"/>";
    ways += tags + "</way>\n";
  };
  const std::string street = "<tag k=\"highway\" v=\"residential\"/>";
  for (int row = 0; row <= 2; ++row) add_way({add_node(10.0, 48.0 + row * 0.0015), add_node(10.006, 48.0 + row * 0.0015)}, street);
  for (int col = 0; col <= 3; ++col) add_way({add_node(10.0 + col * 0.002, 48.0), add_node(10.0 + col * 0.002, 48.003)}, street);
  // A w x h degree box at a face's centre (col, row), moved by (dx, dy), with its tags.
  auto box = [&](int col, int row, double w, double h, double dx, double dy, const std::string& tags) {
    const double x = 10.001 + col * 0.002 + dx - w / 2, y = 48.00075 + row * 0.0015 + dy - h / 2;
    const int a = add_node(x, y), b = add_node(x + w, y), c = add_node(x + w, y + h), d = add_node(x, y + h);
    add_way({a, b, c, d, a}, tags);
  };
  const std::string house = "<tag k=\"building\" v=\"house\"/>";
  for (double dx : {-0.0004, 0.0, 0.0004}) box(0, 0, 0.00013, 0.00009, dx, 0, house);
  box(1, 0, 0.0008, 0.0005, 0, 0, "<tag k=\"building\" v=\"warehouse\"/>");
  box(2, 0, 0.0004, 0.00027, 0, 0, "<tag k=\"building\" v=\"yes\"/>");  // 30 x 30 m
  box(0, 1, 0.00013, 0.00009, 0, 0, "<tag k=\"building\" v=\"yes\"/>");
  box(1, 1, 0.0018, 0.0013, 0, 0, "<tag k=\"landuse\" v=\"residential\"/>");
  box(1, 1, 0.00013, 0.00009, 0, 0, house);
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<osm version=\"0.6\" generator=\"test\">\n"
         "  <bounds minlat=\"47.999\" minlon=\"9.999\" maxlat=\"48.004\" maxlon=\"10.007\"/>\n" +
         nodes + ways + "</osm>\n";
}

}  // namespace

// Before, roads.geojson and CityJSON had no OSM attributes and city.osm no way id, sidewalk,
// bridge, layer or tunnel.
TEST(OsmOutput, StreetsKeepTheirWaysAttributesInEveryOutput) {
  const TaggedStreetsCity& city = tagged_streets_city();
  ASSERT_EQ(city.ids_of_way.count("way/100"), 1u);
  ASSERT_EQ(city.ids_of_way.count("way/101"), 1u);
  ASSERT_EQ(city.ids_of_way.count("way/102"), 1u);
  // Every piece of a way the map cuts (at junctions) keeps the way's attributes.
  std::map<int, nlohmann::json> by_id;
  for (const auto& f : city.roads["features"]) by_id[f["properties"]["id"].get<int>()] = f["properties"];
  for (int id : city.ids_of_way.at("way/100")) {
    const nlohmann::json& p = by_id.at(id);
    EXPECT_EQ(p["name"], "Broad Street");
    EXPECT_EQ(p["highway"], "primary");
    EXPECT_EQ(p["oneway"], "yes");
    EXPECT_EQ(p["lanes"], "4");
    EXPECT_EQ(p["maxspeed"], "50");
    EXPECT_EQ(p["sidewalk"], "both");
    EXPECT_FALSE(p.contains("osm_bridge"));
    EXPECT_EQ(p["width"], 14.0);  // 4 lanes of 3.5 m
  }
  for (int id : city.ids_of_way.at("way/101")) {
    EXPECT_EQ(by_id.at(id)["osm_bridge"], "yes");
    EXPECT_EQ(by_id.at(id)["layer"], "1");
    EXPECT_EQ(by_id.at(id)["bridge"], false);  // over no water
  }
  for (int id : city.ids_of_way.at("way/102")) {
    EXPECT_EQ(by_id.at(id)["name"], "Narrow Lane");
    EXPECT_EQ(by_id.at(id)["width"], 7.0);  // a lanes=4 road is twice as wide as a lanes=2 one
  }
  for (int id : city.ids_of_way.at("way/103")) EXPECT_EQ(by_id.at(id)["tunnel"], "building_passage");

  // city.osm: the same tags, the way's id as exacity:osm_id.
  const OsmFile osm = read_osm(city.out / "city.osm");
  int broad = 0;
  for (const auto& tags : osm.ways) {
    if (!tags.count("exacity:osm_id") || tags.at("exacity:osm_id") != "way/101") continue;
    ++broad;
    EXPECT_EQ(tags.at("name"), "Broad Street");
    EXPECT_EQ(tags.at("oneway"), "yes");
    EXPECT_EQ(tags.at("maxspeed"), "50");
    EXPECT_EQ(tags.at("sidewalk"), "both");
    EXPECT_EQ(tags.at("bridge"), "yes");
    EXPECT_EQ(tags.at("layer"), "1");
  }
  EXPECT_EQ(broad, static_cast<int>(city.ids_of_way.at("way/101").size()));

  // CityJSON: each road object carries its road's attributes.
  const nlohmann::json cityjson = nlohmann::json::parse(cli_util::read(city.out / "city.city.json"));
  std::set<std::string> named;
  for (const auto& [key, o] : cityjson["CityObjects"].items())
    if (o["type"] == "Road" && o["attributes"].contains("name")) {
      named.insert(o["attributes"]["name"].get<std::string>() + " " + o["attributes"]["osm_id"].get<std::string>());
      if (o["attributes"]["osm_id"] == "way/100") {
        EXPECT_EQ(o["attributes"]["lanes"], "4");
      }
    }
  EXPECT_EQ(named, (std::set<std::string>{"Broad Street way/100", "Broad Street way/101", "Narrow Lane way/102"}));
}

// Before, sidewalks came only from a class's setting: Broad Street (sidewalk=both, a
// highway, whose class has none) had none, Narrow Lane (sidewalk=left) and the alley
// (sidewalk=no) had the local class's on both sides.
TEST(OsmOutput, SidewalksAreWhereTheWaysSayAndTheClassSettingWhereTheySayNothing) {
  const TaggedStreetsCity& city = tagged_streets_city();
  auto line_y = [&](const std::string& way) {
    for (const auto& f : city.roads["features"])
      if (f["properties"].value("osm_id", "") == way) return f["geometry"]["coordinates"][0][1].get<double>();
    return std::nan("");
  };
  auto sidewalks = [&](const std::string& way) {
    return sidewalk_area_north_and_south(city.road_areas, city.ids_of_way.at(way), line_y(way));
  };
  // Broad Street: 2 m on both sides of 740 m (its class sets none).
  const auto [broad_north, broad_south] = sidewalks("way/100");
  EXPECT_GT(broad_north, 250);
  EXPECT_GT(broad_south, 250);
  // Narrow Lane, drawn east to west: on its left, the south, 1.5 m along 600 m; on its
  // north only the corners of its junctions.
  const auto [lane_north, lane_south] = sidewalks("way/102");
  EXPECT_GT(lane_south, 600);
  EXPECT_LT(lane_north, 0.1 * lane_south);
  // The alley (sidewalk=no) has none but junction corners; the east street, untagged, has
  // its class's on both sides (its "north" here is its east, by centroid x below).
  double alley = 0, east = 0, footway = 0;
  for (const auto& f : city.road_areas["features"]) {
    if (f["properties"]["surface"] != "sidewalk" || !f["properties"]["road"].is_number()) continue;
    const int road = f["properties"]["road"];
    const auto& ring = f["geometry"]["coordinates"][0];
    double a = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
      a += (ring[i][0].get<double>() * ring[i + 1][1].get<double>() - ring[i + 1][0].get<double>() * ring[i][1].get<double>()) / 2;
    if (city.ids_of_way.at("way/103").count(road)) alley += std::abs(a);
    if (city.ids_of_way.at("way/104").count(road)) east += std::abs(a);
    if (city.ids_of_way.at("way/105").count(road)) footway += std::abs(a);
  }
  EXPECT_GT(east, 2 * 1.5 * 300);
  EXPECT_LT(alley, 0.1 * east);
  EXPECT_LT(footway, 0.1 * east);  // a footway is all sidewalk: it has none of its own but junction corners
}

// Before, only `sidewalk` was read: the newer scheme's sides and the width tags were not,
// so every street here had the local class's 1.5 m on both sides. Three streets drawn west
// to east (their left is north) over two areas of land use, each tagged another way.
TEST(OsmOutput, SidewalksFollowTheSideAndWidthTagsOfTheNewerScheme) {
  std::string osm = R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6" generator="test">)";
  int node = 1;
  auto add_node = [&](double lon, double lat) {
    osm += "<node id=\"" + std::to_string(node) + "\" version=\"1\" lat=\"" + std::to_string(lat) + "\" lon=\"" +
           std::to_string(lon) + "\"/>\n";
    return node++;
  };
  int grid[3][2];
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 2; ++col) grid[row][col] = add_node(10.0 + 0.004 * col, 48.0 + 0.0015 * row);
  auto way = [&](int id, const std::vector<int>& nodes, const std::string& tags) {
    osm += "<way id=\"" + std::to_string(id) + "\" version=\"1\">";
    for (int n : nodes) osm += "<nd ref=\"" + std::to_string(n) + "\"/>";
    osm += tags + "</way>\n";
  };
  auto tag = [](const std::string& k, const std::string& v) { return "<tag k=\"" + k + "\" v=\"" + v + "\"/>"; };
  const std::string street = tag("highway", "residential");
  way(100, {grid[0][0], grid[0][1]}, street + tag("sidewalk:both", "yes") + tag("sidewalk:both:width", "3"));
  way(101, {grid[1][0], grid[1][1]}, street + tag("sidewalk", "both") + tag("sidewalk:right", "no"));
  way(102, {grid[2][0], grid[2][1]},
      street + tag("sidewalk:left", "yes") + tag("sidewalk:left:width", "2.5 m") + tag("sidewalk:right", "separate") +
          tag("sidewalk:width", "wide"));
  way(103, {grid[0][0], grid[1][0], grid[2][0]}, street);
  way(104, {grid[0][1], grid[1][1], grid[2][1]}, street);
  for (int row = 0; row < 2; ++row)
    way(200 + row, {grid[row][0], grid[row][1], grid[row + 1][1], grid[row + 1][0], grid[row][0]}, tag("landuse", "residential"));
  osm += "</osm>\n";

  const fs::path dir = testing_util::temp_dir("osm-sidewalk-scheme");
  write(dir / "streets.osm", osm);
  write(dir / "streets.exacity.json", kTaggedStreetsSettings);
  ASSERT_TRUE(generate(dir / "streets.osm", dir / "out").valid);
  const nlohmann::json roads = nlohmann::json::parse(cli_util::read(dir / "out" / "vector" / "roads.geojson"));
  const nlohmann::json areas = nlohmann::json::parse(cli_util::read(dir / "out" / "vector" / "road_areas.geojson"));
  // Each street's sidewalk area north and south of it, over its length: the width, less the
  // junctions at its ends, plus the corners where a wider sidewalk meets a narrower one.
  auto widths = [&](const std::string& way) {
    std::set<int> ids;
    double y = 0, length = 0;
    for (const auto& f : roads["features"])
      if (f["properties"].value("osm_id", "") == way) {
        ids.insert(f["properties"]["id"].get<int>());
        const auto& line = f["geometry"]["coordinates"];
        y = line[0][1];
        for (std::size_t i = 0; i + 1 < line.size(); ++i) length += std::abs(line[i + 1][0].get<double>() - line[i][0].get<double>());
      }
    EXPECT_GT(length, 250) << way;
    const auto [north, south] = sidewalk_area_north_and_south(areas, ids, y);
    return std::pair{north / length, south / length};
  };
  const auto [both_north, both_south] = widths("way/100");  // sidewalk:both=yes, sidewalk:both:width=3
  EXPECT_GT(both_north, 0.9 * 3);
  EXPECT_GT(both_south, 0.9 * 3);
  EXPECT_LT(both_north, 1.1 * 3);
  const auto [middle_north, middle_south] = widths("way/101");  // sidewalk=both, sidewalk:right=no
  EXPECT_GT(middle_north, 0.9 * 1.5);
  EXPECT_LT(middle_north, 1.1 * 1.5);
  EXPECT_LT(middle_south, 0.1);
  const auto [top_north, top_south] = widths("way/102");  // left=yes 2.5 m, right=separate, a width it cannot read
  EXPECT_GT(top_north, 0.9 * 2.5);
  EXPECT_LT(top_north, 1.1 * 2.5);
  EXPECT_LT(top_south, 0.1);
  // The tags themselves go on to the layer as read.
  for (const auto& f : roads["features"])
    if (f["properties"].value("osm_id", "") == "way/102") {
      EXPECT_EQ(f["properties"]["sidewalk:left:width"], "2.5 m");
      EXPECT_EQ(f["properties"]["sidewalk:width"], "wide");
    }
}

// Before, every footway was left out: the two areas were one block.
TEST(OsmOutput, AFootwayAlongTheEdgeOfLandUseBoundsBlocksAndSidewalkFootwaysDoNot) {
  const TaggedStreetsCity& city = tagged_streets_city();
  ASSERT_EQ(city.ids_of_way.count("way/105"), 1u);
  EXPECT_EQ(city.ids_of_way.count("way/106"), 0u);  // footway=sidewalk
  EXPECT_EQ(city.ids_of_way.count("way/107"), 0u);  // across an area, bounding nothing
  const int footway = *city.ids_of_way.at("way/105").begin();
  int fronting = 0;
  for (const auto& b : city.blocks["features"])
    for (const auto& r : b["properties"]["roads"]) fronting += r == footway;
  EXPECT_EQ(fronting, 2);  // a block each side
  for (const auto& f : city.roads["features"])
    if (f["properties"]["id"] == footway) {
      EXPECT_EQ(f["properties"]["highway"], "footway");
    }
  const nlohmann::json sketch = nlohmann::json::parse(cli_util::read(city.out / "sketch.geojson"));
  EXPECT_EQ(sketch["osm"]["skipped"]["highway=footway"], 2);  // the other two, counted as left out
}

TEST(OsmOutput, StreetFacesWithoutLandUseAreZonedFromTheirMappedBuildings) {
  const fs::path dir = testing_util::temp_dir("osm-infer");
  write(dir / "town.osm", streets_and_buildings());
  write(dir / "town.exacity.json", R"({"infer_zones": true})");
  const GenerateResult result = generate(dir / "town.osm", dir / "out");
  EXPECT_EQ(result.report["land_use"], ordered_json::parse(R"({"closed_along_bounds": 0, "infer_zones": {"street_faces": 6,
      "faces_with_land_use": 1, "inferred": {"commercial": 1, "industrial": 1, "residential": 2}, "left_open": 1}})"))
      << result.report["land_use"].dump();
  // The zones given are in the sketch the city was built from, each named as inferred.
  const ordered_json sketch = ordered_json::parse(cli_util::read(dir / "out" / "sketch.geojson"));
  std::multiset<std::string> zones;
  for (const ordered_json& f : sketch["features"])
    if (f["properties"].value("source", "").find("zone inferred from its mapped buildings") != std::string::npos)
      zones.insert(f["properties"]["zone"].get<std::string>());
  EXPECT_EQ(zones, (std::multiset<std::string>{"commercial", "industrial", "residential", "residential"}));
  EXPECT_GT(result.report["mapped_buildings"]["lots_not_built_again"].get<int>(), 0);

  // A setting that is no boolean: one line.
  write(dir / "town.exacity.json", R"({"infer_zones": "yes"})");
  EXPECT_EQ(error_of([&] { load_sketch(dir / "town.osm"); }),
            (dir / "town.osm").string() + ": \"exacity\".infer_zones: expected true or false (true: street faces without land "
            "use are zoned from their mapped buildings)");
}
