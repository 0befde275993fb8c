// In and out of the GIS and OSM ecosystems (docs/gis.md): sketches read
// through OGR and libosmium, lon/lat projected through PROJ, the layers written through OGR
// and the city as an OSM file, each read back with the library made for it.
#include <gtest/gtest.h>

#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include <gdal_priv.h>
#include <gdal_utils.h>
#include <geodesic.h>
#include <ogrsf_frmts.h>
#include <osmium/handler.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/visitor.hpp>

#include "generate/sketch/sketch.h"
#include "generate/errors.h"
#include "generate/export/clutter_layer.h"
#include "generate/export/gis_export.h"
#include "generate/gis/projection.h"
#include "generate/gis/sketch_sources.h"
#include "geom/polygon_check.h"
#include "generate/pipeline.h"
#include "tests/cityjson_seq.h"
#include "tests/cli_util.h"
#include "tests/test_util.h"

using namespace exacity;
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

const fs::path kVillage = cli_util::kSource / "examples" / "osm" / "village.osm";
const fs::path kLibrary = cli_util::kSource / "examples" / "models" / "library.json";

// A small town in metres in UTM zone 35N (Helsinki): a residential zone, a park, a highway.
ordered_json town_in_metres() {
  return ordered_json::parse(R"({"type": "FeatureCollection",
    "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32635"}},
    "features": [
      {"type": "Feature", "properties": {"zone": "residential", "name": "Kallio"},
       "geometry": {"type": "Polygon", "coordinates": [[[385000, 6672000], [385600, 6672000], [385600, 6672500], [385000, 6672500], [385000, 6672000]]]}},
      {"type": "Feature", "properties": {"zone": "park"},
       "geometry": {"type": "Polygon", "coordinates": [[[385100, 6672300], [385200, 6672300], [385200, 6672400], [385100, 6672400], [385100, 6672300]]]}},
      {"type": "Feature", "properties": {"road": "highway", "width": 20},
       "geometry": {"type": "LineString", "coordinates": [[384950, 6671990], [385650, 6672010]]}}]})");
}

const ordered_json kSettings = ordered_json::parse(R"({"seed": 3, "zones": {"residential": {"block_area": 9000}}})");

void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// Generates the sketch into `out` with the given extra vector formats; the city.
GenerateResult generate(const fs::path& sketch, const fs::path& out, std::vector<std::string> formats = {},
                        const fs::path& models = {}) {
  fs::remove_all(out);
  fs::create_directories(out);
  StageClock clock(nullptr, kCityStages + kWriteStages);
  const Sketch loaded = load_sketch(sketch, true, models);
  City city = build_city(loaded, clock);
  ExportOptions options;
  options.vector_formats = std::move(formats);
  return write_city(loaded, city, out, clock, options);
}

// The vector layers of two output folders are the same files.
void expect_same_layers(const fs::path& a, const fs::path& b) {
  for (const char* layer : {"zones", "water", "roads", "road_areas", "blocks", "lots", "buildings"}) {
    const fs::path file = fs::path("vector") / (std::string(layer) + ".geojson");
    EXPECT_EQ(cli_util::read(a / file), cli_util::read(b / file)) << file;
  }
}

// Converts a GeoJSON file with OGR (ogr2ogr's library call).
// `crs` ("EPSG:3857"), if given, is the one to write it in (ogr2ogr's -t_srs); `creation`
// ("SPATIAL_INDEX=NO"), a layer creation option (-lco).
void translate(const fs::path& from, const fs::path& to, const char* driver, const std::string& crs = "",
               const std::string& creation = "") {
  start_gdal();
  GDALDatasetH source = GDALOpenEx(from.string().c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  ASSERT_NE(source, nullptr);
  std::vector<char*> args = {const_cast<char*>("-f"), const_cast<char*>(driver)};
  if (!crs.empty()) args.insert(args.end(), {const_cast<char*>("-t_srs"), const_cast<char*>(crs.c_str())});
  if (!creation.empty()) args.insert(args.end(), {const_cast<char*>("-lco"), const_cast<char*>(creation.c_str())});
  args.push_back(nullptr);
  GDALVectorTranslateOptions* options = GDALVectorTranslateOptionsNew(args.data(), nullptr);
  int error = 0;
  GDALDatasetH made = GDALVectorTranslate(to.string().c_str(), nullptr, 1, &source, options, &error);
  GDALVectorTranslateOptionsFree(options);
  ASSERT_NE(made, nullptr);
  GDALClose(made);
  GDALClose(source);
}

std::string error_of(const fs::path& sketch) {
  try {
    load_sketch(sketch);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Gis, CrsMembersNameTheirEpsgCode) {
  EXPECT_EQ(epsg_of(crs_member(32635)), 32635);
  EXPECT_EQ(epsg_of(ordered_json::parse(R"({"type": "name", "properties": {"name": "EPSG:28992"}})")), 28992);
  EXPECT_EQ(epsg_of(ordered_json::parse(R"({"type": "EPSG", "properties": {"code": 3067}})")), 3067);  // GeoJSON 2008
  EXPECT_EQ(epsg_of(ordered_json::parse(R"({"type": "name", "properties": {"name": "urn:ogc:def:crs:OGC:1.3:CRS84"}})")),
            std::nullopt);
  EXPECT_EQ(epsg_of(nullptr), std::nullopt);
}

TEST(Gis, UtmZonesFromLonLat) {
  EXPECT_EQ(utm_epsg(10, 48), 32632);
  EXPECT_EQ(utm_epsg(151.2, -33.87), 32756);  // south: 327xx
  EXPECT_EQ(utm_epsg(-0.12, 51.5), 32630);
  EXPECT_EQ(utm_epsg(-180, 0), 32601);
  EXPECT_EQ(utm_epsg(179.99, 0), 32660);
  EXPECT_EQ(utm_epsg(180.002, 0.5), 32601);  // drawn across the antimeridian
}

TEST(Gis, ALonLatSketchIsTheCityOfItsProjectionByHand) {
  const fs::path dir = testing_util::temp_dir("gis-lonlat");
  // By hand: every position to WGS 84 lon/lat, the same as a QGIS user's layer.
  ordered_json metres = town_in_metres();
  metres["exacity"] = kSettings;
  ordered_json lonlat = metres;
  lonlat.erase("crs");
  OGRSpatialReference utm, wgs84;
  utm.importFromEPSG(32635), wgs84.importFromEPSG(4326);
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER), wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_lonlat(OGRCreateCoordinateTransformation(&utm, &wgs84));
  std::unique_ptr<OGRCoordinateTransformation> to_utm(OGRCreateCoordinateTransformation(&wgs84, &utm));
  std::function<void(ordered_json&, ordered_json&)> each = [&](ordered_json& c, ordered_json& back) {
    if (c[0].is_number()) {
      double x = c[0], y = c[1];
      to_lonlat->Transform(1, &x, &y);
      c = {x, y};
      double bx = x, by = y;
      to_utm->Transform(1, &bx, &by);  // what Exacity's projection gives, done by hand:
      back = {std::round(bx * 1e6) / 1e6, std::round(by * 1e6) / 1e6};  // PROJ's metres to the micrometre
      return;
    }
    for (std::size_t i = 0; i < c.size(); ++i) each(c[i], back[i]);
  };
  for (std::size_t f = 0; f < lonlat["features"].size(); ++f)
    each(lonlat["features"][f]["geometry"]["coordinates"], metres["features"][f]["geometry"]["coordinates"]);
  write(dir / "lonlat.geojson", lonlat.dump());
  write(dir / "metres.geojson", metres.dump());

  const Sketch sketch = load_sketch(dir / "lonlat.geojson");
  EXPECT_EQ(epsg_of(sketch.crs), 32635);
  EXPECT_EQ(sketch.zones[0].polygons[0].outer[0].x, metres["features"][0]["geometry"]["coordinates"][0][0][0].get<double>());
  EXPECT_NEAR(sketch.zones[0].polygons[0].outer[0].x, 385000, 1e-6);
  const GenerateResult a = generate(dir / "lonlat.geojson", dir / "a"), b = generate(dir / "metres.geojson", dir / "b");
  EXPECT_TRUE(a.valid);
  EXPECT_GT(a.report["counts"]["lots"].get<int>(), 20);
  expect_same_layers(dir / "a", dir / "b");
  // The same drawn in a GeoPackage in EPSG:4326, its settings beside it.
  ordered_json features = lonlat;
  features.erase("exacity");
  write(dir / "drawn.geojson", features.dump());
  translate(dir / "drawn.geojson", dir / "drawn.gpkg", "GPKG");
  write(dir / "drawn.exacity.json", kSettings.dump());
  generate(dir / "drawn.gpkg", dir / "c");
  expect_same_layers(dir / "a", dir / "c");
  // The outputs carry the CRS, CityJSON's reference system too.
  EXPECT_NE(cli_util::read(dir / "a" / "vector" / "lots.geojson").find("EPSG::32635"), std::string::npos);
  EXPECT_NE(cli_util::read(dir / "a" / "city.city.json").find("EPSG/0/32635"), std::string::npos);
}

TEST(Gis, TheSettingsBesideALonLatSketchHaveTheirBoundsProjectedToo) {
  const fs::path dir = testing_util::temp_dir("gis-bounds");
  // Image bounds in lon/lat around the village (lon 10, lat 48), as its sketch's CRS has them.
  const std::string settings =
      R"({"terrain": {"heightmap": "h.png", "bounds": [9.99, 47.99, 10.02, 48.01]},
          "channels": {"d": {"image": "d.png", "bounds": [9.99, 47.99, 10.02, 48.01]}}})";
  fs::copy_file(kVillage, dir / "village.osm");
  write(dir / "village.exacity.json", settings);
  ordered_json lonlat = ordered_json::parse(R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {"zone": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[10, 48], [10.005, 48], [10.005, 48.004], [10, 48]]]}}]})");
  write(dir / "drawn.geojson", lonlat.dump());
  write(dir / "drawn.exacity.json", settings);
  // By hand: the box around the four corners in UTM zone 32N.
  OGRSpatialReference utm, wgs84;
  utm.importFromEPSG(32632), wgs84.importFromEPSG(4326);
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER), wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_utm(OGRCreateCoordinateTransformation(&wgs84, &utm));
  double xs[4] = {9.99, 10.02, 10.02, 9.99}, ys[4] = {47.99, 47.99, 48.01, 48.01};
  ASSERT_TRUE(to_utm->Transform(4, xs, ys));
  const geom::Box expected{*std::min_element(xs, xs + 4), *std::min_element(ys, ys + 4), *std::max_element(xs, xs + 4),
                           *std::max_element(ys, ys + 4)};
  EXPECT_GT(expected.width(), 2000);  // metres, not degrees
  for (const char* name : {"village.osm", "drawn.geojson"}) {
    const Sketch sketch = load_sketch(dir / name, false);
    EXPECT_EQ(epsg_of(sketch.crs), 32632) << name;
    ASSERT_TRUE(sketch.terrain) << name;
    ASSERT_EQ(sketch.channels.size(), 1u) << name;
    for (const geom::Box& b : {sketch.terrain->bounds, sketch.channels[0].bounds}) {
      EXPECT_EQ(b.min_x, expected.min_x) << name;
      EXPECT_EQ(b.max_x, expected.max_x) << name;
      EXPECT_EQ(b.min_y, expected.min_y) << name;
      EXPECT_EQ(b.max_y, expected.max_y) << name;
    }
  }
}

TEST(Gis, GeoPackageAndShapefileSketchesGiveTheSameCity) {
  const fs::path dir = testing_util::temp_dir("gis-formats");
  ordered_json town = town_in_metres();
  write(dir / "town.geojson", town.dump());
  write(dir / "town.exacity.json", kSettings.dump());  // settings beside, for every format
  translate(dir / "town.geojson", dir / "town.gpkg", "GPKG");
  // A shapefile holds one kind of geometry: zones and roads in two, a folder OGR reads as one.
  ordered_json zones = town, roads = town;
  zones["features"].erase(2);
  roads["features"].erase(0), roads["features"].erase(0);
  write(dir / "zones.geojson", zones.dump());
  write(dir / "roads.geojson", roads.dump());
  fs::create_directories(dir / "shp");
  translate(dir / "zones.geojson", dir / "shp" / "zones.shp", "ESRI Shapefile");
  translate(dir / "roads.geojson", dir / "shp" / "roads.shp", "ESRI Shapefile");
  write(dir / "shp.exacity.json", kSettings.dump());
  const GenerateResult geojson = generate(dir / "town.geojson", dir / "from-geojson");
  EXPECT_TRUE(geojson.valid);
  EXPECT_EQ(geojson.report["seed"], 3);  // the settings beside were read
  generate(dir / "town.gpkg", dir / "from-gpkg");
  generate(dir / "shp", dir / "from-shp");
  expect_same_layers(dir / "from-geojson", dir / "from-gpkg");
  expect_same_layers(dir / "from-geojson", dir / "from-shp");
}

// A FlatGeobuf with its spatial index keeps its features in the index's order: overlapping
// zones (the park drawn over the residential zone) are refused, since which covers which is
// lost; without the index, or without overlaps, it is the GeoJSON's city.
TEST(Gis, AFlatGeobufThatLostTheOrderOfOverlappingZonesIsRefused) {
  const fs::path dir = testing_util::temp_dir("gis-fgb-order");
  ordered_json town = town_in_metres();
  write(dir / "town.geojson", town.dump());
  translate(dir / "town.geojson", dir / "indexed.fgb", "FlatGeobuf");
  EXPECT_EQ(error_of(dir / "indexed.fgb"),
            (dir / "indexed.fgb").string() + " layer town: feature 0 and feature 1 overlap, and this FlatGeobuf keeps its "
            "features in its spatial index's order, not the order they were drawn in, so which covers the other is unknown; "
            "write it without the index (ogr2ogr -lco SPATIAL_INDEX=NO) or as a GeoPackage");
  translate(dir / "town.geojson", dir / "unindexed.fgb", "FlatGeobuf", "", "SPATIAL_INDEX=NO");
  write(dir / "town.exacity.json", kSettings.dump());
  write(dir / "unindexed.exacity.json", kSettings.dump());
  generate(dir / "town.geojson", dir / "from-geojson");
  generate(dir / "unindexed.fgb", dir / "from-fgb");
  expect_same_layers(dir / "from-geojson", dir / "from-fgb");
  // The park moved beside the zone, touching it along an edge: no overlap, nothing refused.
  town["features"][1]["geometry"]["coordinates"] =
      ordered_json::parse("[[[385600, 6672300], [385700, 6672300], [385700, 6672400], [385600, 6672400], [385600, 6672300]]]");
  write(dir / "beside.geojson", town.dump());
  translate(dir / "beside.geojson", dir / "beside.fgb", "FlatGeobuf");
  EXPECT_EQ(error_of(dir / "beside.fgb"), "");
}

TEST(Gis, AnOsmExtractBecomesZonesRoadsAndWater) {
  const Sketch sketch = load_sketch(kVillage);
  EXPECT_EQ(epsg_of(sketch.crs), 32632);  // lon 10: UTM zone 32N
  std::multiset<ZoneType> zones;
  for (const ZoneFeature& z : sketch.zones) zones.insert(z.type);
  EXPECT_EQ(zones, (std::multiset<ZoneType>{ZoneType::Residential, ZoneType::Commercial, ZoneType::Park,
                                            ZoneType::Water, ZoneType::Water}));  // the pond and the river
  for (const ZoneFeature& z : sketch.zones)
    if (z.type == ZoneType::Commercial) {  // the multipolygon relation, its courtyard a hole
      ASSERT_EQ(z.polygons.size(), 1u);
      EXPECT_EQ(z.polygons[0].holes.size(), 1u);
      EXPECT_NE(z.source.find("relation 900"), std::string::npos) << z.source;
    }
  std::map<RoadClass, int> roads;
  for (const RoadFeature& r : sketch.roads) {
    ++roads[r.road_class];
    if (r.road_class == RoadClass::Highway) {
      EXPECT_EQ(r.width, 14);  // lanes=4
    }
  }
  EXPECT_EQ(roads[RoadClass::Highway], 1);
  EXPECT_EQ(roads[RoadClass::Local], 6);  // the footway and the tunnel left out
  EXPECT_EQ(sketch.zone_settings.at(ZoneType::Residential).roads.layout->name(), "streets");
  EXPECT_EQ(sketch.seed, 11u);  // village.exacity.json
  const ordered_json doc = ordered_json::parse(sketch.geojson);
  EXPECT_EQ(doc["osm"]["skipped"], ordered_json::parse(R"({"highway=footway": 1, "tunnel": 1})"));

  const fs::path out = testing_util::temp_dir("gis-village") / "out";
  const GenerateResult result = generate(kVillage, out);
  EXPECT_TRUE(result.valid);
  EXPECT_GT(result.report["counts"]["lots"].get<int>(), 50);
  EXPECT_EQ(result.report["counts"]["water"].get<int>(), 2);
  // report.json counts every feature the extract's reader took, left out and mended (they
  // were only in OUT/sketch.geojson), and what became of the roads it took: all 7 in the
  // map, each with its area.
  const ordered_json& osm = result.report["osm"];
  EXPECT_EQ(osm["taken"], ordered_json::parse(R"({"rivers": 1, "roads": 7, "zones": 4})")) << osm.dump();
  ASSERT_EQ(osm["files"].size(), 1u) << osm.dump();
  EXPECT_EQ(osm["files"][0]["left_out"], 2);
  EXPECT_EQ(osm["files"][0]["left_out_why"], doc["osm"]["skipped"]);
  EXPECT_EQ(osm["files"][0]["repaired"], ordered_json::array());
  EXPECT_EQ(result.report["sketch_roads"], ordered_json::parse(R"({"in_sketch": 7, "with_road_area": 7,
      "without_road_area": 0, "narrowed_for_mapped_buildings": 0, "generated": 0})"));
}

TEST(Gis, EveryVectorFormatReadsBackWithOgr) {
  const fs::path out = testing_util::temp_dir("gis-out") / "out";
  const GenerateResult result = generate(kVillage, out, {"gpkg", "fgb", "shp", "dxf"}, kLibrary);
  ASSERT_TRUE(result.valid);
  start_gdal();
  auto open = [](const fs::path& file) {
    return GDALDatasetUniquePtr(GDALDataset::Open(file.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  };
  const std::vector<std::string> layers{"blocks", "buildings", "clutter", "lots", "road_areas", "roads", "water", "zones"};
  std::map<std::string, std::size_t> counts;
  for (const std::string& name : layers)
    counts[name] = nlohmann::json::parse(cli_util::read(out / "vector" / (name + ".geojson")))["features"].size();
  auto expect_layer = [&](OGRLayer* layer, const std::string& name, const std::string& where) {
    ASSERT_NE(layer, nullptr) << where << " " << name;
    EXPECT_EQ(static_cast<std::size_t>(layer->GetFeatureCount()), counts[name]) << where << " " << name;
    const OGRSpatialReference* srs = layer->GetSpatialRef();
    ASSERT_NE(srs, nullptr) << where << " " << name;
    EXPECT_STREQ(srs->GetAuthorityCode(nullptr), "32632") << where << " " << name;
    EXPECT_GE(layer->GetLayerDefn()->GetFieldIndex("id"), 0) << where << " " << name;
  };
  GDALDatasetUniquePtr gpkg = open(out / "city.gpkg");
  ASSERT_TRUE(gpkg);
  EXPECT_EQ(gpkg->GetLayerCount(), static_cast<int>(layers.size()));
  for (const std::string& name : layers) {
    expect_layer(gpkg->GetLayerByName(name.c_str()), name, "city.gpkg");
    GDALDatasetUniquePtr fgb = open(out / "vector" / (name + ".fgb"));
    ASSERT_TRUE(fgb) << name;
    expect_layer(fgb->GetLayer(0), name, name + ".fgb");
    GDALDatasetUniquePtr shp = open(out / "vector" / "shp" / (name + ".shp"));
    ASSERT_TRUE(shp) << name;
    expect_layer(shp->GetLayer(0), name, name + ".shp");
  }
  // Attributes as the GeoJSON has them: a lot's block, a building's height.
  OGRLayer* buildings = gpkg->GetLayerByName("buildings");
  OGRFeatureUniquePtr first(buildings->GetNextFeature());
  ASSERT_TRUE(first);
  EXPECT_GT(first->GetFieldAsDouble("height"), 0);
  EXPECT_STREQ(first->GetFieldAsString("kind"), "building");
  // Same sketch, same bytes, in every format: GeoPackage and DBF would stamp the time.
  const fs::path again = testing_util::temp_dir("gis-out-again") / "out";
  generate(kVillage, again, {"gpkg", "fgb", "shp", "dxf"}, kLibrary);
  for (const fs::path file : {"city.gpkg", "city.dxf", "city.osm", "vector/roads.fgb", "vector/shp/lots.dbf"})
    EXPECT_EQ(cli_util::read(out / file), cli_util::read(again / file)) << file;
  // DXF: every layer's entities on a CAD layer of its name.
  GDALDatasetUniquePtr dxf = open(out / "city.dxf");
  ASSERT_TRUE(dxf);
  std::map<std::string, std::size_t> cad;
  OGRLayer* entities = dxf->GetLayer(0);
  for (OGRFeatureUniquePtr f(entities->GetNextFeature()); f; f.reset(entities->GetNextFeature())) ++cad[f->GetFieldAsString("Layer")];
  for (const std::string& name : layers)
    EXPECT_EQ(cad[name], counts[name]) << name;
}

// The formats are written from the layers in memory, not from the GeoJSON files: into a
// folder without them, every feature with every attribute as the layer has it.
TEST(Gis, EveryVectorFormatIsWrittenFromTheLayersWithoutTheirGeoJsonFiles) {
  const fs::path out = testing_util::temp_dir("gis-no-geojson");
  StageClock clock(nullptr, kCityStages);
  const Sketch sketch = load_sketch(kVillage, true, kLibrary);
  const City city = build_city(sketch, clock);
  const Layer clutter = clutter_layer(city.clutter.items, city.ground, city.model_library());
  const std::vector<const Layer*> layers = vector_files(city.layers, clutter);
  write_vector_formats(layers, out, {"gpkg", "fgb", "shp", "dxf"}, city.settings.crs);
  EXPECT_FALSE(fs::exists(out / "vector" / "roads.geojson"));
  start_gdal();
  auto open = [](const fs::path& file) {
    return GDALDatasetUniquePtr(GDALDataset::Open(file.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  };
  GDALDatasetUniquePtr gpkg = open(out / "city.gpkg");
  ASSERT_TRUE(gpkg);
  ASSERT_EQ(gpkg->GetLayerCount(), 8);
  std::map<std::string, std::size_t> cad;
  GDALDatasetUniquePtr dxf = open(out / "city.dxf");
  ASSERT_TRUE(dxf);
  OGRLayer* entities = dxf->GetLayer(0);
  for (OGRFeatureUniquePtr f(entities->GetNextFeature()); f; f.reset(entities->GetNextFeature())) ++cad[f->GetFieldAsString("Layer")];
  for (const Layer* layer : layers) {
    SCOPED_TRACE(layer->name);
    EXPECT_EQ(cad[layer->name], layer->features.size());
    GDALDatasetUniquePtr fgb = open(out / "vector" / (layer->name + ".fgb"));
    GDALDatasetUniquePtr shp = open(out / "vector" / "shp" / (layer->name + ".shp"));
    ASSERT_TRUE(fgb && shp);
    EXPECT_EQ(static_cast<std::size_t>(fgb->GetLayer(0)->GetFeatureCount()), layer->features.size());
    EXPECT_EQ(static_cast<std::size_t>(shp->GetLayer(0)->GetFeatureCount()), layer->features.size());
    OGRLayer* written = gpkg->GetLayerByName(layer->name.c_str());
    ASSERT_NE(written, nullptr);
    ASSERT_EQ(static_cast<std::size_t>(written->GetFeatureCount()), layer->features.size());
    std::set<std::string> keys;
    for (const VectorFeature& feature : layer->features)
      for (const auto& [key, value] : feature.properties.items()) keys.insert(key);
    EXPECT_EQ(static_cast<std::size_t>(written->GetLayerDefn()->GetFieldCount()), keys.size());
    written->ResetReading();
    for (const VectorFeature& feature : layer->features) {
      OGRFeatureUniquePtr f(written->GetNextFeature());
      ASSERT_TRUE(f);
      for (const auto& [key, value] : feature.properties.items()) {
        const int i = f->GetFieldIndex(key.c_str());
        ASSERT_GE(i, 0) << key;
        if (value.is_null()) EXPECT_FALSE(f->IsFieldSetAndNotNull(i)) << key;
        else if (value.is_string()) EXPECT_EQ(f->GetFieldAsString(i), value.get<std::string>()) << key;
        else if (value.is_boolean()) EXPECT_EQ(f->GetFieldAsInteger(i), value.get<bool>() ? 1 : 0) << key;
        else if (value.is_number_integer()) EXPECT_EQ(f->GetFieldAsInteger64(i), value.get<std::int64_t>()) << key;
        else if (value.is_number_float()) EXPECT_EQ(f->GetFieldAsDouble(i), value.get<double>()) << key;
        else EXPECT_EQ(nlohmann::json::parse(f->GetFieldAsString(i)), nlohmann::json::parse(value.dump())) << key;
      }
      // The geometry's first position, as the layer has it.
      const OGRGeometry* g = f->GetGeometryRef();
      ASSERT_NE(g, nullptr);
      const geom::Vec2 first = layer->lines || layer->name == "clutter" ? feature.line.at(0) : feature.polygon.outer.at(0);
      const OGRPoint* point = layer->name == "clutter" ? g->toPoint() : nullptr;
      const OGRSimpleCurve* curve = layer->lines ? g->toLineString() : point ? nullptr : g->toPolygon()->getExteriorRing();
      EXPECT_EQ(point ? point->getX() : curve->getX(0), first.x);
      EXPECT_EQ(point ? point->getY() : curve->getY(0), first.y);
    }
  }
}

TEST(Gis, EmptyLayersKeepTheirGeometryTypeAndADutchGridSketchItsCrsInEveryFormat) {
  const fs::path dir = testing_util::temp_dir("gis-empty-layers");
  // A park in the Dutch national grid, without Exacity's trees and lamps: every layer but
  // the zones is empty.
  write(dir / "park.geojson", R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::28992"}},
    "exacity": {"builtin_models": []},
    "features": [{"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon",
      "coordinates": [[[85000, 446000], [85200, 446000], [85200, 446150], [85000, 446150], [85000, 446000]]]}}]})");
  const GenerateResult result = generate(dir / "park.geojson", dir / "out", {"gpkg", "fgb", "shp"});
  ASSERT_TRUE(result.valid);
  const std::map<std::string, OGRwkbGeometryType> types{
      {"zones", wkbPolygon},      {"water", wkbPolygon},     {"roads", wkbLineString}, {"road_areas", wkbPolygon},
      {"blocks", wkbPolygon},     {"lots", wkbPolygon},      {"buildings", wkbPolygon}, {"clutter", wkbPoint}};
  start_gdal();
  auto open = [](const fs::path& file) {
    return GDALDatasetUniquePtr(GDALDataset::Open(file.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  };
  GDALDatasetUniquePtr gpkg = open(dir / "out" / "city.gpkg");
  ASSERT_TRUE(gpkg);
  for (const auto& [name, type] : types) {
    SCOPED_TRACE(name);
    EXPECT_EQ(nlohmann::json::parse(cli_util::read(dir / "out" / "vector" / (name + ".geojson")))["features"].size(),
              name == "zones" ? 1u : 0u);
    GDALDatasetUniquePtr fgb = open(dir / "out" / "vector" / (name + ".fgb"));
    GDALDatasetUniquePtr shp = open(dir / "out" / "vector" / "shp" / (name + ".shp"));
    ASSERT_TRUE(fgb);
    ASSERT_TRUE(shp);
    for (OGRLayer* layer : {gpkg->GetLayerByName(name.c_str()), fgb->GetLayer(0), shp->GetLayer(0)}) {
      ASSERT_NE(layer, nullptr);
      EXPECT_EQ(wkbFlatten(layer->GetGeomType()), type) << OGRGeometryTypeToName(layer->GetGeomType());
      ASSERT_NE(layer->GetSpatialRef(), nullptr);
      EXPECT_STREQ(layer->GetSpatialRef()->GetAuthorityCode(nullptr), "28992");
    }
  }
  EXPECT_EQ(nlohmann::json::parse(cli_util::read(dir / "out" / "city.city.json"))["metadata"]["referenceSystem"],
            "https://www.opengis.net/def/crs/EPSG/0/28992");
}

TEST(Gis, CityOsmReadsBackWithOsmiumAsOneNetworkAndClosedBuildings) {
  const fs::path out = testing_util::temp_dir("gis-osm") / "out";
  const GenerateResult result = generate(kVillage, out, {}, kLibrary);
  ASSERT_TRUE(result.valid);
  EXPECT_EQ(result.report["exports"]["city_osm"], "city.osm");
  struct Reader : osmium::handler::Handler {
    std::map<osmium::object_id_type, osmium::object_id_type> parent;  // union-find over nodes
    osmium::object_id_type find(osmium::object_id_type n) {
      while (parent.count(n) && parent[n] != n) n = parent[n] = parent.count(parent[n]) ? parent[parent[n]] : parent[n];
      return n;
    }
    int highways = 0, buildings = 0, open_buildings = 0, lamps = 0;
    std::set<osmium::object_id_type> street_nodes;
    bool in_place = true;
    void node(const osmium::Node& n) {
      in_place &= std::abs(n.location().lon() - 10.003) < 0.02 && std::abs(n.location().lat() - 48.0015) < 0.02;
      lamps += n.tags().has_tag("highway", "street_lamp");
    }
    void way(const osmium::Way& w) {
      if (w.tags().has_key("highway")) {
        ++highways;
        for (const auto& ref : w.nodes()) {
          street_nodes.insert(ref.ref());
          parent.try_emplace(ref.ref(), ref.ref());
          parent[find(ref.ref())] = find(w.nodes().front().ref());
        }
      }
      if (w.tags().has_tag("building", "yes")) ++buildings, open_buildings += !w.is_closed();
    }
  } reader;
  osmium::io::Reader file{(out / "city.osm").string()};
  osmium::apply(file, reader);
  file.close();
  EXPECT_TRUE(reader.in_place);
  EXPECT_EQ(reader.highways, result.report["counts"]["roads"].get<int>());
  EXPECT_GT(reader.buildings, 50);
  EXPECT_EQ(reader.open_buildings, 0);
  EXPECT_EQ(reader.lamps, result.report["clutter"]["placed"]["lamp"].get<int>());
  EXPECT_GT(reader.lamps, 10);
  std::set<osmium::object_id_type> components;
  for (osmium::object_id_type n : reader.street_nodes) components.insert(reader.find(n));
  EXPECT_EQ(components.size(), 1u);  // one street network: junctions share their nodes
}

TEST(Gis, BadInputsAreOneLineNamingTheFile) {
  const fs::path dir = testing_util::temp_dir("gis-bad");
  write(dir / "junk.gpkg", "not a database");
  EXPECT_NE(error_of(dir / "junk.gpkg").find("junk.gpkg: OGR cannot read it"), std::string::npos) << error_of(dir / "junk.gpkg");
  // A layer without zone or road fields.
  const std::string crs = R"("crs": {"type": "name", "properties": {"name": "EPSG:32635"}}, )";
  write(dir / "plain.geojson", R"({"type": "FeatureCollection", )" + crs + R"("features": [{"type": "Feature", "properties": {"kind": "x"},
      "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [100, 0], [100, 100], [0, 0]]]}}]})");
  translate(dir / "plain.geojson", dir / "plain.gpkg", "GPKG");
  EXPECT_NE(error_of(dir / "plain.gpkg").find("layer plain: has neither a \"zone\" nor a \"road\" field"), std::string::npos)
      << error_of(dir / "plain.gpkg");
  // A feature's mistake names the layer and the feature.
  write(dir / "bad.geojson", R"({"type": "FeatureCollection", )" + crs + R"("features": [{"type": "Feature", "properties": {"zone": "residental"},
      "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [100, 0], [100, 100], [0, 0]]]}}]})");
  translate(dir / "bad.geojson", dir / "bad.gpkg", "GPKG");
  EXPECT_NE(error_of(dir / "bad.gpkg").find("bad.gpkg layer bad feature 1: unknown zone type \"residental\""), std::string::npos)
      << error_of(dir / "bad.gpkg");
  // Settings both in the sketch and beside it.
  write(dir / "both.geojson", R"({"type": "FeatureCollection", "exacity": {"seed": 1}, "features": []})");
  write(dir / "both.exacity.json", "{}");
  EXPECT_NE(error_of(dir / "both.geojson").find("both.exacity.json: the sketch both.geojson has settings of its own"),
            std::string::npos) << error_of(dir / "both.geojson");
  // An extract with nothing Exacity reads, and one that is not OSM at all.
  write(dir / "empty.osm", R"(<?xml version="1.0"?><osm version="0.6"><node id="1" lat="48" lon="10"/></osm>)");
  EXPECT_NE(error_of(dir / "empty.osm").find("has no highways, land use or water"), std::string::npos) << error_of(dir / "empty.osm");
  write(dir / "junk.osm", "{not xml");
  EXPECT_NE(error_of(dir / "junk.osm").find("junk.osm: not a readable OpenStreetMap extract"), std::string::npos)
      << error_of(dir / "junk.osm");
  // A crs PROJ does not know.
  write(dir / "crs.geojson", R"({"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "EPSG:999999"}},
      "features": [{"type": "Feature", "properties": {"zone": "park"}, "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [100, 0], [100, 100], [0, 0]]]}}]})");
  EXPECT_NE(error_of(dir / "crs.geojson").find("is not a CRS PROJ knows"), std::string::npos) << error_of(dir / "crs.geojson");
  // ... and only that line: PROJ's own message kept off the terminal.
  const cli_util::Result run = cli_util::run("generate " + (dir / "crs.geojson").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(run.out.rfind("exacity: error: " + (dir / "crs.geojson").string() + ": crs:", 0), 0u) << run.out;
  EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
}

namespace {

// OpenStreetMap's land use and streets as GIS tools export them (docs/gis.md,
// OpenStreetMap): tags as columns, the rest in GDAL's "other_tags".
ordered_json osm_tagged_town() {
  return ordered_json::parse(R"({"type": "FeatureCollection",
    "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32635"}},
    "features": [
      {"type": "Feature", "properties": {"landuse": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[385000, 6672000], [385600, 6672000], [385600, 6672500], [385000, 6672500], [385000, 6672000]]]}},
      {"type": "Feature", "properties": {"leisure": "park"},
       "geometry": {"type": "Polygon", "coordinates": [[[385100, 6672300], [385200, 6672300], [385200, 6672400], [385100, 6672400], [385100, 6672300]]]}},
      {"type": "Feature", "properties": {"highway": "residential", "other_tags": "\"lanes\"=>\"2\",\"surface\"=>\"asphalt\""},
       "geometry": {"type": "LineString", "coordinates": [[384950, 6672250], [385650, 6672250]]}},
      {"type": "Feature", "properties": {"highway": "footway"},
       "geometry": {"type": "LineString", "coordinates": [[385300, 6672000], [385300, 6672500]]}},
      {"type": "Feature", "properties": {"landuse": "farmland"},
       "geometry": {"type": "Polygon", "coordinates": [[[386000, 6672000], [386100, 6672000], [386100, 6672100], [386000, 6672000]]]}},
      {"type": "Feature", "properties": {"landuse": "residential"},
       "geometry": {"type": "Polygon", "coordinates": [[[385000, 6671000], [385010, 6671000], [385000, 6671000]]]}},
      {"type": "Feature", "properties": {"waterway": "river", "width": 20},
       "geometry": {"type": "LineString", "coordinates": [[384900, 6672600], [385700, 6672600]]}},
      {"type": "Feature", "properties": {"zone": "commercial"},
       "geometry": {"type": "Polygon", "coordinates": [[[385600, 6672000], [385800, 6672000], [385800, 6672200], [385600, 6672200], [385600, 6672000]]]}},
      {"type": "Feature", "properties": {"highway": "crossing"}, "geometry": {"type": "Point", "coordinates": [385300, 6672250]}},
      {"type": "Feature", "properties": {"osm_way_id": "27204443", "amenity": "school", "landuse": null},
       "geometry": {"type": "Polygon", "coordinates": [[[385300, 6672100], [385350, 6672100], [385350, 6672150], [385300, 6672100]]]}}]})");
}

geom::Box box_of(const ZoneFeature& zone) {
  geom::Box box = geom::Box::none();
  for (const geom::Polygon& p : zone.polygons)
    for (geom::Vec2 v : p.outer) box.add(v);
  return box;
}

}  // namespace

TEST(Gis, OsmTaggedFeaturesBecomeZonesAndRoads) {
  const fs::path dir = testing_util::temp_dir("gis-osm-tags");
  write(dir / "town.geojson", osm_tagged_town().dump());
  translate(dir / "town.geojson", dir / "town.gpkg", "GPKG");
  for (const char* name : {"town.geojson", "town.gpkg"}) {
    SCOPED_TRACE(name);
    const Sketch sketch = load_sketch(dir / name);
    std::vector<ZoneType> zones;
    for (const ZoneFeature& z : sketch.zones) zones.push_back(z.type);
    // The tagged zones in their places, land use before parks before water; the user's own
    // commercial zone where it was.
    EXPECT_EQ(zones, (std::vector<ZoneType>{ZoneType::Residential, ZoneType::Park, ZoneType::Water, ZoneType::Commercial}));
    // Land use coming with streets reaches 8 m further, to meet them; the park does not.
    EXPECT_NEAR(box_of(sketch.zones[0]).min_x, 385000 - 8, 1e-6);
    EXPECT_NEAR(box_of(sketch.zones[0]).max_y, 6672500 + 8, 1e-6);
    EXPECT_NEAR(box_of(sketch.zones[1]).min_x, 385100, 1e-6);
    // The river, 20 m wide.
    EXPECT_NEAR(box_of(sketch.zones[2]).min_y, 6672600 - 10, 1e-6);
    EXPECT_NEAR(box_of(sketch.zones[2]).max_y, 6672600 + 10, 1e-6);
    ASSERT_EQ(sketch.roads.size(), 1u);
    EXPECT_EQ(sketch.roads[0].road_class, RoadClass::Local);
    EXPECT_EQ(sketch.roads[0].width, 7);  // lanes=2 in other_tags
    ASSERT_EQ(sketch.osm_counts.size(), 1u);
    EXPECT_EQ(sketch.osm_counts[0].file, (dir / name).string());
    EXPECT_EQ(sketch.osm_counts[0].left_out, (std::map<std::string, int>{
                                       {"highway=footway", 1}, {"landuse=farmland", 1}, {"areas of fewer than 3 distinct points", 1},
                                       {"highway=crossing as a point", 1}, {"amenity=school", 1}}));
    EXPECT_EQ(sketch.zone_settings.at(ZoneType::Residential).roads.layout->name(), "streets");
  }
  // Features taken out do not move the others' names: the user's zone is still features[7].
  const Sketch sketch = load_sketch(dir / "town.geojson");
  EXPECT_EQ(sketch.zones[3].source, (dir / "town.geojson").string() + " features[7]");
  EXPECT_TRUE(generate(dir / "town.geojson", dir / "out").valid);

  // Tags that make nothing at all are one line.
  ordered_json paths = osm_tagged_town();
  paths["features"] = ordered_json::array({paths["features"][3], paths["features"][3], paths["features"][4]});
  write(dir / "paths.geojson", paths.dump());
  EXPECT_NE(error_of(dir / "paths.geojson")
                .find("paths.geojson: no feature's OpenStreetMap tags make a zone or a road (highway=footway 2, landuse=farmland 1)"),
            std::string::npos)
      << error_of(dir / "paths.geojson");
}

TEST(Gis, SeveralSketchFilesAreReadAsOne) {
  const fs::path dir = testing_util::temp_dir("gis-several");
  ordered_json town = osm_tagged_town(), land = town, streets = town;
  land["features"] = ordered_json::array();
  streets["features"] = ordered_json::array();
  streets.erase("crs");  // taken to be in the land use's
  for (const ordered_json& f : town["features"])
    (f["geometry"]["type"] == "Polygon" ? land : streets)["features"].push_back(f);
  write(dir / "town.geojson", town.dump());
  write(dir / "land.geojson", land.dump());
  write(dir / "streets.geojson", streets.dump());
  const Sketch one = load_sketch(dir / "town.geojson");
  const Sketch two = load_sketch(std::vector<fs::path>{dir / "land.geojson", dir / "streets.geojson"});
  // The same zones and roads, but for their order: each file's features in turn.
  using Ring = std::vector<std::pair<double, double>>;
  std::multiset<std::pair<int, Ring>> rings_one, rings_two;
  for (const auto& [sketch, rings] : {std::pair{&one, &rings_one}, std::pair{&two, &rings_two}})
    for (const ZoneFeature& z : sketch->zones)
      for (const geom::Polygon& p : z.polygons) {
        Ring ring;
        for (geom::Vec2 v : p.outer) ring.push_back({v.x, v.y});
        rings->insert({static_cast<int>(z.type), ring});
      }
  EXPECT_EQ(rings_one, rings_two);
  ASSERT_EQ(two.roads.size(), 1u);
  EXPECT_EQ(two.roads[0].lines, one.roads[0].lines);
  EXPECT_EQ(epsg_of(two.crs), 32635);
  // Each file's own features counted and named by it: the land use's farmland and
  // degenerate area, the streets' footway and crossing.
  ASSERT_EQ(one.osm_counts.size(), 1u);
  ASSERT_EQ(two.osm_counts.size(), 2u);
  EXPECT_EQ(two.osm_counts[0].file, (dir / "land.geojson").string());
  EXPECT_EQ(two.osm_counts[0].left_out,
            (std::map<std::string, int>{{"landuse=farmland", 1}, {"areas of fewer than 3 distinct points", 1}, {"amenity=school", 1}}));
  EXPECT_EQ(two.osm_counts[1].file, (dir / "streets.geojson").string());
  EXPECT_EQ(two.osm_counts[1].left_out, (std::map<std::string, int>{{"highway=footway", 1}, {"highway=crossing as a point", 1}}));
  std::map<std::string, int> together = two.osm_counts[0].left_out;
  together.insert(two.osm_counts[1].left_out.begin(), two.osm_counts[1].left_out.end());
  EXPECT_EQ(together, one.osm_counts[0].left_out);
  EXPECT_FALSE(ordered_json::parse(two.geojson)["osm"].contains("file"));
  // The notes say so, a file each.
  const cli_util::Result run = cli_util::run("generate " + (dir / "land.geojson").string() + " " +
                                             (dir / "streets.geojson").string() + " -o " + (dir / "out").string() + " -q");
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("note: " + (dir / "land.geojson").string() +
                         ": left out 3 OpenStreetMap features whose tags make no zone or road (amenity=school 1, areas of "
                         "fewer than 3 distinct points 1, landuse=farmland 1)"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("note: " + (dir / "streets.geojson").string() +
                         ": left out 2 OpenStreetMap features whose tags make no zone or road (highway=crossing as a "
                         "point 1, highway=footway 1)"),
            std::string::npos)
      << run.out;

  auto error_of_both = [&](const fs::path& a, const fs::path& b) -> std::string {
    try {
      load_sketch(std::vector<fs::path>{a, b});
    } catch (const UserError& e) {
      return e.what();
    }
    return "";
  };
  // A mistake in the second file is named by that file.
  ordered_json bad = streets;
  bad["features"].push_back({{"type", "Feature"}, {"properties", {{"road", "motorway"}}},
                             {"geometry", {{"type", "LineString"}, {"coordinates", {{385000, 6672100}, {385500, 6672100}}}}}});
  write(dir / "bad.geojson", bad.dump());
  EXPECT_EQ(error_of_both(dir / "land.geojson", dir / "bad.geojson").rfind((dir / "bad.geojson").string() + " features[4]: unknown road class", 0),
            0u)
      << error_of_both(dir / "land.geojson", dir / "bad.geojson");
  // Settings in both, a grid map: refused, naming the file.
  write(dir / "streets.exacity.json", R"({"seed": 2})");
  write(dir / "land.exacity.json", R"({"seed": 3})");
  EXPECT_NE(error_of_both(dir / "land.geojson", dir / "streets.geojson").find("streets.geojson: has settings, and so has"),
            std::string::npos);
  fs::remove(dir / "streets.exacity.json");
  EXPECT_EQ(load_sketch(std::vector<fs::path>{dir / "land.geojson", dir / "streets.geojson"}).seed, 3u);
  EXPECT_NE(error_of_both(dir / "land.geojson", cli_util::kSource / "examples" / "grid" / "town.grid")
                .find("a grid map is a whole sketch"),
            std::string::npos);
}

namespace {

// Every position of a GeoJSON document's features through `t`.
void transform_positions(ordered_json& doc, OGRCoordinateTransformation& t) {
  std::function<void(ordered_json&)> each = [&](ordered_json& c) {
    if (c[0].is_number()) {
      double x = c[0], y = c[1];
      ASSERT_TRUE(t.Transform(1, &x, &y));
      c = {x, y};
      return;
    }
    for (ordered_json& inner : c) each(inner);
  };
  for (ordered_json& f : doc["features"]) each(f["geometry"]["coordinates"]);
}

std::unique_ptr<OGRCoordinateTransformation> transformation(int from, int to) {
  OGRSpatialReference a, b;
  a.importFromEPSG(from), b.importFromEPSG(to);
  a.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER), b.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return std::unique_ptr<OGRCoordinateTransformation>(OGRCreateCoordinateTransformation(&a, &b));
}

// A document in metres of UTM zone `utm` moved so that its first position is at `origin`
// (that zone's metres), then drawn in lon/lat without a crs, as GeoJSON's default is.
ordered_json in_lon_lat(ordered_json doc, int utm, geom::Vec2 origin) {
  const geom::Vec2 first{doc["features"][0]["geometry"]["coordinates"][0][0][0].get<double>(),
                         doc["features"][0]["geometry"]["coordinates"][0][0][1].get<double>()};
  std::function<void(ordered_json&)> move = [&](ordered_json& c) {
    if (c[0].is_number()) return void(c = {c[0].get<double>() - first.x + origin.x, c[1].get<double>() - first.y + origin.y});
    for (ordered_json& inner : c) move(inner);
  };
  for (ordered_json& f : doc["features"]) move(f["geometry"]["coordinates"]);
  transform_positions(doc, *transformation(utm, 4326));
  doc.erase("crs");
  return doc;
}

// Converts a GeoJSON file in lon/lat to `epsg` with OGR, as `ogr2ogr -t_srs EPSG:N` does.
void reproject(const fs::path& from, const fs::path& to, const char* driver, int epsg) {
  translate(from, to, driver, "EPSG:" + std::to_string(epsg));
}

// The areas of a city's buildings, smallest first.
std::vector<double> building_areas(const fs::path& out) {
  std::vector<double> areas;
  const nlohmann::json doc = nlohmann::json::parse(cli_util::read(out / "vector" / "buildings.geojson"));
  for (const auto& f : doc["features"]) {
    if (f["properties"].value("kind", "") != "building") continue;
    for (const auto& polygon : f["geometry"]["type"] == "Polygon" ? nlohmann::json::array({f["geometry"]["coordinates"]})
                                                                  : f["geometry"]["coordinates"]) {
      geom::Ring ring;
      for (const auto& p : polygon[0]) ring.push_back({p[0].get<double>(), p[1].get<double>()});
      areas.push_back(std::abs(geom::signed_area(ring)));
    }
  }
  std::sort(areas.begin(), areas.end());
  return areas;
}

// Two cities of one place: the same counts, and the same buildings within a square millimetre.
void expect_same_city(const GenerateResult& a, const fs::path& out_a, const GenerateResult& b, const fs::path& out_b) {
  for (const char* count : {"roads", "blocks", "lots", "buildings"})
    EXPECT_EQ(a.report["counts"][count], b.report["counts"][count]) << count;
  const std::vector<double> areas_a = building_areas(out_a), areas_b = building_areas(out_b);
  ASSERT_EQ(areas_a.size(), areas_b.size());
  for (std::size_t i = 0; i < areas_a.size(); ++i) EXPECT_NEAR(areas_a[i], areas_b[i], 1e-6) << i;
}

}  // namespace

TEST(Gis, WebMercatorAndFeetSketchesOfAPlaceAreItsLonLatCity) {
  const fs::path dir = testing_util::temp_dir("gis-mercator-feet");
  // San Francisco (UTM zone 10N): Web Mercator's scale there is 1.26, and California's
  // state plane (EPSG:2227) counts US survey feet.
  write(dir / "lonlat.geojson", in_lon_lat(town_in_metres(), 32610, {551000, 4180000}).dump());
  reproject(dir / "lonlat.geojson", dir / "mercator.gpkg", "GPKG", 3857);
  reproject(dir / "lonlat.geojson", dir / "feet.gpkg", "GPKG", 2227);
  for (const char* name : {"lonlat", "mercator", "feet"}) write(dir / (std::string(name) + ".exacity.json"), kSettings.dump());
  const Sketch lonlat = load_sketch(dir / "lonlat.geojson");
  ASSERT_EQ(epsg_of(lonlat.crs), 32610);
  for (const char* name : {"mercator.gpkg", "feet.gpkg"}) {
    SCOPED_TRACE(name);
    const Sketch sketch = load_sketch(dir / name);
    EXPECT_EQ(epsg_of(sketch.crs), 32610);
    ASSERT_EQ(sketch.zones.size(), lonlat.zones.size());
    for (std::size_t z = 0; z < sketch.zones.size(); ++z)
      for (std::size_t i = 0; i < sketch.zones[z].polygons[0].outer.size(); ++i) {
        EXPECT_NEAR(sketch.zones[z].polygons[0].outer[i].x, lonlat.zones[z].polygons[0].outer[i].x, 1e-3);
        EXPECT_NEAR(sketch.zones[z].polygons[0].outer[i].y, lonlat.zones[z].polygons[0].outer[i].y, 1e-3);
      }
  }
  const GenerateResult a = generate(dir / "lonlat.geojson", dir / "a");
  EXPECT_TRUE(a.valid);
  EXPECT_GT(a.report["counts"]["lots"].get<int>(), 20);
  for (const char* name : {"mercator", "feet"}) {
    SCOPED_TRACE(name);
    const GenerateResult b = generate(dir / (std::string(name) + ".gpkg"), dir / name);
    expect_same_city(a, dir / "a", b, dir / name);
    EXPECT_NE(cli_util::read(dir / name / "vector" / "lots.geojson").find("EPSG::32610"), std::string::npos);
  }
}

TEST(Gis, AHundredMetreSquareInFeetIsAHundredMetresOnTheGround) {
  const fs::path dir = testing_util::temp_dir("gis-feet-square");
  // A square of 100 m sides on the ellipsoid (PROJ's geodesics) in San Francisco.
  geod_geodesic wgs84;
  geod_init(&wgs84, 6378137, 1 / 298.257223563);
  std::vector<geom::Vec2> corners{{-122.42, 37.77}};
  for (double azimuth : {90.0, 0.0, -90.0}) {
    double lat = 0, lon = 0;
    geod_direct(&wgs84, corners.back().y, corners.back().x, azimuth, 100, &lat, &lon, nullptr);
    corners.push_back({lon, lat});
  }
  ordered_json ring = ordered_json::array();
  for (geom::Vec2 c : corners) ring.push_back({c.x, c.y});
  ring.push_back(ring[0]);
  ordered_json sketch = {{"type", "FeatureCollection"},
                         {"features", {{{"type", "Feature"}, {"properties", {{"zone", "residential"}}},
                                        {"geometry", {{"type", "Polygon"}, {"coordinates", {ring}}}}}}}};
  write(dir / "square.geojson", sketch.dump());
  reproject(dir / "square.geojson", dir / "feet.gpkg", "GPKG", 2227);
  reproject(dir / "square.geojson", dir / "feet.geojson", "GeoJSON", 2227);
  for (const char* name : {"feet.gpkg", "feet.geojson"}) {
    SCOPED_TRACE(name);
    const Sketch read = load_sketch(dir / name, false);
    ASSERT_EQ(epsg_of(read.crs), 32610);
    const geom::Ring& square = read.zones.at(0).polygons.at(0).outer;
    ASSERT_EQ(square.size(), 4u);
    // In Exacity's metres, the place's UTM map; back in lon/lat, 100 m on the ground.
    const ToLonLat to_lon_lat(32610);
    auto to_utm = transformation(4326, 32610);
    for (std::size_t i = 0; i < 4; ++i) {
      geom::Vec2 expected = corners[i];
      ASSERT_TRUE(to_utm->Transform(1, &expected.x, &expected.y));
      EXPECT_NEAR(square[i].x, expected.x, 1e-3);
      EXPECT_NEAR(square[i].y, expected.y, 1e-3);
    }
    for (std::size_t i = 0; i < 3; ++i) {
      const geom::Vec2 a = to_lon_lat(square[i]), b = to_lon_lat(square[i + 1]);
      double metres = 0;
      geod_inverse(&wgs84, a.y, a.x, b.y, b.x, &metres, nullptr, nullptr);
      EXPECT_NEAR(metres, 100, 1e-3) << "side " << i;
    }
  }
}

TEST(Gis, LonLatWithoutCrsIsFoundOverDegreesAndAcrossTheAntimeridian) {
  const fs::path dir = testing_util::temp_dir("gis-wide-lonlat");
  auto expect_projected_by_hand = [](const Sketch& sketch, const ordered_json& lonlat) {
    const std::optional<int> epsg = epsg_of(sketch.crs);
    ASSERT_TRUE(epsg);
    ordered_json by_hand = lonlat;
    transform_positions(by_hand, *transformation(4326, *epsg));
    const ordered_json& outer = by_hand["features"][0]["geometry"]["coordinates"][0];
    const geom::Ring& ring = sketch.zones.at(0).polygons.at(0).outer;
    ASSERT_EQ(ring.size() + 1, outer.size());
    for (std::size_t i = 0; i < ring.size(); ++i) {  // PROJ's metres, to the micrometre
      EXPECT_EQ(ring[i].x, std::round(outer[i][0].get<double>() * 1e6) / 1e6);
      EXPECT_EQ(ring[i].y, std::round(outer[i][1].get<double>() * 1e6) / 1e6);
    }
  };
  // Two places two degrees apart, as a sketch of a region: lon/lat, not metres.
  ordered_json wide = in_lon_lat(town_in_metres(), 32635, {385000, 6672000});
  ordered_json far = wide["features"][1];
  for (ordered_json& p : far["geometry"]["coordinates"][0]) p[0] = p[0].get<double>() + 2;
  wide["features"].push_back(far);
  write(dir / "wide.geojson", wide.dump());
  const Sketch region = load_sketch(dir / "wide.geojson", false);
  EXPECT_EQ(epsg_of(region.crs), 32635);
  expect_projected_by_hand(region, wide);

  // A town on the antimeridian (Taveuni, Fiji): longitudes from 179.99 to -179.99.
  const ordered_json fiji = in_lon_lat(town_in_metres(), 32760, {819500, 8140000});
  double west = 180, east = -180;
  for (const ordered_json& p : fiji["features"][0]["geometry"]["coordinates"][0])
    west = std::min(west, p[0].get<double>()), east = std::max(east, p[0].get<double>());
  ASSERT_GT(east, 179.9);
  ASSERT_LT(west, -179.9);
  write(dir / "fiji.geojson", fiji.dump());
  write(dir / "fiji.exacity.json", kSettings.dump());
  const Sketch town = load_sketch(dir / "fiji.geojson");
  EXPECT_TRUE(epsg_of(town.crs) == 32760 || epsg_of(town.crs) == 32701) << town.crs.dump();
  expect_projected_by_hand(town, fiji);
  // The town's 600 by 500 m across the antimeridian (turned by the two zones' convergence).
  const geom::Ring& ring = town.zones[0].polygons[0].outer;
  EXPECT_NEAR(std::hypot(ring[1].x - ring[0].x, ring[1].y - ring[0].y), 600, 1);
  EXPECT_NEAR(std::hypot(ring[2].x - ring[1].x, ring[2].y - ring[1].y), 500, 1);
  const GenerateResult city = generate(dir / "fiji.geojson", dir / "fiji");
  EXPECT_TRUE(city.valid);
  EXPECT_GT(city.report["counts"]["lots"].get<int>(), 20);
}

TEST(Gis, FeaturesCutAtTheAntimeridianMeetAgainExactly) {
  const fs::path dir = testing_util::temp_dir("gis-seam");
  // The town across the antimeridian in UTM metres, cut there as ogr2ogr -wrapdateline
  // does: each half computes its own crossing, some 1e-10 degrees from the other's.
  ordered_json town = town_in_metres();
  town["crs"] = crs_member(32760);
  std::function<void(ordered_json&)> move = [&](ordered_json& c) {
    if (c[0].is_number()) return void(c = {c[0].get<double>() + 819500 - 385000, c[1].get<double>() + 8140000 - 6672000});
    for (ordered_json& inner : c) move(inner);
  };
  for (ordered_json& f : town["features"]) move(f["geometry"]["coordinates"]);
  write(dir / "utm.geojson", town.dump());
  start_gdal();  // then to lon/lat as ogr2ogr -t_srs EPSG:4326 -wrapdateline does
  GDALDatasetH source = GDALOpenEx((dir / "utm.geojson").string().c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
  ASSERT_NE(source, nullptr);
  const char* args[] = {"-f", "GeoJSON", "-t_srs", "EPSG:4326", "-wrapdateline", nullptr};
  GDALVectorTranslateOptions* options = GDALVectorTranslateOptionsNew(const_cast<char**>(args), nullptr);
  GDALDatasetH cut = GDALVectorTranslate((dir / "fiji.geojson").string().c_str(), nullptr, 1, &source, options, nullptr);
  GDALVectorTranslateOptionsFree(options);
  ASSERT_NE(cut, nullptr);
  GDALClose(cut);
  GDALClose(source);
  const ordered_json written = ordered_json::parse(cli_util::read(dir / "fiji.geojson"));
  ASSERT_EQ(written["features"][0]["geometry"]["type"], "MultiPolygon");
  ASSERT_EQ(written["features"][2]["geometry"]["type"], "MultiLineString");
  std::set<double> seam_latitudes;  // as written: the halves' crossings differ
  for (const ordered_json& polygon : written["features"][0]["geometry"]["coordinates"])
    for (const ordered_json& p : polygon[0])
      if (std::abs(p[0].get<double>()) == 180) seam_latitudes.insert(p[1].get<double>());
  ASSERT_GT(seam_latitudes.size(), 2u);

  write(dir / "fiji.exacity.json", kSettings.dump());
  const Sketch sketch = load_sketch(dir / "fiji.geojson");
  // The road's halves end at one point, and every seam vertex of one half of the zone is a
  // vertex of the other.
  const std::vector<geom::Polyline>& road = sketch.roads.at(0).lines;
  ASSERT_EQ(road.size(), 2u);
  EXPECT_TRUE(road[0].back() == road[1].front() || road[0].front() == road[1].back());
  const std::vector<geom::Polygon>& halves = sketch.zones.at(0).polygons;
  ASSERT_EQ(halves.size(), 2u);
  auto shared = [](const geom::Ring& a, const geom::Ring& b) {
    return std::count_if(a.begin(), a.end(), [&](geom::Vec2 p) { return std::find(b.begin(), b.end(), p) != b.end(); });
  };
  EXPECT_EQ(shared(halves[0].outer, halves[1].outer), 2);
}

// Names that are not UTF-8 (Latin-1 from old tools) are read where they are text the outputs
// can hold, and refused in one line where they are the user's own file names; a file whose
// CRS is in degrees but whose coordinates are metres is named as such.
TEST(Gis, NamesNotInUtf8AndCoordinatesNotInTheFilesCrs) {
  const fs::path dir = testing_util::temp_dir("gis-not-utf8");
  ordered_json town = town_in_metres();
  write(dir / "town.geojson", town.dump());
  write(dir / "town.exacity.json", kSettings.dump());
  const std::string latin1 = "zon\xe9s";  // "zonés" in Latin-1
  start_gdal();
  auto to_gpkg = [&](const fs::path& from, const fs::path& to) {
    GDALDatasetH source = GDALOpenEx(from.string().c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
    ASSERT_NE(source, nullptr);
    const char* args[] = {"-f", "GPKG", "-nln", latin1.c_str(), nullptr};
    GDALVectorTranslateOptions* options = GDALVectorTranslateOptionsNew(const_cast<char**>(args), nullptr);
    GDALDatasetH made = GDALVectorTranslate(to.string().c_str(), nullptr, 1, &source, options, nullptr);
    GDALVectorTranslateOptionsFree(options);
    ASSERT_NE(made, nullptr);
    GDALClose(made);
    GDALClose(source);
  };
  to_gpkg(dir / "town.geojson", dir / "town.gpkg");
  // A layer named in Latin-1: the sources name it in UTF-8.
  const cli_util::Result named = cli_util::run("generate " + (dir / "town.gpkg").string() + " -o " + (dir / "out").string());
  ASSERT_EQ(named.code, 0) << named.out;
  const ordered_json sketch = ordered_json::parse(cli_util::read(dir / "out" / "sketch.geojson"));
  EXPECT_NE(sketch.dump().find("layer zon\u00e9s"), std::string::npos);

  auto refused = [&](const std::string& args, const std::string& says, const fs::path& out) {
    const cli_util::Result r = cli_util::run("generate " + args + " -o '" + out.string() + "'");
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_NE(r.out.find(says), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out));
  };
  // The user's own file names: the outputs record them in JSON.
  fs::copy_file(dir / "town.gpkg", dir / ("caf\xe9.gpkg"));
  refused("'" + (dir / "caf\xe9.gpkg").string() + "'", "its name is not UTF-8 text", dir / "out2");
  refused((dir / "town.gpkg").string(), "the output path is not UTF-8 text", dir / "out\xe9");
  // A GeoJSON in metres without a crs is lon/lat to ogr2ogr, as GeoJSON says: the GeoPackage
  // it writes is in EPSG:4326 with coordinates of hundreds of thousands.
  ordered_json no_crs = town;
  no_crs.erase("crs");
  write(dir / "no_crs.geojson", no_crs.dump());
  to_gpkg(dir / "no_crs.geojson", dir / "degrees.gpkg");
  refused((dir / "degrees.gpkg").string(),
          "degrees.gpkg layer zon\u00e9s feature 1: position [385000, 6672000] is no longitude and latitude, though " +
              (dir / "degrees.gpkg").string() + "'s CRS, EPSG:4326, counts in degrees",
          dir / "out3");
}

TEST(Gis, LonLatWithoutCrsSpanningTensOfDegreesIsRefusedButNoSmallSketchInMetres) {
  const fs::path dir = testing_util::temp_dir("gis-far-lonlat");
  // Helsinki's town and a copy of it 34 degrees west, in one file without a crs.
  ordered_json two_towns = in_lon_lat(town_in_metres(), 32635, {385000, 6672000});
  for (std::size_t i = 0; i < 3; ++i) {
    ordered_json copy = two_towns["features"][i];
    std::function<void(ordered_json&)> west = [&](ordered_json& c) {
      if (c[0].is_number()) return void(c[0] = c[0].get<double>() - 34);
      for (ordered_json& inner : c) west(inner);
    };
    west(copy["geometry"]["coordinates"]);
    two_towns["features"].push_back(copy);
  }
  write(dir / "towns.geojson", two_towns.dump());
  const std::string error = error_of(dir / "towns.geojson");
  EXPECT_EQ(error.rfind((dir / "towns.geojson").string() +
                            ": has no crs, and its coordinates lie within longitude and latitude ranges but span 34.0° "
                            "of longitude and 0.0° of latitude",
                        0),
            0u)
      << error;
  EXPECT_NE(error.find("add a \"crs\" member naming its CRS"), std::string::npos) << error;
  const cli_util::Result run = cli_util::run("generate " + (dir / "towns.geojson").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // Named as lon/lat, as the line says, it is a sketch one map cannot hold.
  two_towns["crs"] = crs_member(4326);
  write(dir / "named.geojson", two_towns.dump());
  EXPECT_NE(error_of(dir / "named.geojson").find("more than one map holds"), std::string::npos) << error_of(dir / "named.geojson");

  // Small sketches in metres, whose coordinates lie within lon/lat ranges too, stay in
  // metres with no place: 100 by 80 m at the origin in whole metres and in half metres,
  // and the town moved to the origin (500 by 400 m).
  auto metres = [](double step) {
    ordered_json doc = {{"type", "FeatureCollection"}, {"features", ordered_json::array()}};
    doc["features"].push_back({{"type", "Feature"}, {"properties", {{"zone", "residential"}}},
                               {"geometry", {{"type", "Polygon"},
                                             {"coordinates", {{{0, 0}, {100, 0}, {100, 80}, {0, 80}, {0, 0}}}}}}});
    doc["features"].push_back({{"type", "Feature"}, {"properties", {{"road", "local"}}},
                               {"geometry", {{"type", "LineString"}, {"coordinates", {{-5, 40 + step}, {105, 40 + step}}}}}});
    return doc;
  };
  ordered_json origin = town_in_metres();
  origin.erase("crs");
  std::function<void(ordered_json&)> to_origin = [&](ordered_json& c) {
    if (c[0].is_number()) return void(c = {c[0].get<double>() - 385000, c[1].get<double>() - 6672000});
    for (ordered_json& inner : c) to_origin(inner);
  };
  for (ordered_json& f : origin["features"]) to_origin(f["geometry"]["coordinates"]);
  for (const auto& [name, doc] : {std::pair{"whole.geojson", metres(0)}, std::pair{"half.geojson", metres(0.5)},
                                  std::pair{"origin.geojson", origin}}) {
    SCOPED_TRACE(name);
    write(dir / name, doc.dump());
    const Sketch sketch = load_sketch(dir / name, false);
    EXPECT_TRUE(sketch.crs.is_null()) << sketch.crs.dump();
    EXPECT_EQ(sketch.zones.at(0).polygons.at(0).outer[1].x, doc["features"][0]["geometry"]["coordinates"][0][1][0].get<double>());
  }
}

TEST(Gis, FilesReadTogetherAreEachBroughtFromTheirOwnCrs) {
  const fs::path dir = testing_util::temp_dir("gis-mixed-crs");
  // Land use in lon/lat without a crs, streets in Web Mercator: the one lon/lat town.
  const ordered_json town = in_lon_lat(osm_tagged_town(), 32635, {385000, 6672000});
  ordered_json land = town, streets = town;
  land["features"] = ordered_json::array(), streets["features"] = ordered_json::array();
  for (const ordered_json& f : town["features"])
    (f["geometry"]["type"] == "Polygon" ? land : streets)["features"].push_back(f);
  write(dir / "town.geojson", town.dump());
  write(dir / "land.geojson", land.dump());
  write(dir / "streets-lonlat.geojson", streets.dump());
  reproject(dir / "streets-lonlat.geojson", dir / "streets.gpkg", "GPKG", 3857);
  const Sketch one = load_sketch(dir / "town.geojson", false);
  const Sketch two = load_sketch(std::vector<fs::path>{dir / "land.geojson", dir / "streets.gpkg"}, false);
  EXPECT_EQ(epsg_of(two.crs), 32635);
  ASSERT_EQ(two.zones.size(), one.zones.size());
  ASSERT_EQ(two.roads.size(), one.roads.size());
  ASSERT_EQ(two.roads.size(), 1u);
  for (std::size_t i = 0; i < one.roads[0].lines[0].size(); ++i) {
    EXPECT_NEAR(two.roads[0].lines[0][i].x, one.roads[0].lines[0][i].x, 1e-6);
    EXPECT_NEAR(two.roads[0].lines[0][i].y, one.roads[0].lines[0][i].y, 1e-6);
  }
  for (const ZoneFeature& z : two.zones) {  // the river, widened from the street file's line
    if (z.type != ZoneType::Water) continue;
    EXPECT_NEAR(box_of(z).height(), 20, 1e-6);
  }
  // A file in another national grid is brought to the first's: land use in UTM 35N
  // metres, streets in 34N.
  ordered_json land_utm = land, streets_utm = streets;
  transform_positions(land_utm, *transformation(4326, 32635));
  transform_positions(streets_utm, *transformation(4326, 32634));
  land_utm["crs"] = crs_member(32635), streets_utm["crs"] = crs_member(32634);
  write(dir / "land-utm.geojson", land_utm.dump());
  write(dir / "streets-utm.geojson", streets_utm.dump());
  const Sketch grids = load_sketch(std::vector<fs::path>{dir / "land-utm.geojson", dir / "streets-utm.geojson"}, false);
  EXPECT_EQ(epsg_of(grids.crs), 32635);
  ASSERT_EQ(grids.roads.size(), 1u);
  EXPECT_NEAR(grids.roads[0].lines[0][0].x, one.roads[0].lines[0][0].x, 1e-6);
  EXPECT_NEAR(grids.roads[0].lines[0][0].y, one.roads[0].lines[0][0].y, 1e-6);
}

TEST(Gis, AMapInMetresTrueToScaleStaysAndOneFarFromScaleIsProjected) {
  const fs::path dir = testing_util::temp_dir("gis-kept-crs");
  // Delft in the Dutch national grid (EPSG:28992): its own metres, kept to the byte.
  ordered_json delft = in_lon_lat(town_in_metres(), 32631, {597000, 5763000});
  transform_positions(delft, *transformation(4326, 28992));
  delft["crs"] = crs_member(28992);
  write(dir / "delft.geojson", delft.dump());
  const Sketch kept = load_sketch(dir / "delft.geojson", false);
  EXPECT_EQ(epsg_of(kept.crs), 28992);
  EXPECT_EQ(kept.zones[0].polygons[0].outer[0].x, delft["features"][0]["geometry"]["coordinates"][0][0][0].get<double>());
  EXPECT_TRUE(kept.geojson.empty());  // the file as it is
  // UTM zone 35N's metres used 18 degrees west of its zone, where its scale is 4% off: the
  // zone of the place instead (32N).
  ordered_json stretched = in_lon_lat(town_in_metres(), 32632, {500000, 5320000});
  ordered_json lonlat = stretched;
  transform_positions(stretched, *transformation(4326, 32635));
  stretched["crs"] = crs_member(32635);
  write(dir / "stretched.geojson", stretched.dump());
  const Sketch moved = load_sketch(dir / "stretched.geojson", false);
  EXPECT_EQ(epsg_of(moved.crs), 32632);
  transform_positions(lonlat, *transformation(4326, 32632));
  EXPECT_NEAR(moved.zones[0].polygons[0].outer[0].x, lonlat["features"][0]["geometry"]["coordinates"][0][0][0].get<double>(), 1e-6);
  EXPECT_NEAR(box_of(moved.zones[0]).width(), 600, 1e-3);
}

TEST(Gis, ASketchWiderThanOneMapHoldsIsRefusedNamingTheStrayFeature) {
  const fs::path dir = testing_util::temp_dir("gis-stray");
  // The village with node 14, the primary road's last, moved to longitude -170.
  std::string village = cli_util::read(kVillage);
  const std::string node = R"(<node id="14" version="1" lat="48.0000000" lon="10.0088705"/>)";
  ASSERT_NE(village.find(node), std::string::npos);
  village.replace(village.find(node), node.size(), R"(<node id="14" version="1" lat="48.0000000" lon="-170.0000000"/>)");
  write(dir / "stray.osm", village);
  const std::string osm = error_of(dir / "stray.osm");
  EXPECT_EQ(osm.rfind((dir / "stray.osm").string() + ": the sketch spans longitude", 0), 0u) << osm;
  EXPECT_NE(osm.find("stray.osm way 100 lies farthest from the rest, at longitude -170.00000, latitude 48.00000"),
            std::string::npos) << osm;
  // A GeoJSON in CRS84 with one stray road, and the same without a crs.
  ordered_json town = in_lon_lat(town_in_metres(), 32632, {500000, 5320000});
  town["features"][2]["geometry"]["coordinates"][1] = {-170, 48};
  write(dir / "lonlat.geojson", town.dump());
  town["crs"] = {{"type", "name"}, {"properties", {{"name", "urn:ogc:def:crs:OGC:1.3:CRS84"}}}};
  write(dir / "crs84.geojson", town.dump());
  for (const char* name : {"lonlat.geojson", "crs84.geojson"}) {
    const std::string error = error_of(dir / name);
    EXPECT_NE(error.find("the sketch spans longitude"), std::string::npos) << error;
    EXPECT_NE(error.find((dir / name).string() + " features[2] lies farthest from the rest"), std::string::npos) << error;
  }
  // Through the program: one line, exit 2, nothing written.
  const cli_util::Result run = cli_util::run("generate " + (dir / "stray.osm").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // One UTM zone holds a sketch a few degrees wide; not one of 20 at the equator.
  ordered_json wide = {{"type", "FeatureCollection"},
                       {"features", {{{"type", "Feature"}, {"properties", {{"zone", "park"}}},
                                      {"geometry", {{"type", "Polygon"}, {"coordinates", {{{0.5, 0}, {20.5, 0}, {20.5, 1}, {0.5, 0}}}}}}}}}};
  write(dir / "equator.geojson", wide.dump());
  EXPECT_NE(error_of(dir / "equator.geojson").find("scale is"), std::string::npos) << error_of(dir / "equator.geojson");
}

TEST(Gis, AWidthOutOfRangeNamesTheFileOnce) {
  const fs::path dir = testing_util::temp_dir("gis-width");
  ordered_json town = town_in_metres();
  town["features"][2]["properties"]["width"] = 1000;
  write(dir / "town.geojson", town.dump());
  translate(dir / "town.geojson", dir / "town.gpkg", "GPKG");
  EXPECT_EQ(error_of(dir / "town.gpkg"),
            (dir / "town.gpkg").string() + " layer town feature 3: width: value 1000.0 is out of range; use a value from 0.5 to 500.0");
}

namespace {

// A closed way added to the village: its ring of (x, y) in metres east and north of the
// village's south-west corner (at its own scale) and its tags; its id.
using AddWay = std::function<long(std::vector<std::pair<double, double>>, const std::map<std::string, std::string>&)>;

std::vector<std::pair<double, double>> box(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// The village with the closed ways `add` adds (ids from 5000) and the relations it writes.
std::string village_with(const std::function<void(const AddWay&, std::ostream& relations)>& add) {
  std::ostringstream osm;
  osm << std::setprecision(10);
  long node = 5000, way = 5000;
  auto at = [](double x, double y) {
    return std::pair{10 + x * 0.0026880 / 200, 48 + y * 0.0017986 / 200};
  };
  auto ring = [&](std::vector<std::pair<double, double>> points) {
    std::vector<long> ids;
    for (auto [x, y] : points) {
      const auto [lon, lat] = at(x, y);
      osm << "  <node id=\"" << node << "\" version=\"1\" lat=\"" << lat << "\" lon=\"" << lon << "\"/>\n";
      ids.push_back(node++);
    }
    ids.push_back(ids.front());
    return ids;
  };
  std::ostringstream ways, relations;
  const AddWay building = [&](std::vector<std::pair<double, double>> points, const std::map<std::string, std::string>& tags) {
    const std::vector<long> ids = ring(std::move(points));
    ways << "  <way id=\"" << way++ << "\" version=\"1\">\n";
    for (long id : ids) ways << "    <nd ref=\"" << id << "\"/>\n";
    for (const auto& [k, v] : tags) ways << "    <tag k=\"" << k << "\" v=\"" << v << "\"/>\n";
    ways << "  </way>\n";
    return way - 1;
  };
  add(building, relations);
  osm << ways.str() << relations.str();
  std::string village = cli_util::read(kVillage);
  // Nodes before the village's ways, ways and the relation after its own.
  const std::string added = osm.str();
  const std::size_t ways_at = added.find("  <way ");
  village.insert(village.rfind("</osm>"), added.substr(ways_at));
  village.insert(village.find("  <way "), added.substr(0, ways_at));
  return village;
}

// The village with buildings mapped in its residential land use: a house with a height,
// its terraced neighbour with levels, a gabled house, one untagged, one with a skillion
// roof, a courtyard block (a multipolygon relation), a pavilion in the park, a house with a
// spike and a bow tie (repaired), one overlapping the first house and one across a street
// (refused: half of each or more stands on what was there before it).
std::string village_with_buildings() {
  return village_with([](const AddWay& building, std::ostream& relations) {
    building(box(90, 50, 102, 60), {{"building", "house"}, {"height", "9"}});                 // 5000
    building(box(102, 50, 114, 60), {{"building", "yes"}, {"building:levels", "3"}});         // 5001
    building(box(60, 120, 72, 130), {{"building", "house"}, {"building:levels", "2"}, {"roof:shape", "gabled"},
                                     {"roof:height", "3"}});                                    // 5002
    building(box(30, 150, 42, 160), {{"building", "yes"}});                                    // 5003
    building(box(150, 40, 160, 50), {{"building", "shed"}, {"roof:shape", "skillion"}, {"height", "4"}});  // 5004
    const long outer = building(box(120, 120, 160, 160), {}), inner = building(box(130, 130, 150, 150), {});  // 5005, 5006
    building(box(90, 290, 100, 300), {{"building", "pavilion"}, {"height", "5 m"}});          // 5007
    building({{30, 60}, {42, 60}, {42, 70}, {36, 70}, {36, 74}, {36, 70}, {30, 70}}, {{"building", "yes"}});  // 5008
    building({{60, 40}, {70, 50}, {70, 40}, {60, 50}}, {{"building", "yes"}});                 // 5009
    building(box(95, 55, 105, 65), {{"building", "yes"}});                                     // 5010
    building(box(195, 150, 205, 160), {{"building", "yes"}});                                  // 5011
    relations << "  <relation id=\"5900\" version=\"1\">\n    <member type=\"way\" ref=\"" << outer
              << "\" role=\"outer\"/>\n    <member type=\"way\" ref=\"" << inner
              << "\" role=\"inner\"/>\n    <tag k=\"type\" v=\"multipolygon\"/>\n    <tag k=\"building\" v=\"apartments\"/>\n"
                 "    <tag k=\"height\" v=\"15\"/>\n  </relation>\n";
  });
}

// The city of the village extract `osm`, with the example's settings, in dir/out.
GenerateResult generate_village(const fs::path& dir, const std::string& osm) {
  write(dir / "village.osm", osm);
  fs::copy_file(cli_util::kSource / "examples" / "osm" / "village.exacity.json", dir / "village.exacity.json");
  GenerateResult result = generate(dir / "village.osm", dir / "out");
  EXPECT_TRUE(result.valid) << result.report["validation"].dump();
  return result;
}

// A building layer's footprints by OSM id, rings as written.
std::map<std::string, std::vector<ordered_json>> mapped_by_osm_id(const ordered_json& buildings) {
  std::map<std::string, std::vector<ordered_json>> out;
  for (const ordered_json& f : buildings["features"])
    if (f["properties"].value("mapped", false)) out[f["properties"]["osm_id"].get<std::string>()].push_back(f);
  return out;
}

}  // namespace

TEST(Gis, MappedBuildingsAreKeptRaisedAndNeverBuiltOver) {
  const fs::path dir = testing_util::temp_dir("gis-mapped"), out = dir / "out";
  const GenerateResult result = generate_village(dir, village_with_buildings());
  const ordered_json& report = result.report["mapped_buildings"];
  EXPECT_EQ(report["in_sketch"], 11) << report.dump(1);
  EXPECT_EQ(report["kept"], 7) << report.dump(1);
  EXPECT_EQ(report["repaired"], 2) << report.dump(1);
  EXPECT_EQ(report["repairs"], ordered_json::parse(R"({"self-intersecting footprint made valid by GEOS's MakeValid": 1,
      "self-intersecting footprint made valid by GEOS's MakeValid, in pieces": 1})")) << report.dump(1);
  EXPECT_EQ(report["refused_why"], ordered_json::parse(R"({"crosses a road surface": 1,
      "overlaps a mapped building kept before it": 1})")) << report.dump(1);
  EXPECT_EQ(report["heights_from"], ordered_json::parse(R"({"building:levels": 2, "height": 4, "zone": 3})"));
  EXPECT_EQ(report["roofs_made_flat"], ordered_json::parse(R"({"skillion: not a shape Exacity builds": 1})"));
  EXPECT_GT(report["lots_not_built_again"].get<int>(), 0);
  EXPECT_GT(report["generated"].get<int>(), 20);

  const ordered_json buildings = ordered_json::parse(cli_util::read(out / "vector" / "buildings.geojson"));
  const auto mapped = mapped_by_osm_id(buildings);
  std::set<std::string> ids;
  for (const auto& [id, features] : mapped) ids.insert(id);
  EXPECT_EQ(ids, (std::set<std::string>{"way/5000", "way/5001", "way/5002", "way/5003", "way/5004", "relation/5900",
                                        "way/5007", "way/5008", "way/5009"}));
  // The bow tie as GEOS's MakeValid leaves it, and as QGIS's "Fix geometries" would: its two
  // triangles, one building as high in each.
  ASSERT_EQ(mapped.at("way/5009").size(), 2u);
  EXPECT_EQ(mapped.at("way/5009")[0]["properties"]["height"], mapped.at("way/5009")[1]["properties"]["height"]);
  auto height = [&](const char* id) { return mapped.at(id)[0]["properties"]["height"].get<double>(); };
  EXPECT_EQ(height("way/5000"), 9);
  EXPECT_EQ(height("way/5001"), 9);   // 3 levels of the zone's 3 m
  EXPECT_EQ(height("way/5002"), 9);   // 2 levels and a roof of 3 m
  EXPECT_EQ(height("way/5004"), 4);
  EXPECT_EQ(height("way/5007"), 5);
  EXPECT_EQ(height("relation/5900"), 15);
  EXPECT_EQ(mapped.at("way/5002")[0]["properties"]["roof"], "gabled");
  EXPECT_EQ(mapped.at("way/5004")[0]["properties"]["roof"], "flat");
  EXPECT_EQ(mapped.at("way/5000")[0]["properties"]["building"], "house");
  EXPECT_EQ(mapped.at("relation/5900")[0]["geometry"]["coordinates"].size(), 2u);  // its courtyard
  EXPECT_TRUE(mapped.at("way/5007")[0]["properties"]["lot"].is_null());             // in the park

  // Footprints as the sketch has them, vertex for vertex (turned counter-clockwise).
  const ordered_json sketch = ordered_json::parse(cli_util::read(out / "sketch.geojson"));
  int compared = 0;
  for (const ordered_json& f : sketch["features"]) {
    if (!f["properties"].contains("building") || f["properties"]["osm_id"] != "way/5000") continue;
    std::set<std::pair<double, double>> drawn, written;
    for (const ordered_json& p : f["geometry"]["coordinates"][0][0]) drawn.insert(std::pair{p[0].get<double>(), p[1].get<double>()});
    for (const ordered_json& p : mapped.at("way/5000")[0]["geometry"]["coordinates"][0])
      written.insert(std::pair{p[0].get<double>(), p[1].get<double>()});
    EXPECT_EQ(drawn, written);
    ++compared;
  }
  EXPECT_EQ(compared, 1);

  // No generated structure overlaps a mapped footprint, nor stands on a lot one holds.
  std::vector<geom::Polygon> kept;
  std::set<int> held;
  auto polygon = [](const ordered_json& rings) {
    geom::Polygon p;
    for (std::size_t r = 0; r < rings.size(); ++r) {
      geom::Ring ring;
      for (std::size_t i = 0; i + 1 < rings[r].size(); ++i)
        ring.push_back(geom::Vec2{rings[r][i][0].get<double>(), rings[r][i][1].get<double>()});
      (r ? p.holes.emplace_back() : p.outer) = ring;
    }
    return p;
  };
  for (const auto& [id, features] : mapped)
    for (const ordered_json& f : features) {
      kept.push_back(polygon(f["geometry"]["coordinates"]));
      if (f["properties"]["lot"].is_number_integer()) held.insert(f["properties"]["lot"].get<int>());
    }
  int generated = 0;
  for (const ordered_json& f : buildings["features"]) {
    if (f["properties"].value("mapped", false)) continue;
    ++generated;
    EXPECT_EQ(held.count(f["properties"]["lot"].get<int>()), 0u) << f["properties"].dump();
    const geom::Polygon p = polygon(f["geometry"]["coordinates"]);
    for (const geom::Polygon& m : kept) EXPECT_FALSE(geom::interiors_overlap(p, m)) << f["properties"].dump();
  }
  EXPECT_GT(generated, 20);

  // The same attributes in CityJSON and city.osm.
  const ordered_json cityjson = ordered_json::parse(cli_util::read(out / "city.city.json"));
  std::set<std::string> in_cityjson;
  for (const auto& [key, object] : cityjson["CityObjects"].items())
    if (object.contains("attributes") && object["attributes"].value("mapped", false))
      in_cityjson.insert(object["attributes"]["osm_id"].get<std::string>());
  EXPECT_EQ(in_cityjson, ids);
  const std::string city_osm = cli_util::read(out / "city.osm");
  EXPECT_NE(city_osm.find("<tag k=\"exacity:osm_id\" v=\"relation/5900\"/>"), std::string::npos);
  EXPECT_NE(city_osm.find("<tag k=\"building\" v=\"pavilion\"/>"), std::string::npos);
  // The building with a courtyard as OSM maps one: a multipolygon relation of an outer and
  // an inner way, closed, which osmium assembles into its area with one hole.
  struct Relations : osmium::handler::Handler {
    std::vector<std::pair<std::map<std::string, std::string>, std::vector<std::string>>> found;
    void relation(const osmium::Relation& r) {
      auto& [tags, roles] = found.emplace_back();
      for (const osmium::Tag& t : r.tags()) tags[t.key()] = t.value();
      for (const osmium::RelationMember& m : r.members()) roles.push_back(m.role());
    }
  } relations;
  osmium::io::Reader reader{(out / "city.osm").string()};
  osmium::apply(reader, relations);
  reader.close();
  ASSERT_EQ(relations.found.size(), 1u);
  EXPECT_EQ(relations.found[0].first.at("type"), "multipolygon");
  EXPECT_EQ(relations.found[0].first.at("exacity:osm_id"), "relation/5900");
  EXPECT_EQ(relations.found[0].second, (std::vector<std::string>{"outer", "inner"}));
  const ordered_json read_back = osm_sketch_document(out / "city.osm");
  int courtyards = 0;
  for (const ordered_json& f : read_back["features"])
    if (f["properties"].contains("building"))
      for (const ordered_json& polygon : f["geometry"]["coordinates"]) courtyards += static_cast<int>(polygon.size()) - 1;
  EXPECT_EQ(courtyards, 1);
}

// OSM's Simple 3D Buildings: a building's outline is its footprint in the map and the
// layers, and its building:parts are its 3D, each from its min_height (or min_level) to its
// height under its own roof: BuildingParts in CityJSON, closed prisms in city.glb,
// building:part ways in city.osm. A part in no kept building is refused, and counted.
TEST(Gis, BuildingPartsAreTheThreeDOfTheirBuildingWhoseOutlineStaysTheFootprint) {
  const fs::path dir = testing_util::temp_dir("gis-parts"), out = dir / "out";
  const GenerateResult result = generate_village(dir, village_with([](const AddWay& way, std::ostream& relations) {
          way(box(90, 50, 114, 60), {{"building", "yes"}, {"building:levels", "2"}});                // 5000
          way(box(90, 50, 102, 60), {{"building:part", "yes"}, {"height", "12"}, {"roof:shape", "hipped"},
                                     {"roof:height", "3"}});                                          // 5001
          way(box(102, 50, 114, 60), {{"building:part", "yes"}, {"min_height", "4"}, {"building:levels", "3"}});  // 5002
          way(box(30, 150, 42, 160), {{"building:part", "yes"}});                                     // 5003, in no building
          way(box(60, 120, 80, 136), {{"building", "school"}});                                       // 5004
          const long outer = way(box(60, 120, 80, 136), {}), inner = way(box(66, 126, 74, 130), {});  // 5005, 5006
          relations << "  <relation id=\"5900\" version=\"1\">\n    <member type=\"way\" ref=\"" << outer
                    << "\" role=\"outer\"/>\n    <member type=\"way\" ref=\"" << inner
                    << "\" role=\"inner\"/>\n    <tag k=\"type\" v=\"multipolygon\"/>\n"
                       "    <tag k=\"building:part\" v=\"classroom\"/>\n    <tag k=\"building:min_level\" v=\"1\"/>\n"
                       "    <tag k=\"height\" v=\"6\"/>\n  </relation>\n";
        }));
  const ordered_json& report = result.report["mapped_buildings"];
  EXPECT_EQ(report["kept"], 2) << report.dump(1);
  EXPECT_EQ(report["refused"], 0) << report.dump(1);
  EXPECT_EQ(report["building_parts"], ordered_json::parse(R"({"in_sketch": 4, "kept": 3, "refused": 1,
      "refused_why": {"building:part in no kept building": 1}, "roofs": {"flat": 2, "hipped": 1}})")) << report.dump(1);

  // The outlines are the footprints, as mapped; the building as tall as its tallest part.
  const auto mapped = mapped_by_osm_id(ordered_json::parse(cli_util::read(out / "vector" / "buildings.geojson")));
  ASSERT_EQ(mapped.size(), 2u);
  EXPECT_EQ(mapped.at("way/5000")[0]["properties"]["height"], 12);
  EXPECT_EQ(mapped.at("way/5004")[0]["properties"]["height"], 6);
  EXPECT_EQ(mapped.at("way/5000")[0]["geometry"]["coordinates"][0].size(), 5u);

  // CityJSON: each building's parts are its BuildingParts, each its own prism between its
  // bottom and its top (millimetres; the village is flat, at 0).
  const ordered_json cityjson = ordered_json::parse(cli_util::read(out / "city.city.json"));
  std::map<std::string, std::pair<double, double>> part_heights;  // by osm_id: lowest and highest vertex
  std::map<std::string, std::size_t> children;
  for (const auto& [key, object] : cityjson["CityObjects"].items()) {
    if (object["type"] == "Building" && object["attributes"].value("mapped", false))
      children[object["attributes"]["osm_id"].get<std::string>()] = object.value("children", ordered_json::array()).size();
    if (object["type"] != "BuildingPart") continue;
    EXPECT_TRUE(cityjson["CityObjects"].contains(object["parents"][0].get<std::string>()));
    double low = INFINITY, high = -INFINITY;
    std::function<void(const ordered_json&)> visit = [&](const ordered_json& b) {
      if (b.is_number()) {
        const double z = cityjson["vertices"][b.get<int>()][2].get<double>() * 0.001;
        low = std::min(low, z), high = std::max(high, z);
      } else {
        for (const ordered_json& x : b) visit(x);
      }
    };
    for (const ordered_json& g : object["geometry"]) visit(g["boundaries"]);
    part_heights[object["attributes"]["osm_id"].get<std::string>()] = {low, high};
  }
  EXPECT_EQ(children, (std::map<std::string, std::size_t>{{"way/5000", 2}, {"way/5004", 1}}));
  EXPECT_EQ(part_heights, (std::map<std::string, std::pair<double, double>>{
                              {"way/5001", {0, 12}}, {"way/5002", {4, 9}}, {"relation/5900", {3, 6}}}));
  const fs::path schemas = cli_util::cityjson_schemas();
  const cli_util::Result cityjson_check =
      cli_util::shell(cli_util::node_tool("check_cityjson.mjs") + " " + (out / "city.city.json").string() +
                      (fs::exists(schemas / "cityjson.schema.json") ? " " + schemas.string() : ""));
  EXPECT_EQ(cityjson_check.code, 0) << cityjson_check.out;
  const cli_util::Result glb_check = cli_util::shell(cli_util::node_tool("check_glb.mjs") + " " + (out / "city.glb").string());
  EXPECT_EQ(glb_check.code, 0) << glb_check.out;
  // As CityJSONSeq, each building with its parts is one feature; the document is as without it.
  const cli_util::Result seq = cli_util::run("generate " + (dir / "village.osm").string() + " -q --cityjson-seq -o " +
                                             (dir / "seq").string());
  ASSERT_EQ(seq.code, 0) << seq.out;
  EXPECT_TRUE(cli_util::read(dir / "seq" / "city.city.json") == cli_util::read(out / "city.city.json"));
  cityjson_seq::expect_same_city_objects(out / "city.city.json", dir / "seq" / "city.city.jsonl");

  // city.osm: the outline and its parts as OSM maps them; read back, the parts are parts again.
  const ordered_json read_back = osm_sketch_document(out / "city.osm");
  std::multiset<std::string> parts;  // each as "way HEIGHT/MIN_HEIGHT"
  for (const ordered_json& f : read_back["features"])
    if (f["properties"].contains("building:part")) {
      const std::string id = f["properties"]["osm_id"];
      parts.insert(id.substr(0, id.find('/')) + " " + f["properties"].value("height", "") + "/" +
                   f["properties"].value("min_height", ""));
    }
  EXPECT_EQ(parts, (std::multiset<std::string>{"way 12/", "way 9/4", "relation 6/3"}));
}

// A mapped building is what stands there: a street whose width only its class gives (8 m
// for a residential street) and which reaches over a house mapped 3.8 m from its centre line
// narrows to clear it, down to the two lanes it must keep (7 m), and says so; a house on
// those lanes is still refused.
TEST(Gis, AStreetGivesWayToAMappedBuildingBesideItDownToItsCarriageway) {
  const fs::path dir = testing_util::temp_dir("gis-give-way");
  const GenerateResult result = generate_village(dir, village_with([](const AddWay& way, std::ostream&) {
    way(box(250, 203.8, 262, 213.8), {{"building", "house"}});  // 5000, beside Mittelweg (y = 200)
    way(box(300, 198, 310, 208), {{"building", "house"}});      // 5001, on it
  }));
  const ordered_json& report = result.report["mapped_buildings"];
  EXPECT_EQ(report["kept"], 1) << report.dump(1);
  EXPECT_EQ(report["refused_why"], ordered_json::parse(R"({"crosses a road surface": 1})")) << report.dump(1);
  EXPECT_EQ(report["roads_narrowed"], 1) << report.dump(1);
  EXPECT_EQ(result.report["sketch_roads"]["narrowed_for_mapped_buildings"], 1);  // repaired, among the roads taken
  ASSERT_EQ(report["roads_narrowed_named"].size(), 1u) << report.dump(1);
  const std::string narrowed = report["roads_narrowed_named"][0];
  EXPECT_EQ(narrowed.substr(0, narrowed.find(" to ")), "way/105: 8 m wide") << narrowed;
  EXPECT_EQ(narrowed.substr(narrowed.find(" m, ")), " m, sidewalks 0 | 0 m to 0 | 0 m, for way/5000") << narrowed;
  const double width = std::stod(narrowed.substr(narrowed.find(" to ") + 4));
  EXPECT_GE(width, 7.0) << narrowed;
  EXPECT_LT(width, 7.6) << narrowed;
  const auto mapped = mapped_by_osm_id(ordered_json::parse(cli_util::read(dir / "out" / "vector" / "buildings.geojson")));
  EXPECT_EQ(mapped.count("way/5000"), 1u);
}

// A mapped building is what stands there and a road's surface partly a guess: a building a
// road runs through (a passage, or a street drawn a little wide) is cut back from the road
// surface, and one mapped over its neighbour's wall from that neighbour, where at least half
// of it stands clear; its pieces are one building. A building mostly on the road is refused.
TEST(Gis, AMappedBuildingOverARoadOrItsNeighbourIsCutBackWhereMostOfItStandsClear) {
  const fs::path dir = testing_util::temp_dir("gis-cut-back");
  const GenerateResult result = generate_village(dir, village_with([](const AddWay& way, std::ostream&) {
    way(box(300, 185, 312, 225), {{"building", "yes"}});    // 5000, across Mittelweg (y = 200, 8 m wide)
    way(box(250, 210, 262, 222), {{"building", "house"}});  // 5001
    way(box(258, 215, 270, 227), {{"building", "house"}});  // 5002, over a corner of 5001
    way(box(400, 197, 412, 210), {{"building", "yes"}});    // 5003, more than half on Mittelweg
  }));
  const ordered_json& report = result.report["mapped_buildings"];
  EXPECT_EQ(report["kept"], 1) << report.dump(1);
  EXPECT_EQ(report["repaired"], 2) << report.dump(1);
  EXPECT_EQ(report["repairs"], ordered_json::parse(R"({"cut back from a mapped building kept before it": 1,
      "cut back from a road surface": 1})")) << report.dump(1);
  EXPECT_EQ(report["refused_why"], ordered_json::parse(R"({"crosses a road surface": 1})")) << report.dump(1);
  const std::string refusal = (dir / "village.osm").string() + " way 5003: refused, crosses a road surface: ";
  EXPECT_TRUE(std::any_of(report["named"].begin(), report["named"].end(), [&](const ordered_json& n) {
    return n.get<std::string>().rfind(refusal, 0) == 0 && n.get<std::string>().find("under half") != std::string::npos;
  })) << report.dump(1);

  const auto mapped = mapped_by_osm_id(ordered_json::parse(cli_util::read(dir / "out" / "vector" / "buildings.geojson")));
  auto area = [&](const char* id) {
    double sum = 0;
    for (const ordered_json& f : mapped.at(id)) {
      geom::Ring ring;
      for (const auto& p : f["geometry"]["coordinates"][0]) ring.push_back({p[0].get<double>(), p[1].get<double>()});
      sum += std::abs(geom::signed_area(ring));
    }
    return sum;
  };
  // 5000 on both sides of the carriageway (11 m and 21 m of its 40), each piece as high.
  ASSERT_EQ(mapped.at("way/5000").size(), 2u);
  EXPECT_EQ(mapped.at("way/5000")[0]["properties"]["height"], mapped.at("way/5000")[1]["properties"]["height"]);
  EXPECT_NEAR(area("way/5000"), 32 * 12, 2);
  // 5001 as mapped; 5002 less the 4 x 7 m of 5001 it covered.
  EXPECT_NEAR(area("way/5001"), 144, 0.5);
  ASSERT_EQ(mapped.at("way/5002").size(), 1u);
  EXPECT_NEAR(area("way/5002"), 144 - 28, 0.5);
  EXPECT_EQ(mapped.count("way/5003"), 0u);
}

// A GIS export of OpenStreetMap's buildings (GDAL's OSM driver's columns): each polygon a
// mapped building with its OSM id as a type and number and its tags from other_tags.
TEST(Gis, BuildingsOfAGisExportAreMappedBuildings) {
  const fs::path dir = testing_util::temp_dir("gis-export-buildings");
  ordered_json town = town_in_metres();
  auto square = [](double x, double y) {
    return ordered_json{{"type", "Polygon"},
                        {"coordinates", {{{x, y}, {x + 10, y}, {x + 10, y + 10}, {x, y + 10}, {x, y}}}}};
  };
  town["features"].push_back({{"type", "Feature"},
                              {"properties", {{"osm_id", nullptr}, {"osm_way_id", "4198"}, {"building", "yes"},
                                              {"other_tags", "\"building:levels\"=>\"6\",\"roof:shape\"=>\"hipped\""}}},
                              {"geometry", square(385300, 6672200)}});
  town["features"].push_back({{"type", "Feature"},
                              {"properties", {{"osm_id", "77"}, {"osm_way_id", nullptr}, {"building", "church"}, {"height", 30}}},
                              {"geometry", square(385400, 6672200)}});
  write(dir / "town.geojson", town.dump());
  const Sketch sketch = load_sketch(dir / "town.geojson");
  ASSERT_EQ(sketch.buildings.size(), 2u);
  EXPECT_EQ(sketch.buildings[0].osm_id, "way/4198");
  EXPECT_EQ(sketch.buildings[0].levels, 6);
  EXPECT_EQ(sketch.buildings[0].roof_shape, "hipped");
  EXPECT_EQ(sketch.buildings[1].osm_id, "relation/77");
  EXPECT_EQ(sketch.buildings[1].building, "church");
  EXPECT_EQ(sketch.buildings[1].height, 30);
  EXPECT_EQ(sketch.zones.size(), 2u);
  EXPECT_EQ(sketch.roads.size(), 1u);
}

namespace {

// A footprint at (x, y) in the town's UTM metres, 20 x 15 m, with its fields.
ordered_json footprint(double x, double y, const ordered_json& fields) {
  return {{"type", "Feature"}, {"properties", fields},
          {"geometry", {{"type", "Polygon"}, {"coordinates", {{{x, y}, {x + 20, y}, {x + 20, y + 15}, {x, y + 15}, {x, y}}}}}}};
}

}  // namespace

// A layer of footprints with no zone, road or OSM tag, given beside the sketch with
// --buildings, in another format: each polygon a mapped building raised from the fields a
// GIS file names heights by; a feature that is no polygon and a building BAG says was
// demolished are counted and named as refused.
TEST(Gis, AFootprintLayerGivenWithBuildingsIsKeptAsMappedBuildings) {
  const fs::path dir = testing_util::temp_dir("gis-footprints");
  ordered_json sketch = town_in_metres();
  sketch["exacity"] = ordered_json::parse(R"({"seed": 3, "zones": {"residential": {"layout": "streets"}}})");
  write(dir / "town.geojson", sketch.dump());
  ordered_json layer = {{"type", "FeatureCollection"}, {"crs", sketch["crs"]}, {"features", ordered_json::array()}};
  layer["features"].push_back(footprint(385300, 6672200, {{"building", "office"}, {"height", 12.5},
                                                          {"identificatie", "NL.IMBAG.Pand.0503100000030264"}}));
  layer["features"].push_back(footprint(385340, 6672200, {{"building", "house"}, {"bouwlagen", 3}}));
  layer["features"].push_back(footprint(385380, 6672200, {{"building", "school"}, {"b3_h_dak_70p", 20.5}, {"b3_h_maaiveld", 0.5}}));
  layer["features"].push_back(footprint(385420, 6672200, ordered_json::object()));
  layer["features"].push_back(footprint(385460, 6672200, {{"status", "Pand gesloopt"}}));
  layer["features"].push_back({{"type", "Feature"}, {"properties", ordered_json::object()},
                               {"geometry", {{"type", "LineString"}, {"coordinates", {{385300, 6672250}, {385320, 6672250}}}}}});
  write(dir / "footprints.geojson", layer.dump());
  translate(dir / "footprints.geojson", dir / "footprints.gpkg", "GPKG");

  const fs::path out = dir / "out";
  const cli_util::Result run = cli_util::run("generate -q " + (dir / "town.geojson").string() + " --buildings " +
                                             (dir / "footprints.gpkg").string() + " --vector-format gpkg -o " + out.string());
  ASSERT_EQ(run.code, 0) << run.out;
  const ordered_json report = ordered_json::parse(cli_util::read(out / "report.json"))["mapped_buildings"];
  EXPECT_EQ(report["kept"], 4) << report.dump(1);
  EXPECT_EQ(report["refused_why"], ordered_json::parse(R"x({"buildings not standing (BAG's status Pand gesloopt)": 1,
      "buildings that are not polygons": 1})x")) << report.dump(1);
  EXPECT_EQ(report["heights_from"], ordered_json::parse(R"({"building:levels": 1, "height": 2, "zone": 1})")) << report.dump(1);
  EXPECT_NE(run.out.find((dir / "footprints.gpkg").string() + ": left out 2 buildings"), std::string::npos) << run.out;
  const std::string feature = (dir / "footprints.gpkg").string() + " layer footprints feature ";
  EXPECT_EQ(report["named"], ordered_json({feature + "5: refused, buildings not standing (BAG's status Pand gesloopt)",
                                           feature + "6: refused, buildings that are not polygons"}))
      << report.dump(1);

  // Each kept as drawn, raised from its own field.
  std::map<std::string, ordered_json> by_tag;
  const ordered_json buildings = ordered_json::parse(cli_util::read(out / "vector" / "buildings.geojson"));
  for (const ordered_json& f : buildings["features"])
    if (f["properties"].value("mapped", false)) by_tag[f["properties"]["building"].get<std::string>()] = f;
  ASSERT_EQ(by_tag.size(), 4u);
  EXPECT_EQ(by_tag["office"]["properties"]["height"], 12.5);
  EXPECT_EQ(by_tag["house"]["properties"]["height"], 9);  // 3 storeys of the zone's 3 m
  EXPECT_EQ(by_tag["school"]["properties"]["height"], 20);
  std::set<std::pair<double, double>> written;
  for (const ordered_json& p : by_tag["office"]["geometry"]["coordinates"][0]) written.insert({p[0].get<double>(), p[1].get<double>()});
  EXPECT_EQ(written, (std::set<std::pair<double, double>>{{385300, 6672200}, {385320, 6672200}, {385320, 6672215}, {385300, 6672215}}));
  // Each keeps its identifier: BAG's identificatie, else its FID in the layer (the
  // GeoPackage's count from 1), in every export; in city.osm BAG's as OSM's ref:bag.
  EXPECT_EQ(by_tag["office"]["properties"]["identificatie"], "NL.IMBAG.Pand.0503100000030264");
  EXPECT_FALSE(by_tag["office"]["properties"].contains("fid"));
  EXPECT_EQ(by_tag["house"]["properties"]["fid"], "2");
  const ordered_json cityjson = ordered_json::parse(cli_util::read(out / "city.city.json"));
  std::set<std::string> ids_in_cityjson;
  for (const auto& [key, object] : cityjson["CityObjects"].items())
    for (const char* id : {"identificatie", "fid"})
      if (object.contains("attributes") && object["attributes"].contains(id))
        ids_in_cityjson.insert(id + std::string("=") + object["attributes"][id].get<std::string>());
  EXPECT_EQ(ids_in_cityjson, (std::set<std::string>{"identificatie=NL.IMBAG.Pand.0503100000030264", "fid=2", "fid=3", "fid=4"}));
  // The GeoPackage too, whose key column is named apart from the buildings' "fid" field
  // (GDAL refused the field: "Wrong field type for fid").
  GDALDatasetUniquePtr gpkg(GDALDataset::Open((out / "city.gpkg").string().c_str(), GDAL_OF_VECTOR));
  ASSERT_TRUE(gpkg);
  OGRLayer* gpkg_buildings = gpkg->GetLayerByName("buildings");
  ASSERT_NE(gpkg_buildings, nullptr);
  std::set<std::string> fids_in_gpkg;
  for (const auto& f : *gpkg_buildings)
    if (f->IsFieldSetAndNotNull(f->GetFieldIndex("fid"))) fids_in_gpkg.insert(f->GetFieldAsString("fid"));
  EXPECT_EQ(fids_in_gpkg, (std::set<std::string>{"2", "3", "4"}));
  const std::string city_osm = cli_util::read(out / "city.osm");
  EXPECT_NE(city_osm.find("<tag k=\"ref:bag\" v=\"503100000030264\"/>"), std::string::npos);
  EXPECT_NE(city_osm.find("<tag k=\"exacity:fid\" v=\"2\"/>"), std::string::npos);

  // A layer of points is no footprints: one line, exit 2, nothing written.
  write(dir / "points.geojson", R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
      "geometry": {"type": "Point", "coordinates": [385300, 6672200]}}]})");
  const cli_util::Result points = cli_util::run("generate -q " + (dir / "town.geojson").string() + " --buildings " +
                                                (dir / "points.geojson").string() + " -o " + (dir / "none").string());
  EXPECT_EQ(points.code, 2) << points.out;
  EXPECT_EQ(points.out, "exacity: error: " + (dir / "points.geojson").string() +
                            " layer points: holds points, not building footprints; give --buildings a file of polygons, "
                            "or draw the footprints\n");
  EXPECT_FALSE(fs::exists(dir / "none"));
}

// docs/outputs.md's list of formats is the formats' table, row by row.
TEST(Formats, TheOutputsPageListsTheFormatsTable) {
  std::istringstream outputs(cli_util::read(cli_util::kSource / "docs" / "outputs.md"));
  std::vector<std::string> rows;
  bool in_table = false;
  for (std::string line; std::getline(outputs, line);) {
    if (line.rfind("| format | files | written |", 0) == 0) in_table = true;
    else if (in_table && line.rfind("| ", 0) == 0) rows.push_back(line);
    else if (in_table && line.rfind("|---", 0) != 0) break;
  }
  ASSERT_EQ(rows.size(), kCityFormats.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const CityFormat& f = kCityFormats[i];
    const std::string when = f.kind == FormatKind::Vector         ? "always"
                             : f.kind == FormatKind::OptionalVector ? std::string("with --vector-format ") + f.name
                                                                    : "in the 3D export";
    EXPECT_EQ(rows[i].rfind(std::string("| ") + f.name + " | OUT/" + f.files + " | " + when, 0), 0u) << rows[i];
  }
  EXPECT_EQ(optional_vector_formats_text(),
            "gpkg (OUT/city.gpkg), fgb (OUT/vector/*.fgb), shp (OUT/vector/shp/) or dxf (OUT/city.dxf)");
}

// A PBF extract saved under an .osm name (as osm2streets' test data is) is read as the PBF it
// holds: the features of the XML extract it was written from, not "not a readable extract".
TEST(Gis, APbfNamedOsmIsReadAsTheExtractItHolds) {
  const fs::path dir = testing_util::temp_dir("pbf_named_osm");
  // osmium-tool (scripts/install-deps.sh) writes it.
  ASSERT_EQ(cli_util::shell("osmium cat " + kVillage.string() + " -f pbf -o " + (dir / "village.osm").string()).code, 0);
  const nlohmann::ordered_json xml = osm_sketch_document(kVillage), pbf = osm_sketch_document(dir / "village.osm");
  ASSERT_GT(xml["features"].size(), 5u);
  ASSERT_EQ(pbf["features"].size(), xml["features"].size());
  for (std::size_t i = 0; i < xml["features"].size(); ++i) {
    EXPECT_EQ(pbf["features"][i]["geometry"], xml["features"][i]["geometry"]) << i;
    EXPECT_EQ(pbf["features"][i]["properties"].value("zone", ""), xml["features"][i]["properties"].value("zone", "")) << i;
    EXPECT_EQ(pbf["features"][i]["properties"].value("road", ""), xml["features"][i]["properties"].value("road", "")) << i;
  }
  const cli_util::Result run = cli_util::run("generate " + (dir / "village.osm").string() + " -q -o " + (dir / "out").string());
  EXPECT_EQ(run.code, 0) << run.out;
}
