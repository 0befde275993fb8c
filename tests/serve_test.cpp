// exacity serve's API through httplib's client, against a server in this process
// (docs/serve.md; docs/design.md, Serving).
#include <OpenImageIO/imageio.h>
#include <gdal_priv.h>
#include <tiny_gltf.h>
#include <ogr_spatialref.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <fstream>
#include <functional>
#include <map>
#include <future>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "generate/cancel.h"
#include "generate/city/palette.h"
#include "generate/city/structure_albedos.h"
#include "generate/sketch/sketch.h"
#include "generate/errors.h"
#include "generate/export/gis_export.h"
#include "generate/pipeline.h"
#include "generate/regenerate.h"
#include "generate/layout/road_settings.h"
#include "generate/parcels/parcel_settings.h"
#include "generate/placement/building_settings.h"
#include "generate/placement/model_library.h"
#include "render/denoise.h"
#include "render/primary_layer.h"
#include "render/render.h"
#include "serve/connections.h"
#include "serve/city_tiles.h"
#include "serve/job_runner.h"
#include "serve/server.h"
#include "tests/cli_util.h"
#include "tests/place_sketch.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using exacity::serve::CityServer;
using exacity::serve::JobRunner;
using exacity::serve::JobState;
using json = nlohmann::json;

namespace {

// Two zones across a highway: a city of a few streets (tests/cli_test.cpp's small sketch).
const std::string kSmallSketch = R"({"type": "FeatureCollection", "exacity": {"seed": 3, "builtin_models": []}, "features": [
  {"type": "Feature", "properties": {"zone": "residential"},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [400, 0], [400, 300], [0, 300], [0, 0]]]}},
  {"type": "Feature", "properties": {"zone": "commercial"},
   "geometry": {"type": "Polygon", "coordinates": [[[400, 0], [600, 0], [600, 300], [400, 300], [400, 0]]]}},
  {"type": "Feature", "properties": {"road": "highway", "width": 16},
   "geometry": {"type": "LineString", "coordinates": [[-50, 150], [650, 150]]}}]}
)";

// The small sketch with `settings` as its "exacity" member.
std::string sketch_with(const std::string& settings) {
  json doc = json::parse(kSmallSketch);
  doc["exacity"] = json::parse(settings);
  return doc.dump();
}

// The message the CLI gives for `text` read from `file`; empty when the sketch is good.
std::string cli_message(const std::string& text, const fs::path& file) {
  try {
    exacity::parse_sketch(text, file);
  } catch (const exacity::UserError& e) {
    return e.what();
  }
  return "";
}

void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A greyscale PNG: a ramp with a pond of value 0 in one corner.
void write_heightmap(const fs::path& file) {
  const int n = 16;
  std::vector<unsigned char> pixels(n * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) pixels[y * n + x] = (x < 4 && y < 4) ? 0 : static_cast<unsigned char>(40 + 10 * x);
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out && out->open(file.string(), OIIO::ImageSpec(n, n, 1, OIIO::TypeDesc::UINT8)));
  out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
  out->close();
}

// The token the in-process servers are given; every request carries it.
const std::string kToken = "test-token-0123456789abcdef";

class ServeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir =
        testing_util::temp_dir(std::string("serve_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    // A page folder with links out of it, and a secret beside it that no URL may reach.
    fs::create_directories(dir / "web" / "lib");
    write(dir / "web" / "index.html", "<!doctype html><title>exacity</title>");
    write(dir / "web" / "lib" / "app.js", "export const ok = 1;");
    write(dir / "secret.txt", "SECRET");
    fs::create_symlink(dir / "secret.txt", dir / "web" / "leak.txt");
    fs::create_symlink(dir, dir / "web" / "up");
    start();
  }
  void start() {
    exacity::serve::ServeOptions o;
    o.work = dir / "work", o.web = dir / "web", o.port = 0, o.max_body = 64 * 1024, o.token = kToken;
    // Short, so the tests of slow clients are: a request on loopback takes milliseconds.
    o.connections.headers = o.connections.body = std::chrono::milliseconds(2000);
    server = std::make_unique<CityServer>(o);
    port = server->bind();
    serving = std::thread([this] { server->run(); });
    client = std::make_unique<httplib::Client>("127.0.0.1", port);
    client->set_read_timeout(60);
    client->set_bearer_token_auth(kToken.c_str());
  }
  void TearDown() override {
    server->stop();
    serving.join();
    server->finish_jobs();
  }
  // A new server on the same work folder, as after the user started it again.
  void restart() {
    TearDown();
    start();
  }

  fs::path work() const { return server->work_folder(); }
  fs::path sketch_file() const { return work() / "sketch.geojson"; }
  // A message as the server gives it: paths in the work folder named from it.
  std::string in_work(std::string message) const {
    const std::string prefix = work().string() + "/";
    for (std::size_t at; (at = message.find(prefix)) != std::string::npos;) message.erase(at, prefix.size());
    return message;
  }

  // Polls the status until no job runs; the last status. Bounded: 20 minutes under the sanitizers.
  json wait_for_job(httplib::Client& c) {
    json status;
    for (int i = 0; i < 12000; ++i) {
      auto r = c.Get("/api/status");
      if (!r) break;
      status = json::parse(r->body);
      if (status["state"] != "running") return status;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    ADD_FAILURE() << "the job did not end: " << status.dump();
    return status;
  }

  void put_small_and_generate() {
    ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
    auto r = client->Post("/api/generate", "", "application/json");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 202) << r->body;
    const json done = wait_for_job(*client);
    ASSERT_EQ(done["state"], "done") << done.dump();
  }

  // report.json of work/city's sketch generated as exacity generate does (the server's
  // leaves out the counts of the 3D files it writes only when they are downloaded).
  json full_build_report() const {
    const fs::path alone = testing_util::temp_dir("full_build");
    exacity::generate_city(exacity::parse_sketch(read(work() / "city" / "sketch.geojson"), sketch_file()), alone,
                           nullptr);
    return json::parse(read(alone / "report.json"));
  }

  // `sketch`'s city generated into `dir` with its GeoPackage, as `exacity generate
  // --vector-format gpkg` writes them.
  void generate_with_gpkg(const std::string& sketch, const fs::path& dir) const {
    const exacity::Sketch parsed = exacity::parse_sketch(sketch, sketch_file());
    exacity::StageClock clock(nullptr, exacity::kCityStages + exacity::kWriteStages);
    exacity::ExportOptions options;
    options.vector_formats = {"gpkg"};
    exacity::write_city(parsed, exacity::build_city(parsed, clock), dir, clock, options);
  }

  // Listens to GET /api/events on a thread of its own, giving `on` each event's name and data
  // until it returns false; returns once the stream has opened.
  std::thread listen(std::function<bool(const std::string&, const json&)> on) {
    auto listening = std::make_shared<std::promise<void>>();
    std::future<void> opened = listening->get_future();
    std::thread t([this, on = std::move(on), listening] {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(600);
      c.set_bearer_token_auth(kToken.c_str());
      std::string buffer;
      bool told = false;
      c.Get("/api/events", [&](const char* data, std::size_t n) {
        buffer.append(data, n);
        for (std::size_t end; (end = buffer.find("\n\n")) != std::string::npos; buffer.erase(0, end + 2)) {
          const std::string event = buffer.substr(0, end);
          if (!told) told = true, listening->set_value();
          const auto name = event.find("event: "), data_at = event.find("data: ");
          if (name == std::string::npos || data_at == std::string::npos) continue;
          if (!on(event.substr(name + 7, event.find('\n', name) - name - 7), json::parse(event.substr(data_at + 6))))
            return false;
        }
        return true;
      });
    });
    opened.wait();
    return t;
  }

  fs::path dir;
  std::unique_ptr<CityServer> server;
  int port = 0;
  std::thread serving;
  std::unique_ptr<httplib::Client> client;
};

TEST_F(ServeTest, SketchRoundTrip) {
  auto empty = client->Get("/api/sketch");
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->status, 200);
  EXPECT_TRUE(json::parse(empty->body)["features"].empty());
  auto put = client->Put("/api/sketch", kSmallSketch, "application/geo+json");
  ASSERT_TRUE(put);
  EXPECT_EQ(put->status, 200) << put->body;
  auto got = client->Get("/api/sketch");
  EXPECT_EQ(got->body, kSmallSketch);
  EXPECT_EQ(read(sketch_file()), kSmallSketch);
}

TEST_F(ServeTest, BadJsonIsRefusedWithTheCliMessage) {
  const std::string bad = "{\"type\": \"FeatureCollection\",\n \"features\": [}";
  auto r = client->Put("/api/sketch", bad, "application/geo+json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(r->body, in_work(cli_message(bad, sketch_file())));
  EXPECT_NE(r->body.find("malformed JSON"), std::string::npos) << r->body;
  EXPECT_FALSE(fs::exists(sketch_file()));
}

TEST_F(ServeTest, BadSketchIsRefusedWithTheCliMessageAndTheOldOneKept) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  for (const std::string& bad :
       {sketch_with(R"({"seed": 3, "zones": {"residential": {"block_area": -5}}})"),
        sketch_with(R"({"seed": 3, "zones": {"residential": {"layout": "spiral"}}})"),
        std::string(R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"zone": "parc"},
          "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}}]})"),
        std::string(R"({"type": "FeatureCollection", "features": []})")}) {
    auto r = client->Put("/api/sketch", bad, "application/geo+json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400);
    const std::string expected = in_work(cli_message(bad, sketch_file()));
    EXPECT_FALSE(expected.empty());
    EXPECT_EQ(r->body, expected);
    EXPECT_EQ(r->body.find('\n'), std::string::npos) << "one line: " << r->body;
  }
  EXPECT_EQ(client->Get("/api/sketch")->body, kSmallSketch);
}

// The page's forms come from the settings the CLI reads: every key a zone type takes, once,
// with the kind, bounds and default its step reads it with, a unit and a description; a
// value the table says is out of range is one the CLI refuses.
TEST_F(ServeTest, SettingsTableIsTheOneTheCliReads) {
  auto r = client->Get("/api/settings");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/json");
  const json zones = json::parse(r->body)["zones"];
  std::set<std::string> keys = exacity::road_setting_keys();
  for (const auto* more : {&exacity::parcel_setting_keys(), &exacity::building_setting_keys()})
    keys.insert(more->begin(), more->end());
  for (const char* zone : {"residential", "commercial", "industrial"}) {
    std::set<std::string> listed;
    for (const json& row : zones[zone]) {
      EXPECT_TRUE(listed.insert(row["key"]).second) << zone << " lists " << row["key"] << " twice";
      EXPECT_FALSE(row["description"].get<std::string>().empty()) << row["key"];
    }
    EXPECT_EQ(listed, keys) << zone;
  }
  const auto row = [&](const char* zone, const char* key) {
    for (const json& r : zones[zone])
      if (r["key"] == key) return r;
    return json();
  };
  EXPECT_EQ(row("residential", "block_area"),
            json::parse(R"({"key": "block_area", "kind": "number", "min": 100, "max": 1e9, "default": 12000,
                            "unit": "m²", "description": "cells above this are grown again, one level deeper"})"));
  EXPECT_EQ(row("commercial", "block_area")["default"], 15000);
  EXPECT_EQ(row("industrial", "lot_width")["default"], json::array({40, 90}));
  EXPECT_EQ(row("industrial", "lot_width")["kind"], "range");
  EXPECT_EQ(row("residential", "layout")["choices"], json::array({"growth", "grammar", "voronoi", "streets"}));
  EXPECT_EQ(row("residential", "grid_passes")["kind"], "whole");
  EXPECT_EQ(row("residential", "nesting")["kind"], "boolean");
  EXPECT_EQ(row("residential", "road_widths")["default"], json::array({12, 8}));
  EXPECT_EQ(row("commercial", "heights")["default"], json::array({12, 48}));
  EXPECT_EQ(row("commercial", "heights")["kind"], "json");
  // Just past the table's bound the CLI refuses, naming the key; at the bound it takes it.
  const json area = row("residential", "block_area");
  for (double v : {area["min"].get<double>(), area["max"].get<double>()})
    EXPECT_EQ(cli_message(sketch_with(R"({"zones": {"residential": {"block_area": )" + json(v).dump() + "}}}"),
                          sketch_file()),
              "");
  const std::string below = cli_message(sketch_with(R"({"zones": {"residential": {"block_area": 99}}})"), sketch_file());
  EXPECT_NE(below.find("\"exacity\".zones.residential.block_area: value 99.0 is out of range"), std::string::npos) << below;
  // A GET the token-less stranger cannot make, as every route.
  httplib::Client stranger("127.0.0.1", port);
  EXPECT_EQ(stranger.Get("/api/settings")->status, 403);
}

// The small sketch moved into UTM zone 33 north (EPSG:32633), around 15 degrees east,
// 49.65 north: x 499650 to 500350, y 5500000 to 5500300.
std::string placed_small_sketch() {
  json doc = json::parse(kSmallSketch);
  doc["crs"] = {{"type", "name"}, {"properties", {{"name", "urn:ogc:def:crs:EPSG::32633"}}}};
  const auto moved = [](json& p) { p = {p[0].get<double>() + 499700, p[1].get<double>() + 5500000}; };
  for (int zone : {0, 1})
    for (json& p : doc["features"][zone]["geometry"]["coordinates"][0]) moved(p);
  for (json& p : doc["features"][2]["geometry"]["coordinates"]) moved(p);
  return doc.dump();
}

// A sketch with a place on Earth gives the page a grid of lon/lat over it for a basemap: on
// UTM zone 33's central meridian (x = 500000) the longitude is 15 degrees exactly; rows go
// north. One with no place on Earth has none.
TEST_F(ServeTest, LonLatGridPlacesTheSketch) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  EXPECT_EQ(json::parse(client->Get("/api/lonlat")->body), json::parse(R"({"epsg": null})"));
  auto put = client->Put("/api/sketch", placed_small_sketch(), "application/geo+json");
  ASSERT_EQ(put->status, 200) << put->body;
  auto r = client->Get("/api/lonlat");
  ASSERT_EQ(r->status, 200) << r->body;
  const json grid = json::parse(r->body);
  EXPECT_EQ(grid["epsg"], 32633);
  ASSERT_EQ(grid["side"], 9);
  ASSERT_EQ(grid["lonlat"].size(), 81u);
  // The features span x 499650 to 500350: the box, grown by 700 each way, is centred on 500000.
  EXPECT_EQ(grid["box"], json::array({499650 - 700, 5500000 - 700, 500350 + 700, 5500300 + 700}));
  for (int row = 0; row < 9; ++row) {
    EXPECT_NEAR(grid["lonlat"][row * 9 + 4][0].get<double>(), 15, 1e-9) << row;
    if (row) {
      EXPECT_GT(grid["lonlat"][row * 9][1].get<double>(), grid["lonlat"][(row - 1) * 9][1].get<double>());
    }
  }
  EXPECT_NEAR(grid["lonlat"][40][1].get<double>(), 49.65, 0.01);  // 5500 km north of the equator
}

// A 200 x 200 GeoTIFF of 10-unit pixels in EPSG `epsg` (0: no CRS, its coordinates the
// sketch's), white but for a red 6-pixel square centred on `mark` (a point in EPSG:32633, or
// in the sketch's coordinates without a CRS) and a pixel's grid corner there.
void write_geotiff(const fs::path& file, int epsg, double mark_x, double mark_y) {
  GDALAllRegister();
  double x = mark_x, y = mark_y;
  OGRSpatialReference srs;
  if (epsg) {
    OGRSpatialReference utm;
    utm.importFromEPSG(32633);
    utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    srs.importFromEPSG(epsg);
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> to(OGRCreateCoordinateTransformation(&utm, &srs));
    ASSERT_TRUE(to && to->Transform(1, &x, &y));
  }
  const int n = 200;
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(file.c_str(), n, n, 3, GDT_Byte, nullptr);
  ASSERT_NE(ds, nullptr);
  double transform[6] = {x - 1000, 10, 0, y + 1000, 0, -10};
  ds->SetGeoTransform(transform);
  if (epsg) ds->SetSpatialRef(&srs);
  for (int band = 1; band <= 3; ++band) {
    std::vector<unsigned char> pixels(n * n, 255);
    if (band > 1)
      for (int row = 97; row < 103; ++row)
        for (int col = 97; col < 103; ++col) pixels[row * n + col] = 0;
    ASSERT_EQ(ds->GetRasterBand(band)->RasterIO(GF_Write, 0, 0, n, n, pixels.data(), n, n, GDT_Byte, 0, 0), CE_None);
  }
  GDALClose(ds);
}

// The red square's centre in a basemap picture served with `extent`, in the sketch's
// coordinates; and its alpha there.
std::pair<geom::Vec2, int> red_mark(const std::string& png, const json& extent, const fs::path& scratch) {
  write(scratch, png);
  auto in = OIIO::ImageInput::open(scratch.string());
  EXPECT_TRUE(in);
  if (!in) return {{}, 0};
  const OIIO::ImageSpec spec = in->spec();
  std::vector<unsigned char> pixels(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data());
  EXPECT_EQ(spec.nchannels, 4);  // RGB and alpha
  double sx = 0, sy = 0, weight = 0;
  int alpha = 0;
  for (int row = 0; row < spec.height; ++row)
    for (int col = 0; col < spec.width; ++col) {
      const unsigned char* p = &pixels[(static_cast<std::size_t>(row) * spec.width + col) * spec.nchannels];
      const double red = p[3] == 255 ? (p[0] - p[1]) / 255.0 : 0;  // white 0, the square's red 1
      if (red <= 0.05) continue;
      sx += red * (col + 0.5), sy += red * (row + 0.5), weight += red;
      alpha = std::max(alpha, int(p[3]));
    }
  EXPECT_GT(weight, 4) << "no red square in the picture";
  const double x0 = extent[0], y0 = extent[1], x1 = extent[2], y1 = extent[3];
  return {{x0 + sx / weight * (x1 - x0) / spec.width, y1 - sy / weight * (y1 - y0) / spec.height}, alpha};
}

// A GeoTIFF below the work folder, in the sketch's CRS, in Web Mercator or in another UTM
// zone, is reprojected into the sketch's CRS by GDAL and drawn where it lies: its red mark
// lands on the point it marks, within a source pixel's half (5 m). Without CRS on both
// sides its coordinates are the sketch's. Names that leave the folder, files that are not
// GeoTIFFs, a CRS on one side only and a GeoTIFF far away are refused with one line.
TEST_F(ServeTest, GeoTiffBasemapIsPlacedInTheSketchsCrs) {
  ASSERT_EQ(client->Put("/api/sketch", placed_small_sketch(), "application/geo+json")->status, 200);
  const geom::Vec2 mark{499900, 5500120};
  for (const int epsg : {32633, 3857, 32634}) {
    const std::string name = "maps/mark_" + std::to_string(epsg) + ".tif";
    fs::create_directories(work() / "maps");
    write_geotiff(work() / name, epsg, mark.x, mark.y);
    auto where = client->Get("/api/basemap?file=" + name);
    ASSERT_EQ(where->status, 200) << where->body;
    const json placed = json::parse(where->body);
    EXPECT_EQ(placed["file"], name);
    EXPECT_EQ(placed["crs"], "EPSG:32633");
    // Cut to the sketch's surroundings: its features' box grown by 700 m each way.
    const json extent = placed["extent"];
    EXPECT_GE(extent[0].get<double>(), 499650 - 700.0);
    EXPECT_LE(extent[2].get<double>(), 500350 + 700.0);
    EXPECT_GE(extent[1].get<double>(), 5500000 - 700.0);
    EXPECT_LE(extent[3].get<double>(), 5500300 + 700.0);
    auto png = client->Get("/api/basemap.png?file=" + name);
    ASSERT_EQ(png->status, 200) << png->body;
    EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
    const auto [at, alpha] = red_mark(png->body, extent, dir / "basemap.png");
    EXPECT_NEAR(at.x, mark.x, 5) << epsg;
    EXPECT_NEAR(at.y, mark.y, 5) << epsg;
    EXPECT_EQ(alpha, 255) << epsg;
  }

  const auto refused = [&](const std::string& query, const std::string& says) {
    auto r = client->Get("/api/basemap?file=" + query);
    ASSERT_TRUE(r) << query;
    EXPECT_EQ(r->status, 400) << query;
    EXPECT_NE(r->body.find(says), std::string::npos) << query << ": " << r->body;
    EXPECT_EQ(r->body.find('\n'), std::string::npos) << r->body;
    EXPECT_EQ(r->body.find(work().string()), std::string::npos) << r->body;
    EXPECT_EQ(client->Get("/api/basemap.png?file=" + query)->status, 400) << query;
  };
  write_geotiff(dir / "outside.tif", 32633, mark.x, mark.y);
  fs::create_symlink(dir / "outside.tif", work() / "maps" / "link.tif");
  refused("../outside.tif", "\"..\" would leave the folder");
  refused("maps/%252e%252e/%252e%252e/outside.tif", "percent-encoded");  // "%2e%2e" once decoded
  refused("maps%2f..%2f..%2foutside.tif", "\"..\" would leave the folder");
  refused(dir.string() + "/outside.tif", "absolute");
  refused("maps/link.tif", "symbolic link");
  refused("maps/.hidden.tif", "hidden");
  refused("maps/none.tif", "no such file in the work folder");
  refused("sketch.geojson", "not a GeoTIFF GDAL reads");
  refused("", "no file named");
  // A VRT names files anywhere: not read, whatever its name.
  write(work() / "maps" / "outside.tif.vrt",
        "<VRTDataset rasterXSize=\"1\" rasterYSize=\"1\"><VRTRasterBand dataType=\"Byte\" band=\"1\"><SimpleSource>"
        "<SourceFilename>" + (dir / "outside.tif").string() + "</SourceFilename></SimpleSource></VRTRasterBand></VRTDataset>");
  refused("maps/outside.tif.vrt", "not a GeoTIFF GDAL reads");
  write_geotiff(work() / "maps" / "plain.tif", 0, mark.x, mark.y);
  refused("maps/plain.tif", "has no CRS while the sketch is in EPSG:32633");
  write_geotiff(work() / "maps" / "far.tif", 32633, mark.x + 50000, mark.y);
  refused("maps/far.tif", "away from the sketch");
  // Only with the token.
  EXPECT_EQ(httplib::Client("127.0.0.1", port).Get("/api/basemap.png?file=maps/mark_3857.tif")->status, 403);

  // No CRS on either side: the GeoTIFF's coordinates are the sketch's.
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  write_geotiff(work() / "maps" / "local.tif", 0, 250, 100);
  auto where = client->Get("/api/basemap?file=maps/local.tif");
  ASSERT_EQ(where->status, 200) << where->body;
  EXPECT_TRUE(json::parse(where->body)["crs"].is_null());
  const auto [at, alpha] = red_mark(client->Get("/api/basemap.png?file=maps/local.tif")->body,
                                    json::parse(where->body)["extent"], dir / "basemap.png");
  EXPECT_NEAR(at.x, 250, 5);
  EXPECT_NEAR(at.y, 100, 5);
  refused("maps/mark_3857.tif", "while the sketch has no place on Earth");
}

// The page draws with the program's colours and default road widths.
TEST_F(ServeTest, PaletteIsTheProgramsOwn) {
  auto r = client->Get("/api/palette");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const json p = json::parse(r->body);
  EXPECT_EQ(p["road_widths"], json::parse(R"({"highway": 24, "main": 12, "local": 8})"));
  EXPECT_EQ(p["sketch_zones"]["residential"], exacity::sketch_zone_colour(exacity::ZoneType::Residential));
  EXPECT_EQ(p["sketch_zones"]["water"], exacity::kMapWater);
  EXPECT_EQ(p["sketch_roads"]["main"], "#333333");
  EXPECT_EQ(p["map"]["building"], exacity::kMapBuilding);
  EXPECT_EQ(p["map"]["zones"]["park"], "#a8d38d");
  EXPECT_EQ(httplib::Client("127.0.0.1", port).Get("/api/palette")->status, 403);
}

TEST_F(ServeTest, UnknownRoutesAreRefusedWithAMessage) {
  for (const char* path : {"/api/nothing", "/api/layers/streets.geojson", "/api/render/sky.png", "/nothing.html"}) {
    auto r = client->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
    EXPECT_FALSE(r->body.empty()) << path;
  }
  auto post = client->Post("/api/nothing", "{}", "application/json");
  EXPECT_EQ(post->status, 404);
  EXPECT_NE(post->body.find("no such route"), std::string::npos) << post->body;
  auto del = client->Delete("/api/sketch");
  EXPECT_EQ(del->status, 404);
  EXPECT_NE(del->body.find("no such route"), std::string::npos) << del->body;
  auto page = client->Get("/");
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("exacity"), std::string::npos);
  EXPECT_EQ(client->Get("/lib/app.js")->status, 200);
}

TEST_F(ServeTest, UrlsThatTryToLeaveTheFoldersAreRefused) {
  for (const char* path :
       {"/../secret.txt", "/%2e%2e/secret.txt", "/%2E%2E%2Fsecret.txt", "/..%2fsecret.txt", "/lib/..%2f..%2fsecret.txt",
        "/%252e%252e/secret.txt", "/.%2e/secret.txt", "/leak.txt", "/up/secret.txt", "/%2fetc%2fpasswd", "//etc/passwd",
        "/lib/%2e%2e/%2e%2e/secret.txt", "/..%5csecret.txt", "/%00index.html", "/api/layers/..%2f..%2fsecret.geojson",
        "/api/render/..%2f..%2fsecret.png"}) {
    auto r = client->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_GE(r->status, 400) << path;
    EXPECT_LT(r->status, 500) << path;
    EXPECT_EQ(r->body.find("SECRET"), std::string::npos) << path;
    EXPECT_EQ(r->body.find("root:"), std::string::npos) << path;
  }
}

TEST_F(ServeTest, SketchPathsThatLeaveTheWorkFolderAreRefused) {
  write_heightmap(dir / "outside.png");
  fs::create_symlink(dir / "outside.png", work() / "link.png");
  write(dir / "town.grid", "RRR\n");
  const std::string terrain = R"(, "terrain": {"bounds": [0, 0, 600, 300], "height": [0, 50], "heightmap": )";
  for (const std::string& settings :
       {R"({"seed": 3)" + terrain + R"("../outside.png"}})",
        R"({"seed": 3)" + terrain + "\"" + (dir / "outside.png").string() + "\"}}",
        R"({"seed": 3)" + terrain + R"("link.png"}})", R"({"seed": 3)" + terrain + R"("sub/../../outside.png"}})",
        std::string(R"({"seed": 3, "grid": "../town.grid"})"),
        std::string(R"({"seed": 3, "zones": {"residential": {"layout": "grammar", "grammar": "/etc/passwd"}}})"),
        std::string(R"({"seed": 3, "models": "../library.json"})")}) {
    auto r = client->Put("/api/sketch", sketch_with(settings), "application/geo+json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << settings;
    EXPECT_EQ(r->body.find('\n'), std::string::npos) << r->body;
    EXPECT_NE(r->body.find("\"exacity\"."), std::string::npos) << "names the key: " << r->body;
  }
  EXPECT_FALSE(fs::exists(sketch_file()));
  // Inside the work folder the same heightmap is taken.
  fs::copy_file(dir / "outside.png", work() / "valley.png");
  auto ok =
      client->Put("/api/sketch", sketch_with(R"({"seed": 3)" + terrain + R"("valley.png"}})"), "application/geo+json");
  EXPECT_EQ(ok->status, 200) << ok->body;
}

// A model library in the work folder is taken when its OBJ and .mtl files are there too.
TEST_F(ServeTest, ModelLibraryFilesMustStayInTheWorkFolder) {
  write(dir / "secret.mtl", "newmtl SECRET\n");
  fs::create_directories(work() / "models");
  for (const char* name : {"library.json", "house_gabled.obj", "library.mtl"})
    fs::copy_file(cli_util::kSource / "examples" / "models" / name, work() / "models" / name);
  write(work() / "models" / "one.json",
        R"({"models": [{"file": "house_gabled.obj", "zones": ["residential"], "up": "y"}]})");
  EXPECT_EQ(
      client->Put("/api/sketch", sketch_with(R"({"seed": 3, "models": "models/one.json"})"), "application/geo+json")
          ->status,
      200);
  write(work() / "models" / "out.json", R"({"models": [{"file": "/etc/hostname", "zones": ["residential"]}]})");
  write(work() / "models" / "leaky.obj", "mtllib ../../secret.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write(work() / "models" / "leaky.json", R"({"models": [{"file": "leaky.obj", "zones": ["residential"]}]})");
  for (const char* manifest : {"models/out.json", "models/leaky.json"}) {
    auto r = client->Put("/api/sketch", sketch_with(std::string(R"({"seed": 3, "models": ")") + manifest + "\"}"),
                         "application/geo+json");
    EXPECT_EQ(r->status, 400) << manifest;
    EXPECT_NE(r->body.find("\"exacity\".models"), std::string::npos) << r->body;
    EXPECT_EQ(r->body.find('\n'), std::string::npos) << r->body;
  }
}

// The example library's files as a multipart form, each part named by its file name.
httplib::MultipartFormDataItems example_library() {
  httplib::MultipartFormDataItems items;
  for (const auto& entry : fs::directory_iterator(cli_util::kSource / "examples" / "models"))
    if (entry.path().extension() != ".py")
      items.push_back({"file", read(entry.path()), entry.path().filename().string(), "application/octet-stream"});
  return items;
}

// A library uploaded from the page: stored in work/models, named by the sketch, and used by
// the generation (models stand on the lots).
TEST_F(ServeTest, UploadedModelLibraryIsUsedByTheGeneration) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  auto r = client->Post("/api/models", example_library());
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json::parse(r->body)["exacity"]["models"], "models/library.json");
  EXPECT_EQ(json::parse(client->Get("/api/sketch")->body)["exacity"]["models"], "models/library.json");
  EXPECT_EQ(read(work() / "models" / "house_l.obj"), read(cli_util::kSource / "examples" / "models" / "house_l.obj"));
  ASSERT_EQ(client->Post("/api/generate", "", "application/json")->status, 202);
  const json done = wait_for_job(*client);
  ASSERT_EQ(done["state"], "done") << done.dump();
  const json buildings = json::parse(client->Get("/api/layers/buildings.geojson")->body);
  std::set<std::string> models;
  for (const json& f : buildings["features"])
    if (f["properties"]["model"].is_string()) models.insert(f["properties"]["model"].get<std::string>());
  EXPECT_TRUE(models.count("house_gabled") || models.count("house_wide") || models.count("house_l"))
      << buildings["features"].size();
  // Every placed model and piece of clutter in one tile, as city.glb has one node each.
  const json index = json::parse(client->Get("/api/tiles.json")->body);
  const json report = json::parse(client->Get("/api/report")->body);
  std::size_t placed = 0, clutter = 0;
  for (const json& tile : index["tiles"])
    placed += tile["models"].get<std::size_t>(), clutter += tile["clutter"].get<std::size_t>();
  EXPECT_GT(placed, 0u);
  EXPECT_EQ(placed + clutter, full_build_report()["counts"]["gltf"]["instances"].get<std::size_t>());
}

// The library in use, as the model library stage reads it: each model's kind and the zone
// types it stands in; none before a sketch names one.
TEST_F(ServeTest, LibraryInUseIsListed) {
  EXPECT_EQ(json::parse(client->Get("/api/models")->body),
            json::parse(R"({"file": null, "models": [], "builtin": []})"));
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  EXPECT_EQ(json::parse(client->Get("/api/models")->body)["file"], nullptr);
  ASSERT_EQ(client->Post("/api/models", example_library())->status, 200);
  auto r = client->Get("/api/models");
  ASSERT_EQ(r->status, 200) << r->body;
  const json library = json::parse(r->body);
  EXPECT_EQ(library["file"], "models/library.json");
  EXPECT_EQ(library["builtin"], json::array());  // the small sketch turns them off
  const exacity::ModelLibrary loaded = exacity::load_model_library(work() / "models" / "library.json");
  ASSERT_EQ(library["models"].size(), loaded.models.size());
  std::map<std::string, json> by_name;
  for (const json& m : library["models"]) by_name[m["name"]] = m;
  EXPECT_EQ(by_name["apartment"]["zones"], json::array({"residential", "commercial"}));
  EXPECT_EQ(by_name["apartment"]["kind"], "building");
  EXPECT_EQ(by_name["tree"]["kind"], "tree");
  EXPECT_EQ(by_name["house_gabled"]["weight"], 3);
  EXPECT_EQ(by_name["house_gabled"]["size"].size(), 3u);
}

// A bad library is refused with the message the CLI gives for it; the library and sketch
// from before stay.
TEST_F(ServeTest, BadModelLibraryIsRefusedWithTheCliMessage) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  ASSERT_EQ(client->Post("/api/models", example_library())->status, 200);
  const std::string sketch_before = client->Get("/api/sketch")->body;
  const std::string bad_manifest = R"({"models": [{"file": "missing.obj", "zones": ["residential"]}]})";
  auto r = client->Post("/api/models", httplib::MultipartFormDataItems{
                                           {"file", bad_manifest, "bad.json", "application/json"},
                                           {"file", read(cli_util::kSource / "examples" / "models" / "house_l.obj"),
                                            "house_l.obj", "application/octet-stream"}});
  ASSERT_EQ(r->status, 400);
  EXPECT_EQ(r->body.find('\n'), std::string::npos) << r->body;
  EXPECT_EQ(client->Get("/api/sketch")->body, sketch_before);
  EXPECT_TRUE(fs::is_regular_file(work() / "models" / "library.json"));
  EXPECT_FALSE(fs::exists(work() / "models" / "bad.json"));
  // The CLI's message for the same files in the same place.
  write(work() / "models" / "bad.json", bad_manifest);
  std::string cli;
  try {
    exacity::load_model_library(work() / "models" / "bad.json");
  } catch (const exacity::UserError& e) {
    cli = e.what();
  }
  EXPECT_FALSE(cli.empty());
  EXPECT_EQ(r->body, in_work(cli));
  // Not a form, no manifest, two manifests.
  EXPECT_EQ(client->Post("/api/models", "{}", "application/json")->status, 415);
  auto none = client->Post("/api/models", httplib::MultipartFormDataItems{{"file", "v 0 0 0\n", "a.obj", ""}});
  EXPECT_EQ(none->status, 400);
  EXPECT_NE(none->body.find("no .json manifest"), std::string::npos) << none->body;
  auto two = client->Post("/api/models",
                          httplib::MultipartFormDataItems{{"file", "{}", "a.json", ""}, {"file", "{}", "b.json", ""}});
  EXPECT_EQ(two->status, 400);
  EXPECT_NE(two->body.find("two .json files"), std::string::npos) << two->body;
}

// No uploaded file lands outside work/models, however it is named, and a manifest naming
// files outside the work folder is refused as a sketch naming them would be.
TEST_F(ServeTest, ModelUploadNamesThatTryToLeaveAreRefused) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  const std::string manifest = R"({"models": [{"file": "house_l.obj", "zones": ["residential"], "up": "z"}]})";
  const std::string obj = read(cli_util::kSource / "examples" / "models" / "house_l.obj");
  for (const char* name : {"../escape.obj", "/tmp/escape.obj", "sub/../../escape.obj", ".hidden.obj",
                           "sub/.hidden/escape.obj", "a\\escape.obj", "sub//escape.obj", ""}) {
    auto r = client->Post("/api/models",
                          httplib::MultipartFormDataItems{{"file", manifest, "lib.json", ""}, {"file", obj, name, ""}});
    EXPECT_EQ(r->status, 400) << name;
    EXPECT_NE(r->body.find("the model library upload"), std::string::npos) << name << ": " << r->body;
  }
  EXPECT_FALSE(fs::exists(dir / "escape.obj"));
  EXPECT_FALSE(fs::exists(work() / "escape.obj"));
  EXPECT_FALSE(fs::exists("/tmp/escape.obj"));
  write(dir / "secret.obj", obj);
  auto out = client->Post(
      "/api/models", httplib::MultipartFormDataItems{
                         {"file", R"({"models": [{"file": "../../secret.obj", "zones": ["residential"], "up": "z"}]})",
                          "lib.json", ""}});
  EXPECT_EQ(out->status, 400);
  EXPECT_NE(out->body.find("\"exacity\".models"), std::string::npos) << out->body;
  EXPECT_FALSE(fs::exists(work() / "models"));
}

// A real place (tests/place_sketch.h) with `buildings` footprints, as the file uploaded.
std::string place_geojson(int buildings) { return place_sketch::measured_place(buildings).dump(); }

// A place uploaded from the page (generate --like): stored in work/like, named by the
// sketch, measured as generate measures it (GET /api/like), and looked like by the
// generation.
TEST_F(ServeTest, UploadedPlaceIsMeasuredAndLookedLike) {
  EXPECT_EQ(json::parse(client->Get("/api/like")->body), json::parse(R"({"file": null, "measured": null})"));
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  auto r = client->Post("/api/like", httplib::MultipartFormDataItems{{"file", place_geojson(12), "place.geojson", ""}});
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(json::parse(r->body)["exacity"]["like"], "like/place.geojson");
  EXPECT_EQ(json::parse(client->Get("/api/sketch")->body)["exacity"]["like"], "like/place.geojson");
  EXPECT_EQ(read(work() / "like" / "place.geojson"), place_geojson(12));
  const json like = json::parse(client->Get("/api/like")->body);
  EXPECT_EQ(like["file"], "like/place.geojson");
  EXPECT_EQ(like["measured"]["file"], "like/place.geojson");
  EXPECT_EQ(like["measured"]["footprints"], 12);
  EXPECT_EQ(like["measured"]["zones"]["residential"]["measured"]["area_m2"],
            json::parse(R"({"count": 12, "p10": 120.0, "median": 200.0, "p90": 300.0})"));
  EXPECT_EQ(like["measured"]["zones"]["residential"]["set"]["setback"], 5.0);
  EXPECT_EQ(like["measured"]["zones"]["commercial"]["kept_defaults"], "fewer than 10 mapped buildings in commercial land");
  ASSERT_EQ(client->Post("/api/generate", "", "application/json")->status, 202);
  const json done = wait_for_job(*client);
  ASSERT_EQ(done["state"], "done") << done.dump();
  const json report = json::parse(client->Get("/api/report")->body);
  EXPECT_EQ(report["like"], like["measured"]);
  // The city's sketch holds what was set in place of "like", as generate's copy does.
  const json copy = json::parse(read(work() / "city" / "sketch.geojson"));
  EXPECT_FALSE(copy["exacity"].contains("like"));
  EXPECT_EQ(copy["exacity"]["zones"]["residential"]["setback"], 5.0);
}

// A place the CLI cannot measure is refused with its message; so are uploads that are no
// place, two places, a file that is not what its name says (an OGR VRT named .gpkg could
// read any file) and names that leave the folder. The sketch and the place from before stay.
TEST_F(ServeTest, BadPlaceUploadsAreRefused) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  ASSERT_EQ(client->Post("/api/like", httplib::MultipartFormDataItems{{"file", place_geojson(12), "place.geojson", ""}})->status,
            200);
  const std::string sketch_before = client->Get("/api/sketch")->body;
  auto few = client->Post("/api/like", httplib::MultipartFormDataItems{{"file", place_geojson(3), "few.geojson", ""}});
  EXPECT_EQ(few->status, 400);
  EXPECT_EQ(few->body, "like/few.geojson: maps 3 building footprints, too few to measure a place by (at least 10); give an "
                       "extract or a file with more of its buildings, or leave out --like");
  const std::string vrt = "<OGRVRTDataSource><OGRVRTLayer name=\"x\"><SrcDataSource>" + (dir / "secret.txt").string() +
                          "</SrcDataSource></OGRVRTLayer></OGRVRTDataSource>";
  const std::vector<std::pair<httplib::MultipartFormDataItems, std::string>> refused{
      {{{"file", vrt, "place.gpkg", ""}}, "like/place.gpkg: not a GPKG file, as its name says; save it as one"},
      {{{"file", "x", "place.txt", ""}}, "the place upload: \"place.txt\" is not a file of a place exacity serve reads"},
      {{{"file", "{}", "a.geojson", ""}, {"file", "{}", "b.osm", ""}}, "the place upload has two places"},
      {{{"file", "x", "place.dbf", ""}}, "the place upload has only a shapefile's companions"},
      {{{"file", place_geojson(12), "../place.geojson", ""}}, "the place upload: the file name \"../place.geojson\" has"},
      {{{"file", place_geojson(12), "sub/.hidden.geojson", ""}}, "the place upload: the file name"},
      {{{"file", place_geojson(12), "", ""}}, "the place upload: the file name \"\" has no name"}};
  for (const auto& [items, message] : refused) {
    auto r = client->Post("/api/like", items);
    EXPECT_EQ(r->status, 400) << message;
    EXPECT_EQ(r->body.rfind(message, 0), 0u) << message << " / " << r->body;
    EXPECT_EQ(r->body.find('\n'), std::string::npos) << r->body;
  }
  EXPECT_EQ(client->Post("/api/like", place_geojson(12), "application/geo+json")->status, 415);
  EXPECT_EQ(client->Get("/api/sketch")->body, sketch_before);
  EXPECT_EQ(read(work() / "like" / "place.geojson"), place_geojson(12));
  EXPECT_FALSE(fs::exists(dir / "place.geojson"));
  EXPECT_FALSE(fs::exists(work() / "like" / "place.gpkg"));
}

TEST_F(ServeTest, OversizedBodyIsRefused) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  std::string big = kSmallSketch;
  big.insert(big.size() - 2, std::string(100 * 1024, ' '));
  auto r = client->Put("/api/sketch", big, "application/geo+json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_NE(r->body.find("too large"), std::string::npos) << r->body;
  EXPECT_EQ(read(sketch_file()), kSmallSketch);
}

TEST_F(ServeTest, RenderBeforeAnyGenerationIsRefused) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  auto r = client->Post("/api/render", R"({"size": "32x24", "spp": 1})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409);
  EXPECT_NE(r->body.find("POST /api/generate first"), std::string::npos) << r->body;
  for (const char* path :
       {"/api/render/still.png", "/api/map.svg", "/api/report", "/api/city.glb", "/api/layers/roads.geojson"})
    EXPECT_EQ(client->Get(path)->status, 404) << path;
  EXPECT_EQ(json::parse(client->Get("/api/status")->body)["state"], "idle");
}

TEST_F(ServeTest, BadRenderRequestsAreRefused) {
  for (const char* body : {"not json", R"({"size": "0x0"})", R"({"spp": 0})", R"({"spp": 1.5})", R"({"zoom": 2})",
                           R"({"camera": "orbit:target=0,0"})", R"({"overview": "yes"})"}) {
    auto r = client->Post("/api/render", body, "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << body;
    EXPECT_EQ(r->body.find('\n'), std::string::npos) << r->body;
  }
}

// A generation with its events, then its outputs, a second generation refused while it runs,
// and a render.
TEST_F(ServeTest, GenerateStreamsStagesThenServesOutputsAndRenders) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  std::vector<std::string> stages;
  std::string ended;
  std::thread events = listen([&](const std::string& kind, const json& payload) {
    if (kind == "stage") stages.push_back(payload["stage"]);
    if (kind == "state" && payload["state"] != "running" && payload["job"] == "generate") {
      ended = payload["state"];
      return false;
    }
    return true;
  });
  auto first = client->Post("/api/generate", "", "application/json");
  ASSERT_EQ(first->status, 202) << first->body;
  EXPECT_EQ(json::parse(first->body)["state"], "running");
  auto second = client->Post("/api/generate", "", "application/json");
  EXPECT_EQ(second->status, 409) << second->body;
  EXPECT_NE(second->body.find("running"), std::string::npos) << second->body;
  events.join();
  EXPECT_EQ(ended, "done");
  // The CLI's stage names, in its order, but the 3D files', which are written when first
  // downloaded, and validation's, after the tiles (the page's answer).
  EXPECT_EQ(stages, (std::vector<std::string>{"terrain", "model library", "zone map", "road network", "blocks", "lots",
                                              "buildings", "ground", "clutter", "vector layers", "export", "tiles",
                                              "validation"}));
  EXPECT_EQ(json::parse(client->Get("/api/status")->body)["state"], "done");

  EXPECT_EQ(client->Get("/api/map.svg")->body.find("<svg") != std::string::npos, true);
  const json report = json::parse(client->Get("/api/report")->body);
  EXPECT_GT(report["counts"]["lots"].get<int>(), 0);
  EXPECT_FALSE(report["counts"].contains("gltf"));
  for (const char* name : {"city.glb", "city.city.json", "city.obj", "city.ply", "city.gpkg"})
    EXPECT_FALSE(fs::exists(work() / "city" / name)) << name << ": written before it was asked for";
  EXPECT_EQ(client->Get("/api/city.glb")->body.substr(0, 4), "glTF");
  for (const char* layer : {"zones", "water", "roads", "road_areas", "blocks", "lots", "buildings"}) {
    auto r = client->Get(std::string("/api/layers/") + layer + ".geojson");
    ASSERT_EQ(r->status, 200) << layer;
    EXPECT_EQ(json::parse(r->body)["type"], "FeatureCollection") << layer;
  }
  // Every 3D and GIS file generate writes, to download: city.osm not, the sketch having no
  // CRS; the GeoPackage with every layer.
  EXPECT_EQ(json::parse(client->Get("/api/status")->body)["files"],
            json::parse(R"(["city.glb", "city.city.json", "city.obj", "city.ply", "city.gpkg", "map.svg"])"));
  for (const char* name : {"city.glb", "city.city.json", "city.obj", "city.ply", "city.gpkg", "map.svg"}) {
    auto r = client->Get(std::string("/api/files/") + name);
    ASSERT_EQ(r->status, 200) << name;
    EXPECT_EQ(r->body, read(work() / "city" / name)) << name;
  }
  EXPECT_EQ(client->Get("/api/files/city.gpkg")->body.substr(0, 15), "SQLite format 3");
  EXPECT_EQ(client->Get("/api/files/city.osm")->status, 404);
  EXPECT_EQ(client->Get("/api/files/report.json")->status, 404);
  EXPECT_EQ(client->Get("/api/files/..")->status, 404);

  auto render =
      client->Post("/api/render",
                   R"({"camera": "orbit:target=300,150,0,azimuth=225,elevation=35,distance=600", "size": "32x24",
                                 "spp": 1, "overview": true, "minimap": true})",
                   "application/json");
  ASSERT_EQ(render->status, 202) << render->body;
  const json rendered = wait_for_job(*client);
  ASSERT_EQ(rendered["state"], "done") << rendered.dump();
  for (const char* image : {"still", "overview", "minimap"}) {
    auto r = client->Get(std::string("/api/render/") + image + ".png");
    ASSERT_EQ(r->status, 200) << image;
    EXPECT_EQ(r->body.substr(1, 3), "PNG") << image;
  }
}

// The page is answered once what it shows is written (docs/design.md, Serving: jobs): the
// "answered" event comes after the tiles and before validation; from then the layers are
// there, a 3D file not yet written is written when asked for, and a generation asked for
// does not wait for the validation, whose city it replaces.
TEST_F(ServeTest, TheCityIsAnsweredBeforeItsValidation) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  std::vector<std::string> order;  // the stages and the answers, as they came
  std::vector<json> ends;          // the generations' end states
  int lots = 0, again = 0;
  std::string glb;
  std::thread events = listen([&](const std::string& kind, const json& e) {
    if (kind == "stage") order.push_back(e["stage"]);
    if (kind == "answered" && order.back() == "tiles") {
      order.push_back("answered");
      if (again) return true;
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(60);
      c.set_bearer_token_auth(kToken.c_str());
      lots = c.Get("/api/layers/lots.geojson")->status;
      glb = c.Get("/api/files/city.glb")->body;
      again = c.Post("/api/generate", "", "application/json")->status;
    }
    if (kind == "state" && e["state"] != "running" && e["job"] == "generate") ends.push_back(e);
    return ends.size() < (again == 202 ? 2u : 1u);  // the second generation's end too, once started
  });
  ASSERT_EQ(client->Post("/api/generate", "", "application/json")->status, 202);
  events.join();
  const std::vector<std::string> answer{"export", "tiles", "answered", "validation"};
  int answers = 0;
  for (std::size_t i = 2; i + 1 < order.size(); ++i)
    if (order[i] == "answered") {
      ++answers;
      EXPECT_EQ(std::vector<std::string>(order.begin() + i - 2, order.begin() + i + 2), answer)
          << testing::PrintToString(order);
    }
  EXPECT_EQ(answers, 2) << testing::PrintToString(order);
  EXPECT_EQ(lots, 200);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
  EXPECT_EQ(again, 202);
  // The first generation validated its city before the second began, or was stopped in its
  // validation; the second's city is the same sketch's, validated.
  ASSERT_EQ(ends.size(), 2u);
  if (ends[0]["state"] == "cancelled")
    EXPECT_EQ(ends[0]["error"].get<std::string>().rfind("stopped during the validation stage after its answer", 0), 0u)
        << ends[0].dump();
  else
    EXPECT_EQ(ends[0]["state"], "done") << ends[0].dump();
  EXPECT_EQ(ends[1]["state"], "done") << ends[1].dump();
  const json report = json::parse(client->Get("/api/report")->body);
  EXPECT_EQ(report["validation"]["ok"], true) << report["validation"].dump();
  EXPECT_GT(report["answer_s"].get<double>(), 0);
  EXPECT_TRUE(report["timings_s"].contains("validation"));
  EXPECT_TRUE(client->Get("/api/files/city.glb")->body == glb);
}

// The 3D view's tiles: every structure in one tile, at full level exactly city.glb's
// triangles (a city without models, whose meshes city.glb shares between tiles), a box (a
// roof and four walls: 10 triangles) per structure at the next level and fewer at the last.
TEST_F(ServeTest, TilesHoldTheCityAtThreeLevels) {
  EXPECT_EQ(client->Get("/api/tiles.json")->status, 404);
  put_small_and_generate();
  auto r = client->Get("/api/tiles.json");
  ASSERT_EQ(r->status, 200);
  const json index = json::parse(r->body);
  const json report = json::parse(client->Get("/api/report")->body);
  ASSERT_EQ(index["levels"].size(), 3u);
  EXPECT_EQ(index["levels"][2]["until"], nullptr);
  EXPECT_LT(index["levels"][0]["until"].get<double>(), index["levels"][1]["until"].get<double>());
  // 600 m by 300 m (and the highway's ends): two tiles of 250 m at least.
  ASSERT_GE(index["tiles"].size(), 2u) << index.dump();
  EXPECT_EQ(client->Get("/api/tiles/ground.glb")->body.substr(0, 4), "glTF");
  std::size_t structures = 0, clutter = 0, triangles = index["ground_triangles"].get<std::size_t>();
  std::set<std::string> names;
  for (const json& tile : index["tiles"]) {
    EXPECT_TRUE(names.insert(tile["name"].get<std::string>()).second);
    const std::size_t here = tile["buildings"].get<std::size_t>() + tile["models"].get<std::size_t>();
    structures += here, clutter += tile["clutter"].get<std::size_t>();
    triangles += tile["triangles"][0].get<std::size_t>();
    EXPECT_EQ(tile["triangles"][1], 10 * here) << tile.dump();
    EXPECT_LE(tile["triangles"][2].get<std::size_t>(), tile["triangles"][1].get<std::size_t>()) << tile.dump();
    EXPECT_GT(tile["triangles"][2].get<std::size_t>(), 0u) << tile.dump();
    const json& box = tile["box"];
    EXPECT_LT(box[0].get<double>(), box[3].get<double>());
    EXPECT_LT(box[2].get<double>(), box[5].get<double>());
    for (const json& url : tile["levels"]) {
      auto glb = client->Get(url.get<std::string>());
      ASSERT_EQ(glb->status, 200) << url;
      EXPECT_EQ(glb->body.substr(0, 4), "glTF") << url;
    }
  }
  EXPECT_EQ(structures, report["counts"]["buildings"].get<std::size_t>());
  EXPECT_EQ(clutter, report["counts"]["clutter"].get<std::size_t>());
  EXPECT_EQ(triangles, full_build_report()["counts"]["gltf"]["triangles"].get<std::size_t>());
  for (const char* url : {"/api/tiles/99_99/0.glb", "/api/tiles/0_0/3.glb", "/api/tiles/..%2F..%2Fsketch.geojson",
                          "/api/tiles/0_0/..%2F..%2Freport.json"})
    EXPECT_EQ(client->Get(url)->status, 404) << url;
}

// Every file under `dir`, by its path from there, with its bytes.
std::map<std::string, std::string> folder_files(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) out[entry.path().lexically_relative(dir).string()] = read(entry.path());
  return out;
}

// The tiles written after an edit (serve/city_tiles.h) are every byte the edited sketch's
// tiles built from nothing are; a tile made of what a tile of the last build was made of
// keeps that tile's bytes, written without encoding it again.
TEST(CityTilesTest, AnEditsTilesAreTheFullBuildsAndUnchangedTilesAreKept) {
  auto tiles_of = [](const json& doc, std::shared_ptr<exacity::RegionCache> cache, const exacity::City* previous,
                     const std::string& name) {
    exacity::StageClock clock(nullptr, exacity::kCityStages);
    const exacity::Sketch sketch = exacity::parse_sketch(doc.dump(), "small.geojson");
    exacity::City city = previous ? exacity::regenerate(*previous, sketch, clock)
                                  : exacity::build_city(sketch, clock, std::move(cache));
    const fs::path dir = testing_util::temp_dir(name);
    exacity::serve::write_city_tiles(city, dir);
    return std::make_pair(std::move(city), folder_files(dir));
  };
  const json first = json::parse(kSmallSketch);
  json edited = first;
  edited["features"].push_back(json::parse(R"({"type": "Feature", "properties": {"zone": "park"},
    "geometry": {"type": "Polygon", "coordinates": [[[150, 40], [250, 40], [250, 110], [150, 110], [150, 40]]]}})"));
  const auto [before, before_files] = tiles_of(first, std::make_shared<exacity::RegionCache>(), nullptr, "before");
  const auto [after, after_files] = tiles_of(edited, nullptr, &before, "after");
  const auto [whole, whole_files] = tiles_of(edited, nullptr, nullptr, "whole");
  ASSERT_GE(whole_files.size(), 9u);  // two tiles' three levels, the ground, the facades and the index at least
  for (const auto& [file, bytes] : whole_files) EXPECT_TRUE(after_files.count(file) && after_files.at(file) == bytes) << file;
  EXPECT_EQ(after_files.size(), whole_files.size());
  EXPECT_TRUE(after_files != before_files);
  // Generated again as it is: every tile is the last build's.
  const auto [again, again_files] = tiles_of(edited, nullptr, &after, "again");
  const exacity::Memo<exacity::TileFiles>& tiles = again.regions->tiles;
  EXPECT_EQ(tiles.misses(), 0);
  EXPECT_EQ(tiles.hits(), static_cast<int>(json::parse(again_files.at("index.json"))["tiles"].size()));
  EXPECT_TRUE(again_files == whole_files);
}

// A generation after an edit reuses the regions, blocks and lots the edit left as they were
// (generate/regenerate.h); what it writes is what generating the edited sketch alone writes.
// A glb's materials by name, with their base colours.
std::map<std::string, std::array<double, 3>> glb_materials(const std::string& bytes) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  EXPECT_TRUE(loader.LoadBinaryFromMemory(&model, &error, &warning,
                                          reinterpret_cast<const unsigned char*>(bytes.data()),
                                          static_cast<unsigned>(bytes.size())))
      << error;
  std::map<std::string, std::array<double, 3>> out;
  for (const tinygltf::Material& m : model.materials) {
    const auto& c = m.pbrMetallicRoughness.baseColorFactor;
    out[m.name] = {c[0], c[1], c[2]};
  }
  return out;
}

// The 3D view looks like the still: city.glb and the tiles' boxes give each building the
// facade and roof albedo the renderer gives it (a material per albedo, named by its zone,
// surface and index), and the ground the renderer's grass, paving and asphalt.
TEST_F(ServeTest, CityGlbColoursAreTheRenderersAlbedos) {
  put_small_and_generate();
  const json buildings = json::parse(client->Get("/api/layers/buildings.geojson")->body);
  const std::map<std::string, exacity::ZoneType> zones{{"residential", exacity::ZoneType::Residential},
                                                       {"commercial", exacity::ZoneType::Commercial},
                                                       {"industrial", exacity::ZoneType::Industrial}};
  std::map<std::string, exacity::Albedo> expected;
  for (const json& f : buildings["features"]) {
    ASSERT_TRUE(f["properties"]["model"].is_null());  // extruded, as this sketch has no library
    const std::string zone = f["properties"]["zone"];
    const auto albedos = exacity::structure_albedos(zones.at(zone), 3, f["properties"]["id"].get<int>());
    expected[zone + "_wall_" + std::to_string(albedos.facade)] = exacity::facade_albedos(zones.at(zone))[albedos.facade];
    expected[zone + "_roof_" + std::to_string(albedos.roof)] = exacity::roof_albedos(zones.at(zone))[albedos.roof];
  }
  ASSERT_GE(expected.size(), 6u);  // residential and commercial buildings, in more than one colour each
  const auto structure_colours = [&](const std::map<std::string, std::array<double, 3>>& materials) {
    std::map<std::string, exacity::Albedo> out;
    for (const auto& [name, c] : materials)
      if (name.find("_wall_") != std::string::npos || name.find("_roof_") != std::string::npos)
        out[name] = {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
    return out;
  };
  const auto city = glb_materials(client->Get("/api/city.glb")->body);
  EXPECT_EQ(structure_colours(city), expected);
  EXPECT_EQ(city.at("ground_residential"), (std::array<double, 3>{0.30f, 0.45f, 0.20f}));  // grass
  EXPECT_EQ(city.at("ground_commercial"), (std::array<double, 3>{0.50f, 0.49f, 0.46f}));   // paving
  EXPECT_EQ(city.at("road"), (std::array<double, 3>{0.125f, 0.12f, 0.115f}));              // asphalt
  // The boxes standing for buildings further away are coloured as the buildings are.
  std::map<std::string, exacity::Albedo> boxes;
  const json index = json::parse(client->Get("/api/tiles.json")->body);
  for (const json& tile : index["tiles"])
    for (const auto& named : structure_colours(glb_materials(client->Get(tile["levels"][1].get<std::string>())->body)))
      boxes.insert(named);
  EXPECT_EQ(boxes, expected);
}

// The 3D files and the GeoPackage of a city another run of the server generated: written
// when asked for, from the city rebuilt from its sketch, as the generation would have.
TEST_F(ServeTest, DownloadsOfAnotherRunsCityAreWrittenWhenAskedFor) {
  put_small_and_generate();
  restart();
  EXPECT_EQ(json::parse(client->Get("/api/status")->body)["files"],
            json::parse(R"(["city.glb", "city.city.json", "city.obj", "city.ply", "city.gpkg", "map.svg"])"));
  const fs::path alone = testing_util::temp_dir("alone");
  generate_with_gpkg(kSmallSketch, alone);
  for (const char* file : {"city.gpkg", "city.obj", "city.glb", "city.city.json", "city.ply"}) {
    auto r = client->Get(std::string("/api/files/") + file);
    ASSERT_EQ(r->status, 200) << file << ": " << r->body;
    EXPECT_TRUE(r->body == read(alone / file)) << file;
  }
  EXPECT_FALSE(fs::exists(work() / ".downloads.partial"));
}

TEST_F(ServeTest, GenerationAfterAnEditWritesTheEditedSketchsCity) {
  put_small_and_generate();
  json edited = json::parse(kSmallSketch);
  edited["features"][1]["geometry"]["coordinates"][0][2] = json::array({620, 310});  // north of the highway only
  ASSERT_EQ(client->Put("/api/sketch", edited.dump(), "application/geo+json")->status, 200);
  ASSERT_EQ(client->Post("/api/generate", "", "application/json")->status, 202);
  ASSERT_EQ(wait_for_job(*client)["state"], "done");
  const fs::path alone = testing_util::temp_dir("alone");
  generate_with_gpkg(edited.dump(), alone);
  for (const char* file : {"vector/zones.geojson", "vector/roads.geojson", "vector/road_areas.geojson",
                           "vector/blocks.geojson", "vector/lots.geojson", "vector/buildings.geojson",
                           "vector/clutter.geojson", "map.svg"})
    EXPECT_TRUE(read(work() / "city" / file) == read(alone / file)) << file;
  // The 3D files and the GeoPackage, written when asked for, from the city in memory.
  for (const char* file : {"city.city.json", "city.glb", "city.obj", "city.ply", "city.gpkg"})
    EXPECT_TRUE(client->Get(std::string("/api/files/") + file)->body == read(alone / file)) << file;
  // The report says what was reused: each kind's count within all it asked for.
  const json reused = json::parse(read(work() / "city" / "report.json"))["reused"];
  for (const char* kind : {"region_plans", "block_plans", "lot_placements", "structure_meshes"}) {
    EXPECT_GT(reused[kind]["of"].get<int>(), 0) << kind;
    EXPECT_LE(reused[kind]["reused"].get<int>(), reused[kind]["of"].get<int>()) << kind;
  }
  // Generated again without an edit: every region plan, block plan and mesh is reused.
  ASSERT_EQ(client->Post("/api/generate", "", "application/json")->status, 202);
  ASSERT_EQ(wait_for_job(*client)["state"], "done");
  const json again = json::parse(read(work() / "city" / "report.json"))["reused"];
  for (const char* kind : {"region_plans", "block_plans", "structure_meshes"})
    EXPECT_EQ(again[kind]["reused"], again[kind]["of"]) << kind;
  EXPECT_FALSE(json::parse(read(alone / "report.json")).contains("reused"));  // a generation without a cache
}

// Eight clients poll the status and fetch a layer while the city is generated again; every
// answer must be whole and right.
TEST_F(ServeTest, EightClientsDuringAGeneration) {
  put_small_and_generate();
  const std::string roads = client->Get("/api/layers/roads.geojson")->body;
  ASSERT_EQ(client->Post("/api/generate", "", "application/json")->status, 202);
  std::atomic<int> answers{0}, wrong{0}, while_running{0};
  std::vector<std::thread> clients;
  for (int i = 0; i < 8; ++i)
    clients.emplace_back([&] {
      httplib::Client c("127.0.0.1", port);
      c.set_read_timeout(60);
      c.set_bearer_token_auth(kToken.c_str());
      for (int round = 0; round < 2000; ++round) {
        auto s = c.Get("/api/status");
        auto l = c.Get("/api/layers/roads.geojson");
        answers += 2;
        if (!s || s->status != 200 || !l || l->status != 200) {
          ++wrong;
          return;
        }
        const json status = json::parse(s->body, nullptr, false);
        // The same sketch and seed give the same layer, byte for byte (docs/design.md, Determinism).
        if (status.is_discarded() || (status["state"] != "running" && status["state"] != "done") || l->body != roads)
          ++wrong;
        if (status["state"] != "running") return;
        ++while_running;
      }
    });
  for (std::thread& t : clients) t.join();
  EXPECT_EQ(wrong, 0) << "of " << answers << " answers";
  EXPECT_GT(while_running, 0);
  EXPECT_EQ(wait_for_job(*client)["state"], "done");
}

// Event streams hold a request thread each; past the cap they are refused and the API answers.
TEST_F(ServeTest, EventStreamsAreCapped) {
  std::atomic<int> open{0}, refused{0};
  std::vector<std::unique_ptr<httplib::Client>> clients;
  std::vector<std::thread> streams;
  for (int i = 0; i < 18; ++i) {
    clients.push_back(std::make_unique<httplib::Client>("127.0.0.1", port));
    clients.back()->set_bearer_token_auth(kToken.c_str());
    streams.emplace_back([&, c = clients.back().get()] {
      c->Get(
          "/api/events",
          [&](const httplib::Response& r) {
            ++(r.status == 200 ? open : refused);
            return true;
          },
          [](const char*, std::size_t) { return true; });
    });
  }
  for (int i = 0; i < 500 && open + refused < 18; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(open, 16);
  EXPECT_EQ(refused, 2);
  EXPECT_EQ(client->Get("/api/status")->status, 200);
  for (auto& c : clients) c->stop();
  for (std::thread& t : streams) t.join();
}

TEST_F(ServeTest, HeightmapUploadPointsTheSketchAtIt) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  EXPECT_EQ(client->Get("/api/heightmap.png")->status, 404);
  auto junk = client->Put("/api/heightmap", "not an image", "image/png");
  EXPECT_EQ(junk->status, 400);
  write_heightmap(dir / "upload.png");
  auto r = client->Put("/api/heightmap?height=0,40", read(dir / "upload.png"), "image/png");
  ASSERT_EQ(r->status, 200) << r->body;
  const json sketch = json::parse(client->Get("/api/sketch")->body);
  EXPECT_EQ(sketch["exacity"]["terrain"]["heightmap"], "heightmap.png");
  EXPECT_EQ(sketch["exacity"]["terrain"]["bounds"], json::parse("[-50, 0, 650, 300]"));
  EXPECT_EQ(sketch["exacity"]["terrain"]["height"], json::parse("[0, 40]"));
  EXPECT_EQ(read(work() / "heightmap.png"), read(dir / "upload.png"));
  auto preview = client->Get("/api/heightmap.png");
  ASSERT_EQ(preview->status, 200);
  EXPECT_EQ(preview->body.substr(1, 3), "PNG");
}

// Stopping the server cancels its generation and leaves no half-written city.
TEST_F(ServeTest, StopCancelsTheRunningJob) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  ASSERT_EQ(client->Post("/api/generate", "", "application/json")->status, 202);
  server->stop();
  server->finish_jobs();
  EXPECT_FALSE(fs::exists(work() / "city"));
  for (const auto& entry : fs::directory_iterator(work()))
    EXPECT_EQ(entry.path().filename().string().find(".city.partial"), std::string::npos) << entry.path();
}

// A city some kilometres across: its lots stage takes seconds, long enough to cancel in
// (4.9 s uncancelled in the test build, where a cancel stops it in about 1 s; the
// sanitizers slow both about threefold). The bound is on the CPU seconds spent from the
// cancel to the job's end (0.3 s for that stage in the test build), which a loaded machine
// does not stretch as it stretches the wall clock; exacity_cancel_delay (benchmarks/)
// measures the wall time.
#ifdef __SANITIZE_ADDRESS__
constexpr double kStopSeconds = 3;
#else
constexpr double kStopSeconds = 1;
#endif

// This process's CPU seconds: its server's jobs and the test's own polling.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
const std::string kLargeSketch = R"({"type": "FeatureCollection", "exacity": {"seed": 5}, "features": [
  {"type": "Feature", "properties": {"zone": "residential"},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [3000, 0], [3000, 2000], [0, 2000], [0, 0]]]}},
  {"type": "Feature", "properties": {"zone": "commercial"},
   "geometry": {"type": "Polygon", "coordinates": [[[3000, 0], [4000, 0], [4000, 2000], [3000, 2000], [3000, 0]]]}},
  {"type": "Feature", "properties": {"road": "highway", "width": 16},
   "geometry": {"type": "LineString", "coordinates": [[-50, 1000], [4050, 1000]]}}]}
)";

// POST /api/cancel stops a generation inside its long stage, not at the next one: within a
// few seconds of a stage that takes far longer, its status "cancelled" with the stage named,
// and no city or staging folder left. With no job running it is refused.
TEST_F(ServeTest, CancelStopsAGenerationWithinItsStage) {
  auto idle = client->Post("/api/cancel", "", "application/json");
  EXPECT_EQ(idle->status, 409);
  EXPECT_EQ(idle->body, "no job is running: nothing to cancel");
  ASSERT_EQ(client->Put("/api/sketch", kLargeSketch, "application/geo+json")->status, 200);
  ASSERT_EQ(client->Post("/api/generate", "", "application/json")->status, 202);
  json status;
  for (int i = 0; i < 6000; ++i) {  // bounded: 10 minutes under the sanitizers
    status = json::parse(client->Get("/api/status")->body);
    if (status["stage"] == "lots" || status["state"] != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_EQ(status["stage"], "lots") << status.dump();
  const double asked = cpu_seconds();
  auto cancel = client->Post("/api/cancel", "", "application/json");
  ASSERT_EQ(cancel->status, 202) << cancel->body;
  const json ended = wait_for_job(*client);
  const double seconds = cpu_seconds() - asked;
  EXPECT_EQ(ended["state"], "cancelled") << ended.dump();
  EXPECT_EQ(ended["stage"], "lots");
  EXPECT_EQ(ended["error"].get<std::string>().rfind("cancelled during the lots stage", 0), 0) << ended.dump();
  // Uncancelled, the stage alone takes about twice the bound (kLargeSketch).
  EXPECT_LT(seconds, kStopSeconds);
  EXPECT_FALSE(fs::exists(work() / "city"));
  for (const auto& entry : fs::directory_iterator(work()))
    EXPECT_EQ(entry.path().filename().string().find(".city.partial"), std::string::npos) << entry.path();
  EXPECT_EQ(client->Post("/api/cancel", "", "application/json")->status, 409);
}

// A render far too long to wait for, cancelled: the job ends "cancelled" within the bound
// a generation's stage has (the tracer checks the flag at every pixel, the denoiser at every
// row), the still from before stays, and nothing is left aside. A render past the server's
// cap is refused, saying so; stopping the server stops a render as quickly.
TEST_F(ServeTest, CancelStopsARenderAndKeepsThePreviousStill) {
  put_small_and_generate();
  ASSERT_EQ(client->Post("/api/render", R"({"size": "32x24", "spp": 1})", "application/json")->status, 202);
  ASSERT_EQ(wait_for_job(*client)["state"], "done");
  const std::string still = client->Get("/api/render/still.png")->body;
  ASSERT_EQ(still.substr(1, 3), "PNG");

  auto refused = client->Post("/api/render", R"({"size": "4096x4096", "spp": 4096})", "application/json");
  EXPECT_EQ(refused->status, 400);
  EXPECT_NE(refused->body.find("is 68719476736 samples; this server renders at most 268435456 (exacity serve "
                               "--max-render)"),
            std::string::npos)
      << refused->body;
  EXPECT_EQ(json::parse(client->Get("/api/status")->body)["job"], "render");  // the one before: none started

  // At the cap: a tile of 16x16 pixels is a million samples.
  const std::string big = R"({"size": "256x256", "spp": 4096})";
  auto wait_for_tracing = [&] {
    json status;
    for (int i = 0; i < 600; ++i) {  // bounded: a minute
      status = json::parse(client->Get("/api/status")->body);
      if (status["stage"] == "render" || status["state"] != "running") break;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    // A moment into the tracing, past the scene.
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    return status;
  };
  ASSERT_EQ(client->Post("/api/render", big, "application/json")->status, 202);
  ASSERT_EQ(wait_for_tracing()["stage"], "render");
  double asked = cpu_seconds();
  ASSERT_EQ(client->Post("/api/cancel", "", "application/json")->status, 202);
  const json ended = wait_for_job(*client);
  EXPECT_LT(cpu_seconds() - asked, kStopSeconds);
  EXPECT_EQ(ended["state"], "cancelled") << ended.dump();
  EXPECT_EQ(ended["error"].get<std::string>().rfind("cancelled during the render stage", 0), 0) << ended.dump();
  EXPECT_EQ(client->Get("/api/render/still.png")->body, still);
  EXPECT_FALSE(fs::exists(work() / ".render.partial"));
  // The event stream says so too: its first event is the status as it is.
  std::string first;
  httplib::Client events("127.0.0.1", port);
  events.set_bearer_token_auth(kToken.c_str());
  events.Get("/api/events", [&](const char* data, std::size_t n) {
    first.append(data, n);
    return first.find("\n\n") == std::string::npos;
  });
  EXPECT_NE(first.find("event: state\n"), std::string::npos) << first;
  EXPECT_NE(first.find("\"state\":\"cancelled\""), std::string::npos) << first;

  ASSERT_EQ(client->Post("/api/render", big, "application/json")->status, 202);
  ASSERT_EQ(wait_for_tracing()["stage"], "render");
  asked = cpu_seconds();
  server->stop();
  server->finish_jobs();
  EXPECT_LT(cpu_seconds() - asked, kStopSeconds);
  EXPECT_EQ(read(work() / "render" / "still.png"), still);
}

// Each step of a render stops once its job is cancelled rather than running to its end:
// the scene's build (Embree's commit included), the tracer, the primary layer and the
// denoiser throw Cancelled when the flag is set (generate/cancel.h).
TEST(RenderCancelTest, EveryStepStopsOnceCancelled) {
  const exacity::Sketch sketch = exacity::parse_sketch(kSmallSketch, "small.geojson");
  exacity::StageClock clock([](int, int, const std::string&) {}, exacity::kCityStages);
  const exacity::City city = exacity::build_city(sketch, clock);
  const render::Sky sky(200, 40, 3);
  const render::SceneOptions options;
  const render::RenderScene scene(city, sky.sun_direction(), options);
  const render::Camera camera = scene.to_scene(render::default_camera(city));
  const render::TraceSettings settings{32, 24, 2};
  const render::Image image = render::trace(scene, sky, camera, settings);
  std::atomic<bool> cancelled{true};
  const exacity::CancelScope scope(cancelled);
  EXPECT_THROW({ const render::RenderScene again(city, sky.sun_direction(), options); }, exacity::Cancelled);
  EXPECT_THROW(render::trace(scene, sky, camera, settings), exacity::Cancelled);
  EXPECT_THROW(render::primary_layer(scene, sky, camera, 32, 24, 2, 4), exacity::Cancelled);
  EXPECT_THROW(render::denoise(image), exacity::Cancelled);
}

// A connection to the server's port as a slow client makes one; -1 when none.
int connect_raw(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) return close(fd), -1;
  return fd;
}

// Whether the server ends the connection within 10 s (an end or a reset, not a timeout).
bool closed_by_server(int fd) {
  timeval wait{10, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &wait, sizeof wait);
  char bytes[512];
  ssize_t n;
  while ((n = recv(fd, bytes, sizeof bytes, 0)) > 0) {
  }
  return n == 0 || errno == ECONNRESET;
}

// Thirty-two connections sending a header line every half second, and one sending its body
// as slowly: the API answers meanwhile, and each is closed by its deadline (2 s in these
// tests), which a read timeout alone, restarting with every line, never reaches.
TEST_F(ServeTest, SlowClientsDoNotHoldTheServer) {
  std::vector<int> slow;
  for (int i = 0; i < 32; ++i) {
    const int fd = connect_raw(port);
    ASSERT_GE(fd, 0);
    const std::string start = "GET /api/status HTTP/1.1\r\n";
    send(fd, start.data(), start.size(), MSG_NOSIGNAL);
    slow.push_back(fd);
  }
  const int body = connect_raw(port);
  ASSERT_GE(body, 0);
  const std::string headers = "PUT /api/sketch HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                              "\r\nAuthorization: Bearer " + kToken +
                              "\r\nContent-Type: application/geo+json\r\nContent-Length: 100000\r\n\r\n{";
  send(body, headers.data(), headers.size(), MSG_NOSIGNAL);
  std::atomic<bool> done{false};
  std::thread trickle([&] {
    for (int round = 0; round < 60 && !done; ++round) {  // 30 s at most
      for (int fd : slow) send(fd, "X-Slow: 1\r\n", 11, MSG_NOSIGNAL);
      send(body, " ", 1, MSG_NOSIGNAL);
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // every thread taken
  httplib::Client c("127.0.0.1", port);
  c.set_bearer_token_auth(kToken.c_str());
  c.set_connection_timeout(5);
  c.set_read_timeout(5);
  auto r = c.Get("/api/status");
  EXPECT_TRUE(r && r->status == 200) << (r ? r->body : httplib::to_string(r.error()));
  for (int fd : slow) EXPECT_TRUE(closed_by_server(fd));
  EXPECT_TRUE(closed_by_server(body));
  done = true;
  trickle.join();
  for (int fd : slow) close(fd);
  close(body);
  EXPECT_FALSE(fs::exists(sketch_file()));  // nothing was stored from the half-sent sketch
}

// A client address holds a bounded number of connections: past it, its connection waiting
// longest for a request is closed, or the new one is not taken when all are being
// answered; others are not held back. With every thread taken, the connection waiting
// longest anywhere goes.
TEST(ConnectionTableTest, CapsClientsAndDropsTheLongestWaiting) {
  auto pair = [] {
    int fds[2];
    EXPECT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0);
    return std::pair<int, int>{fds[0], fds[1]};
  };
  auto ended = [](int fd) {
    char byte;
    return recv(fd, &byte, 1, MSG_DONTWAIT) == 0;
  };
  exacity::serve::ConnectionTable table(2);
  const auto a = pair(), b = pair(), c = pair(), d = pair();
  ASSERT_TRUE(table.open(a.first, "10.0.0.1"));
  table.answering(a.first);
  ASSERT_TRUE(table.open(b.first, "10.0.0.1"));
  EXPECT_FALSE(ended(b.second));
  ASSERT_TRUE(table.open(c.first, "10.0.0.1"));  // b, waiting, is dropped for it
  EXPECT_TRUE(ended(b.second));
  EXPECT_FALSE(ended(a.second));
  table.close(b.first);
  table.answering(c.first);
  EXPECT_FALSE(table.open(d.first, "10.0.0.1"));  // both answering
  EXPECT_TRUE(table.open(d.first, "10.0.0.2"));
  table.waiting(a.first);  // after d began waiting: d has waited longest
  EXPECT_TRUE(table.drop_one());
  EXPECT_TRUE(ended(d.second));
  EXPECT_FALSE(ended(a.second));
  EXPECT_TRUE(table.drop_one());
  EXPECT_TRUE(ended(a.second));
  EXPECT_FALSE(table.drop_one());  // c is being answered
  for (const auto& p : {a, b, c, d}) close(p.first), close(p.second);
}

// Only this server's own page drives it: another Host (DNS rebinding), no token, a write
// from another origin and a body of the wrong type are refused before anything happens.
TEST_F(ServeTest, OnlyThisServersOwnPageMayDriveIt) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  const std::string here = "127.0.0.1:" + std::to_string(port);
  for (const std::string& host : {std::string("attacker.example:") + std::to_string(port),
                                  std::string("attacker.example"), std::string("127.0.0.1:1"),
                                  std::string("127.0.0.2:") + std::to_string(port)}) {
    auto r = client->Get("/api/sketch", {{"Host", host}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 403) << host;
    EXPECT_NE(r->body.find("is not this server's"), std::string::npos) << r->body;
    EXPECT_EQ(client->Post("/api/generate", {{"Host", host}}, "", "application/json")->status, 403) << host;
  }
  for (const std::string& host : {"localhost:" + std::to_string(port), here, "[::1]:" + std::to_string(port)})
    EXPECT_EQ(client->Get("/api/status", {{"Host", host}})->status, 200) << host;

  httplib::Client stranger("127.0.0.1", port);
  for (const char* path : {"/", "/api/sketch", "/api/status", "/lib/app.js"})
    EXPECT_EQ(stranger.Get(path)->status, 403) << path;
  EXPECT_EQ(stranger.Get("/api/status", {{"Authorization", "Bearer wrong"}})->status, 403);
  EXPECT_EQ(stranger.Get("/api/status?token=wrong")->status, 403);
  // The page's address: its token becomes a cookie for this port's pages only, which is
  // then enough.
  auto page = stranger.Get(("/?token=" + kToken).c_str());
  ASSERT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Set-Cookie"),
            "exacity_token_" + std::to_string(port) + "=" + kToken + "; Path=/; SameSite=Strict; HttpOnly");
  EXPECT_EQ(
      stranger.Get("/api/status", {{"Cookie", "other=1; exacity_token_" + std::to_string(port) + "=" + kToken}})
          ->status,
      200);

  // Cross-origin simple requests: a text/plain render, a form generate; Sec-Fetch-Site.
  const httplib::Headers evil{{"Origin", "http://evil"}};
  EXPECT_EQ(client->Post("/api/render", evil, R"({"size": "32x24", "spp": 1})", "text/plain")->status, 403);
  EXPECT_EQ(client->Post("/api/generate", evil, "a=1", "application/x-www-form-urlencoded")->status, 403);
  EXPECT_EQ(client->Post("/api/generate", evil, "", "application/json")->status, 403);
  EXPECT_EQ(client->Post("/api/generate", {{"Sec-Fetch-Site", "cross-site"}}, "", "application/json")->status, 403);
  EXPECT_EQ(client->Put("/api/sketch", {{"Origin", "http://" + here + ".evil"}}, kSmallSketch, "application/geo+json")
                ->status,
            403);
  // From the page itself, as a browser says it: taken.
  const httplib::Headers own{{"Origin", "http://" + here}, {"Sec-Fetch-Site", "same-origin"}};
  EXPECT_EQ(client->Post("/api/cancel", own, "", "application/json")->status, 409);  // nothing runs
  EXPECT_EQ(client->Put("/api/sketch", own, kSmallSketch, "application/geo+json")->status, 200);

  // JSON routes take JSON: a sketch of 8.4 KB sent as a form is refused for its type.
  std::string padded = kSmallSketch;
  padded.insert(padded.size() - 2, std::string(8600 - padded.size(), ' '));
  auto form = client->Put("/api/sketch", padded, "application/x-www-form-urlencoded");
  EXPECT_EQ(form->status, 415);
  EXPECT_NE(form->body.find("Content-Type: application/geo+json"), std::string::npos) << form->body;
  EXPECT_EQ(client->Put("/api/sketch", padded, "text/plain")->status, 415);
  EXPECT_EQ(client->Put("/api/sketch", padded, "application/geo+json; charset=utf-8")->status, 200);
  EXPECT_EQ(client->Post("/api/render", R"({"size": "32x24", "spp": 1})", "text/plain")->status, 415);
  EXPECT_EQ(client->Post("/api/generate", "a=1", "application/x-www-form-urlencoded")->status, 415);
  EXPECT_EQ(client->Put("/api/heightmap", "x", "text/plain")->status, 415);
  EXPECT_EQ(json::parse(client->Get("/api/status")->body)["state"], "idle");
}

// Names are given as they are: a percent-encoded one (in a sketch's heightmap, in an
// upload) or one with a control character is refused, not taken literally; messages name
// files from the work folder, not by the server's path to it.
TEST_F(ServeTest, EncodedAndControlCharacterNamesAreRefused) {
  ASSERT_EQ(client->Put("/api/sketch", kSmallSketch, "application/geo+json")->status, 200);
  fs::create_directories(work() / "%2e%2e");
  write_heightmap(work() / "%2e%2e" / "valley.png");
  auto encoded = client->Put(
      "/api/sketch",
      sketch_with(R"({"seed": 3, "terrain": {"bounds": [0, 0, 600, 300], "height": [0, 50], "heightmap": "%2e%2e/valley.png"}})"),
      "application/geo+json");
  EXPECT_EQ(encoded->status, 400);
  EXPECT_NE(encoded->body.find("percent-encoded"), std::string::npos) << encoded->body;
  EXPECT_EQ(encoded->body.rfind("sketch.geojson: ", 0), 0) << encoded->body;
  const std::string manifest = R"({"models": [{"file": "house_l.obj", "zones": ["residential"], "up": "z"}]})";
  const std::string obj = read(cli_util::kSource / "examples" / "models" / "house_l.obj");
  for (const std::string& name : {std::string("%2e%2e/evil5.obj"), std::string("sub/%2E%2e/evil5.obj"),
                                 std::string("evil\x01.obj"), std::string("evil\x7f.obj")}) {
    // A good library, and one more file under that name.
    auto r = client->Post("/api/models", httplib::MultipartFormDataItems{{"file", manifest, "lib.json", ""},
                                                                         {"file", obj, "house_l.obj", ""},
                                                                         {"file", obj, name, ""}});
    EXPECT_EQ(r->status, 400) << name;
    EXPECT_NE(r->body.find("the model library upload: the file name"), std::string::npos) << r->body;
    EXPECT_EQ(r->body.find('\n'), std::string::npos) << r->body;
  }
  EXPECT_FALSE(fs::exists(work() / "models"));
  auto bad = client->Put("/api/sketch", sketch_with(R"({"seed": 3, "zones": {"residential": {"layout": "spiral"}}})"),
                         "application/geo+json");
  EXPECT_EQ(bad->status, 400);
  EXPECT_EQ(bad->body.rfind("sketch.geojson: ", 0), 0) << bad->body;
  EXPECT_EQ(bad->body.find(work().string()), std::string::npos) << bad->body;
}

// `exacity serve ARGS` as a child process, its stdout and stderr into `log`.
pid_t start_program(const std::vector<std::string>& args, const fs::path& log) {
  // Everything the child needs is made before fork: between fork and exec a child of a
  // threaded process may only make async-signal-safe calls (no malloc, no stdio).
  std::vector<char*> argv{const_cast<char*>(EXACITY_BINARY)};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string log_file = log.string();
  const pid_t pid = fork();
  if (pid == 0) {
    const int out = open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, STDOUT_FILENO);
    dup2(out, STDERR_FILENO);
    execv(EXACITY_BINARY, argv.data());
    _exit(127);
  }
  return pid;
}

// The token in the address the program printed (served_port has waited for it).
std::string served_token(const fs::path& log) {
  const std::string text = read(log);
  const auto at = text.find("?token=");
  return at == std::string::npos ? "" : text.substr(at + 7, text.find(' ', at) - at - 7);
}

// The port the program says it serves on; 0 when it has not said so within 30 s. The line
// counts once whole: read while the program writes it, it may end inside the port or token.
int served_port(const fs::path& log) {
  for (int i = 0; i < 300; ++i) {
    const std::string text = read(log);
    const auto at = text.find("serving http://127.0.0.1:");
    if (at != std::string::npos && text.find('\n', at) != std::string::npos) return std::atoi(text.c_str() + at + 25);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return 0;
}

// A client of the program that logs to `log`, serving on `port`, with the token it printed.
httplib::Client served_client(int port, const fs::path& log) {
  httplib::Client c("127.0.0.1", port);
  c.set_bearer_token_auth(served_token(log).c_str());
  return c;
}

// A child's CPU seconds so far, from /proc (utime and stime, fields 14 and 15).
double cpu_seconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream fields(stat.substr(stat.rfind(')') + 2));  // after the command's name, which may hold spaces
  std::string field;
  long ticks = 0;
  for (int i = 3; i <= 15 && fields >> field; ++i)
    if (i >= 14) ticks += std::stol(field);
  return static_cast<double>(ticks) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

int exit_code(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(ServeCommandTest, ImportsTheSketchWithItsHeightmapAndStopsOnSigterm) {
  const fs::path dir = testing_util::temp_dir("serve_command");
  fs::copy_file(cli_util::kSource / "examples" / "valley.png", dir / "hills.png");
  write(dir / "in.geojson", sketch_with(R"({"seed": 3, "terrain": {"heightmap": "hills.png", "bounds": [0, 0, 600, 300],
                                            "height": [0, 40]}})"));
  const pid_t pid = start_program(
      {"serve", (dir / "in.geojson").string(), "--port", "0", "--work", (dir / "work").string()}, dir / "log.txt");
  const int port = served_port(dir / "log.txt");
  ASSERT_GT(port, 0) << read(dir / "log.txt");
  httplib::Client c = served_client(port, dir / "log.txt");
  const json sketch = json::parse(c.Get("/api/sketch")->body);
  EXPECT_EQ(sketch["exacity"]["terrain"]["heightmap"], "heightmap.png");
  EXPECT_EQ(read(dir / "work" / "heightmap.png"), read(dir / "hills.png"));
  EXPECT_EQ(c.Get("/api/heightmap.png")->status, 200);
  kill(pid, SIGTERM);
  EXPECT_EQ(exit_code(pid), 128 + SIGTERM) << read(dir / "log.txt");
}

TEST(ServeCommandTest, ImportsAModelLibrary) {
  const fs::path dir = testing_util::temp_dir("serve_command_models");
  const pid_t pid = start_program({"serve", (cli_util::kSource / "examples" / "hillside.geojson").string(), "--port",
                                   "0", "--work", (dir / "work").string()},
                                  dir / "log.txt");
  const int port = served_port(dir / "log.txt");
  ASSERT_GT(port, 0) << read(dir / "log.txt");
  httplib::Client c = served_client(port, dir / "log.txt");
  EXPECT_EQ(json::parse(c.Get("/api/sketch")->body)["exacity"]["models"], "models/library.json");
  for (const char* name : {"library.json", "house_gabled.obj", "library.mtl", "street_lamp.obj"})
    EXPECT_TRUE(fs::is_regular_file(dir / "work" / "models" / name)) << name;
  kill(pid, SIGTERM);
  EXPECT_EQ(exit_code(pid), 128 + SIGTERM) << read(dir / "log.txt");
}

TEST(ServeCommandTest, ImportsAModelLibrarysTextures) {
  // The texture an .mtl names comes along with it, at its place below the manifest.
  const fs::path dir = testing_util::temp_dir("serve_command_textures");
  fs::create_directories(dir / "lib" / "textures");
  write(dir / "lib" / "library.json", R"({"models": [{"file": "box.obj", "zones": ["residential"], "up": "z"}]})");
  write(dir / "lib" / "box.obj",
        "mtllib box.mtl\nv 0 0 0\nv 8 0 0\nv 0 8 0\nv 0 0 6\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl skin\n"
        "f 1/1 3/3 2/2\nf 1/1 2/2 4/3\nf 1/1 4/3 3/2\nf 2/1 3/2 4/3\n");
  write(dir / "lib" / "box.mtl", "newmtl skin\nmap_Kd textures/skin.png\n");
  fs::copy_file(cli_util::kSource / "examples" / "valley.png", dir / "lib" / "textures" / "skin.png");
  write(dir / "sketch.geojson",
        R"({"type": "FeatureCollection", "exacity": {"models": "lib/library.json"}, "features": [
    {"type": "Feature", "properties": {"zone": "residential"},
     "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [300, 0], [300, 300], [0, 300], [0, 0]]]}}]})");
  const pid_t pid = start_program(
      {"serve", (dir / "sketch.geojson").string(), "--port", "0", "--work", (dir / "work").string()}, dir / "log.txt");
  const int port = served_port(dir / "log.txt");
  ASSERT_GT(port, 0) << read(dir / "log.txt");
  ASSERT_TRUE(fs::is_regular_file(dir / "work" / "models" / "textures" / "skin.png"));
  EXPECT_TRUE(read(dir / "work" / "models" / "textures" / "skin.png") == read(dir / "lib" / "textures" / "skin.png"));
  kill(pid, SIGTERM);
  EXPECT_EQ(exit_code(pid), 128 + SIGTERM) << read(dir / "log.txt");
}

// A sketch's "like" comes along into work/like, a shapefile's companions with it.
TEST(ServeCommandTest, ImportsThePlaceItLooksLike) {
  const fs::path dir = testing_util::temp_dir("serve_command_like");
  fs::create_directories(dir / "places");
  for (const char* extension : {".shp", ".shx", ".dbf", ".prj"}) write(dir / "places" / (std::string("town") + extension), extension);
  write(dir / "in.geojson", sketch_with(R"({"seed": 3, "like": "places/town.shp"})"));
  const pid_t pid = start_program(
      {"serve", (dir / "in.geojson").string(), "--port", "0", "--work", (dir / "work").string()}, dir / "log.txt");
  const int port = served_port(dir / "log.txt");
  ASSERT_GT(port, 0) << read(dir / "log.txt");
  httplib::Client c = served_client(port, dir / "log.txt");
  EXPECT_EQ(json::parse(c.Get("/api/sketch")->body)["exacity"]["like"], "like/town.shp");
  for (const char* extension : {".shp", ".shx", ".dbf", ".prj"})
    EXPECT_EQ(read(dir / "work" / "like" / (std::string("town") + extension)), extension);
  kill(pid, SIGTERM);
  EXPECT_EQ(exit_code(pid), 128 + SIGTERM) << read(dir / "log.txt");
}

// Ctrl-C during a large city's lots stage ends the program within seconds, not at the end
// of the stage, with 130 and no city or staging folder left.
TEST(ServeCommandTest, InterruptStopsAGenerationWithinItsStage) {
  const fs::path dir = testing_util::temp_dir("serve_command_interrupt");
  const pid_t pid = start_program({"serve", "--port", "0", "--work", (dir / "work").string()}, dir / "log.txt");
  const int port = served_port(dir / "log.txt");
  ASSERT_GT(port, 0) << read(dir / "log.txt");
  httplib::Client c = served_client(port, dir / "log.txt");
  ASSERT_EQ(c.Put("/api/sketch", kLargeSketch, "application/geo+json")->status, 200);
  ASSERT_EQ(c.Post("/api/generate", "", "application/json")->status, 202);
  json status;
  for (int i = 0; i < 6000; ++i) {  // bounded: 10 minutes under the sanitizers
    status = json::parse(c.Get("/api/status")->body);
    if (status["stage"] == "lots" || status["state"] != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_EQ(status["stage"], "lots") << status.dump();
  const double asked = cpu_seconds(pid);
  kill(pid, SIGINT);
  rusage used{};
  int wait_status = 0;
  ASSERT_EQ(wait4(pid, &wait_status, 0, &used), pid);
  EXPECT_TRUE(WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 128 + SIGINT) << wait_status << read(dir / "log.txt");
  // As for POST /api/cancel (CancelStopsAGenerationWithinItsStage), in the child's CPU seconds.
  const double seconds = used.ru_utime.tv_sec + used.ru_stime.tv_sec + 1e-6 * (used.ru_utime.tv_usec + used.ru_stime.tv_usec) - asked;
  EXPECT_LT(seconds, kStopSeconds);
  EXPECT_FALSE(fs::exists(dir / "work" / "city"));
  for (const auto& entry : fs::directory_iterator(dir / "work"))
    EXPECT_EQ(entry.path().filename().string().find(".city.partial"), std::string::npos) << entry.path();
}

TEST(ServeCommandTest, RefusesABadSketchAndABusyPort) {
  const fs::path dir = testing_util::temp_dir("serve_command_bad");
  write(dir / "bad.geojson", R"({"type": "FeatureCollection", "features": []})");
  auto bad = cli_util::run("serve " + (dir / "bad.geojson").string() + " --port 0 --work " + (dir / "work").string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.out.find("exacity: error: " + cli_message(read(dir / "bad.geojson"), dir / "bad.geojson")),
            std::string::npos)
      << bad.out;
  // A port in use is named, and the program stops.
  const pid_t first = start_program({"serve", "--port", "0", "--work", (dir / "work").string()}, dir / "log.txt");
  const int port = served_port(dir / "log.txt");
  ASSERT_GT(port, 0) << read(dir / "log.txt");
  // Bounded: a server that took the port anyway would otherwise serve on.
  auto busy = cli_util::shell("timeout 30 " + std::string(EXACITY_BINARY) + " serve --port " + std::to_string(port) +
                              " --work " + (dir / "work2").string());
  EXPECT_EQ(busy.code, 2) << busy.out;
  EXPECT_NE(busy.out.find("cannot listen on 127.0.0.1:" + std::to_string(port)), std::string::npos) << busy.out;
  kill(first, SIGTERM);
  EXPECT_EQ(exit_code(first), 128 + SIGTERM);
}

// A job that has answered is stopped for the next one asked to replace it (exacity serve's
// generation after an edit); one that has not is not, and a plain start is refused.
TEST(JobRunnerTest, AnAnsweredJobIsReplacedByTheNext) {
  JobRunner runner;
  std::atomic<bool> answer{false};
  auto validating = [&answer](JobRunner::Progress& p) {
    p.stage(1, 2, "tiles");
    while (!answer) p.stage(1, 2, "tiles"), std::this_thread::sleep_for(std::chrono::milliseconds(1));
    p.answered();
    for (;;) p.stage(2, 2, "validation"), std::this_thread::sleep_for(std::chrono::milliseconds(1));
  };
  ASSERT_TRUE(runner.start("generate", validating));
  const auto replace = JobRunner::WhileRunning::ReplaceAnswered;
  EXPECT_FALSE(runner.start("generate", [](JobRunner::Progress&) {}, replace));  // not answered yet
  EXPECT_FALSE(runner.status().answered);
  answer = true;
  for (int i = 0; i < 1000 && runner.status().stage != "validation"; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(runner.status().answered);
  EXPECT_EQ(runner.status().to_json()["answered"], true);
  EXPECT_FALSE(runner.start("render", [](JobRunner::Progress&) {}));
  std::atomic<bool> second_ran{false};
  ASSERT_TRUE(runner.start("generate", [&](JobRunner::Progress&) { second_ran = true; }, replace));
  for (int i = 0; i < 1000 && runner.status().state == JobState::Running; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(second_ran);
  EXPECT_EQ(runner.status().state, JobState::Done);
  EXPECT_FALSE(runner.status().answered);
  std::vector<std::string> seen;
  for (const auto& e : runner.events_after(0, std::chrono::milliseconds(0)))
    if (e.name != "stage") seen.push_back(e.name + " " + e.data.value("state", std::string()));
  EXPECT_EQ(seen, (std::vector<std::string>{"state running", "answered ", "state cancelled", "state running", "state done"}));
  for (const auto& e : runner.events_after(0, std::chrono::milliseconds(0)))
    if (e.name == "state" && e.data["state"] == "cancelled") {
      EXPECT_EQ(e.data["error"], "stopped during the validation stage after its answer: the next generate replaces its city");
    }
}

TEST(JobRunnerTest, OneJobAtATimeReportedAndCancellable) {
  JobRunner runner;
  std::promise<void> go;
  std::shared_future<void> released = go.get_future().share();
  ASSERT_TRUE(runner.start("generate", [released](JobRunner::Progress& p) {
    p.stage(1, 2, "terrain");
    released.wait();
    for (int i = 0; i < 100000; ++i) {
      p.stage(2, 2, "roads");
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }));
  EXPECT_FALSE(runner.start("render", [](JobRunner::Progress&) {}));
  EXPECT_EQ(runner.status().state, JobState::Running);
  EXPECT_EQ(runner.status().job, "generate");
  for (int i = 0; i < 1000 && runner.status().stage != "terrain"; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  runner.cancel();
  go.set_value();
  for (int i = 0; i < 1000 && runner.status().state == JobState::Running; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(runner.status().state, JobState::Cancelled);
  EXPECT_EQ(runner.status().to_json()["state"], "cancelled");
  EXPECT_EQ(runner.status().error.rfind("cancelled during the terrain stage", 0), 0) << runner.status().error;
  EXPECT_FALSE(runner.cancel());  // nothing runs now
  bool saw_stage = false;
  for (const auto& e : runner.events_after(0, std::chrono::milliseconds(0)))
    saw_stage |= e.name == "stage" && e.data["stage"] == "terrain";
  EXPECT_TRUE(saw_stage);
  // A job that throws fails with its message; the next one may start.
  ASSERT_TRUE(runner.start("render", [](JobRunner::Progress&) { throw exacity::UserError("bad camera"); }));
  for (int i = 0; i < 1000 && runner.status().state == JobState::Running; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(runner.status().state, JobState::Failed);
  EXPECT_EQ(runner.status().to_json()["error"], "bad camera");
}

}  // namespace
