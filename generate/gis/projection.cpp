#include "generate/gis/projection.h"

#include <cmath>
#include <memory>
#include <regex>
#include <vector>

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "generate/errors.h"

namespace exacity {
namespace {

using nlohmann::ordered_json;

OGRSpatialReference lon_lat() {
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = longitude, as GeoJSON and OSM write
  return srs;
}

OGRSpatialReference from_epsg(int epsg) {
  OGRSpatialReference srs;
  if (srs.importFromEPSG(epsg) != OGRERR_NONE) throw UserError("EPSG:" + std::to_string(epsg) + " is not a CRS PROJ knows");
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return srs;
}

// Calls f on every [x, y] position of a GeoJSON geometry's coordinates.
template <typename F>
void for_each_position(ordered_json& coords, F&& f) {
  if (!coords.is_array() || coords.empty()) return;
  if (coords[0].is_number()) {
    if (coords.size() >= 2 && coords[1].is_number()) f(coords);
    return;
  }
  for (ordered_json& c : coords) for_each_position(c, f);
}

// Every position of the document's features, and its images' bounds as corner pairs.
template <typename F>
void for_each_point(ordered_json& doc, F&& f) {
  if (doc.contains("features") && doc["features"].is_array())
    for (ordered_json& feature : doc["features"])
      if (feature.is_object() && feature.contains("geometry") && feature["geometry"].is_object() &&
          feature["geometry"].contains("coordinates"))
        for_each_position(feature["geometry"]["coordinates"], f);
}

// The bounds [min_x, min_y, max_x, max_y] of a terrain or channel, projected: the box
// around its four corners (an image in lon/lat is not quite a rectangle in metres).
void project_bounds(ordered_json& owner, OGRCoordinateTransformation& t) {
  if (!owner.is_object() || !owner.contains("bounds")) return;
  ordered_json& b = owner["bounds"];
  if (!b.is_array() || b.size() != 4 || !std::all_of(b.begin(), b.end(), [](const auto& v) { return v.is_number(); })) return;
  double xs[4] = {b[0], b[2], b[2], b[0]}, ys[4] = {b[1], b[1], b[3], b[3]};
  if (!t.Transform(4, xs, ys)) return;  // the sketch reader reports what is wrong with them
  b = {*std::min_element(xs, xs + 4), *std::min_element(ys, ys + 4), *std::max_element(xs, xs + 4),
       *std::max_element(ys, ys + 4)};
}

// The CRS a GeoJSON "crs" member names: {"type": "name", "properties": {"name": N}}, or the
// 2008 form {"type": "EPSG", "properties": {"code": C}}; empty for anything else.
std::string crs_name(const ordered_json& crs) {
  if (!crs.is_object() || !crs.contains("properties") || !crs["properties"].is_object()) return "";
  const ordered_json& p = crs["properties"];
  if (p.contains("name") && p["name"].is_string()) return p["name"].get<std::string>();
  if (crs.value("type", "") == "EPSG" && p.contains("code") && p["code"].is_number_integer())
    return "EPSG:" + std::to_string(p["code"].get<int>());
  return "";
}

}  // namespace

void start_gdal() {
  static const bool started = [] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
    return true;
  }();
  (void)started;
}

ordered_json crs_member(int epsg) {
  return {{"type", "name"}, {"properties", {{"name", "urn:ogc:def:crs:EPSG::" + std::to_string(epsg)}}}};
}

std::optional<int> epsg_of(const ordered_json& crs) {
  if (crs.is_null()) return std::nullopt;
  std::smatch m;
  const std::string text = crs_name(crs);
  if (std::regex_search(text, m, std::regex("EPSG:+([0-9]+)"))) return std::stoi(m[1].str());
  return std::nullopt;
}

int utm_epsg(double lon, double lat) {
  lon = std::fmod(std::fmod(lon + 180, 360) + 360, 360) - 180;  // into [-180, 180)
  const int zone = std::clamp(static_cast<int>(std::floor((lon + 180) / 6)) + 1, 1, 60);
  return (lat >= 0 ? 32600 : 32700) + zone;
}

bool project_to_metres(ordered_json& doc, const std::filesystem::path& path) {
  if (!doc.is_object()) return false;
  geom::Box box = geom::Box::none();
  for_each_point(doc, [&](const ordered_json& p) { box.add(geom::Vec2{p[0].get<double>(), p[1].get<double>()}); });
  if (box.min_x > box.max_x) return false;  // no positions: the sketch reader says so
  bool geographic = false;
  if (doc.contains("crs") && !doc["crs"].is_null()) {
    const ordered_json& crs = doc["crs"];
    const std::string name = crs_name(crs);
    OGRSpatialReference srs;
    if (name.empty() || srs.SetFromUserInput(name.c_str()) != OGRERR_NONE)
      throw UserError(path.string() + ": crs: " + crs.dump() +
                      " is not a CRS PROJ knows; name one like {\"type\": \"name\", \"properties\": {\"name\": \"EPSG:32633\"}}");
    geographic = srs.IsGeographic();
  } else {
    // GeoJSON's default is lon/lat; a sketch in metres spans more than a metre. Longitudes
    // past ±180 come from tools that draw across the antimeridian without splitting.
    geographic = box.width() < 1 && box.height() < 1 && box.min_x >= -360 && box.max_x <= 360 && box.min_y >= -90 &&
                 box.max_y <= 90;
  }
  if (!geographic) return false;
  if (box.min_y < -80 || box.max_y > 84)
    throw UserError(path.string() + ": the sketch lies in lon/lat beyond 80°S–84°N, where UTM does not reach; "
                    "project it to a polar CRS in metres first");
  OGRSpatialReference source;
  const std::string source_name = doc.contains("crs") && !doc["crs"].is_null() ? crs_name(doc["crs"]) : "EPSG:4326";
  source.SetFromUserInput(source_name.c_str());
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const int epsg = utm_epsg((box.min_x + box.max_x) / 2, (box.min_y + box.max_y) / 2);
  OGRSpatialReference target = from_epsg(epsg);
  std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&source, &target));
  if (!t) throw UserError(path.string() + ": PROJ cannot project " + source_name + " to EPSG:" + std::to_string(epsg));
  bool failed = false;
  for_each_point(doc, [&](ordered_json& p) {
    double x = p[0], y = p[1];
    if (!t->Transform(1, &x, &y)) failed = true;
    p[0] = x, p[1] = y;
  });
  if (failed) throw UserError(path.string() + ": a position could not be projected to EPSG:" + std::to_string(epsg) + "; check its coordinates");
  if (doc.contains("exacity") && doc["exacity"].is_object()) {
    ordered_json& ex = doc["exacity"];
    if (ex.contains("terrain")) project_bounds(ex["terrain"], *t);
    if (ex.contains("channels") && ex["channels"].is_object())
      for (auto& [name, channel] : ex["channels"].items()) project_bounds(channel, *t);
  }
  doc["crs"] = crs_member(epsg);
  return true;
}

ToLonLat::ToLonLat(int from) {
  OGRSpatialReference source = from_epsg(from), target = lon_lat();
  transform_ = OGRCreateCoordinateTransformation(&source, &target);
  if (!transform_) throw UserError("PROJ cannot project EPSG:" + std::to_string(from) + " to lon/lat");
}

ToLonLat::~ToLonLat() { OGRCoordinateTransformation::DestroyCT(static_cast<OGRCoordinateTransformation*>(transform_)); }

geom::Vec2 ToLonLat::operator()(geom::Vec2 p) const {
  static_cast<OGRCoordinateTransformation*>(transform_)->Transform(1, &p.x, &p.y);
  return p;
}

}  // namespace exacity
