#include "generate/gis/projection.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <regex>
#include <vector>

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <proj.h>

#include "generate/city/format_number.h"
#include "generate/errors.h"

namespace exacity {
namespace {

using nlohmann::ordered_json;
namespace fs = std::filesystem;

// Degrees: a sketch without a crs whose positions lie in lon/lat ranges and span less is
// in lon/lat (a sketch in metres this small could hold no block).
constexpr double kLonLatSpan = 30;
// How far from 1 a map's scale may be anywhere on the sketch: beyond it the city's metres
// are not the ground's (UTM's own error is 0.04% at its central meridian).
constexpr double kMaxScaleError = 0.01;

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

std::string fixed(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
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


// A CRS as PROJ sees it, for what OGR does not tell: its map's unit, method and scale.
class MapCrs {
 public:
  explicit MapCrs(const OGRSpatialReference& srs) : ctx_(proj_context_create()) {
    proj_log_level(ctx_, PJ_LOG_NONE);
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2_2019", nullptr};
    if (srs.exportToWkt(&wkt, options) == OGRERR_NONE && wkt) crs_ = proj_create(ctx_, wkt);
    CPLFree(wkt);
    // The map of a compound CRS (its first part; the other is heights) or of a bound one.
    while (crs_) {
      const PJ_TYPE type = proj_get_type(crs_);
      PJ* map = type == PJ_TYPE_COMPOUND_CRS ? proj_crs_get_sub_crs(ctx_, crs_, 0)
                : type == PJ_TYPE_BOUND_CRS  ? proj_get_source_crs(ctx_, crs_)
                                             : nullptr;
      if (!map) break;
      proj_destroy(crs_);
      crs_ = map;
    }
  }
  ~MapCrs() {
    proj_destroy(crs_);
    proj_context_destroy(ctx_);
  }
  MapCrs(const MapCrs&) = delete;
  MapCrs& operator=(const MapCrs&) = delete;

  bool projected() const { return crs_ && proj_get_type(crs_) == PJ_TYPE_PROJECTED_CRS; }

  // Metres in its unit of easting (0.3048006 for US survey feet).
  double unit() const {
    PJ* cs = proj_crs_get_coordinate_system(ctx_, crs_);
    double metres = 0;
    if (cs) proj_cs_get_axis_info(ctx_, cs, 0, nullptr, nullptr, nullptr, &metres, nullptr, nullptr, nullptr);
    proj_destroy(cs);
    return metres;
  }

  // Web Mercator's method (EPSG 1024), a sphere's Mercator on the ellipsoid's coordinates:
  // neither conformal nor true to scale anywhere but at the equator.
  bool web_mercator() const {
    PJ* conversion = proj_crs_get_coordoperation(ctx_, crs_);
    const char* code = nullptr;
    if (conversion) proj_coordoperation_get_method_info(ctx_, conversion, nullptr, nullptr, &code);
    const bool is = code && std::string(code) == "1024";
    proj_destroy(conversion);
    return is;
  }

  // How far from 1 its scale is at a point, along the meridian or the parallel, whichever
  // is farther; none where the map does not reach.
  std::optional<double> scale_error(geom::Vec2 lonlat) const {
    const PJ_FACTORS f =
        proj_factors(crs_, proj_coord(proj_torad(std::remainder(lonlat.x, 360.0)), proj_torad(lonlat.y), 0, 0));
    const bool failed = proj_errno(crs_) != 0;
    proj_errno_reset(crs_);
    if (failed || !(f.meridional_scale > 0) || !(f.parallel_scale > 0) || !std::isfinite(f.meridional_scale) ||
        !std::isfinite(f.parallel_scale))
      return std::nullopt;
    return std::max(std::abs(f.meridional_scale - 1), std::abs(f.parallel_scale - 1));
  }

 private:
  PJ_CONTEXT* ctx_;
  PJ* crs_ = nullptr;
};

// A document's features, each with its name for messages and its positions (in the
// document, to be projected in place).
struct FeaturePositions {
  std::string name;
  std::vector<ordered_json*> positions;
};

std::vector<FeaturePositions> features_of(ordered_json& doc, const fs::path& path) {
  std::vector<FeaturePositions> out;
  if (!doc.is_object() || !doc.contains("features") || !doc["features"].is_array()) return out;
  ordered_json& features = doc["features"];
  for (std::size_t i = 0; i < features.size(); ++i) {
    ordered_json& f = features[i];
    if (!f.is_object() || !f.contains("geometry") || !f["geometry"].is_object() || !f["geometry"].contains("coordinates"))
      continue;
    FeaturePositions feature;
    const bool sourced = f.contains("properties") && f["properties"].is_object() && f["properties"].contains("source") &&
                         f["properties"]["source"].is_string();
    feature.name = sourced ? f["properties"]["source"].get<std::string>()
                           : path.string() + " features[" + std::to_string(i) + "]";
    for_each_position(f["geometry"]["coordinates"], [&](ordered_json& p) { feature.positions.push_back(&p); });
    if (!feature.positions.empty()) out.push_back(std::move(feature));
  }
  return out;
}

// A feature in longitude and latitude (degrees), for the sketch's extent.
struct Place {
  const std::string* feature;
  std::vector<geom::Vec2> lonlat;
};

// Longitudes into [-180, 180), then those west of the widest arc of the circle that no
// position is in moved east by 360 degrees: a sketch crossing the antimeridian becomes one
// interval (179.99 to 180.01), any other stays as it was.
void unwrap(std::vector<Place>& places) {
  std::vector<double> lons;
  for (Place& place : places)
    for (geom::Vec2& p : place.lonlat) {
      p.x = std::remainder(p.x, 360.0);
      if (p.x >= 180) p.x -= 360;
      lons.push_back(p.x);
    }
  if (lons.empty()) return;
  std::sort(lons.begin(), lons.end());
  double widest = lons.front() + 360 - lons.back(), west_of = -181;  // the arc across ±180 first
  for (std::size_t i = 1; i < lons.size(); ++i)
    if (lons[i] - lons[i - 1] > widest) widest = lons[i] - lons[i - 1], west_of = lons[i - 1];
  for (Place& place : places)
    for (geom::Vec2& p : place.lonlat)
      if (p.x <= west_of) p.x += 360;
}

geom::Box box_of(const std::vector<Place>& places) {
  geom::Box box = geom::Box::none();
  for (const Place& place : places)
    for (geom::Vec2 p : place.lonlat) box.add(p);
  return box;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The place with the position farthest from the sketch's median position (`where`): a
// stray node or feature, when the sketch is too wide for one map.
std::size_t farthest(const std::vector<Place>& places, geom::Vec2& where) {
  std::vector<double> lons, lats;
  for (const Place& place : places)
    for (geom::Vec2 p : place.lonlat) lons.push_back(p.x), lats.push_back(p.y);
  const geom::Vec2 centre{median(lons), median(lats)};
  const double shrink = std::cos(centre.y * M_PI / 180);  // a degree of longitude there
  std::size_t far = 0;
  double farthest_distance = -1;
  for (std::size_t i = 0; i < places.size(); ++i)
    for (geom::Vec2 p : places[i].lonlat)
      if (const double d = std::hypot((p.x - centre.x) * shrink, p.y - centre.y); d > farthest_distance)
        farthest_distance = d, far = i, where = p;
  return far;
}

// Within longitude and latitude ranges; longitudes to ±360, as tools drawing across the
// antimeridian write them.
bool in_lon_lat_ranges(geom::Vec2 p) { return std::abs(p.x) <= 360 && std::abs(p.y) <= 90; }

std::vector<Place> raw_places(const std::vector<FeaturePositions>& features) {
  std::vector<Place> places;
  for (const FeaturePositions& f : features) {
    places.push_back({&f.name, {}});
    for (const ordered_json* p : f.positions) places.back().lonlat.push_back({(*p)[0].get<double>(), (*p)[1].get<double>()});
  }
  return places;
}

// A document without a crs is in lon/lat when every position is within lon/lat ranges
// (longitudes to ±360, as tools drawing across the antimeridian write them), not every
// coordinate is a whole number (a sketch in metres a few metres wide, as tests draw them;
// no place is drawn in whole degrees), and the positions span under kLonLatSpan degrees,
// or all but one feature's under a degree (a stray node, which the extent's check then
// names). One spanning more whose features are mostly under a unit across is lon/lat of
// places too far apart for one map (a sketch in metres has features metres across), and is
// refused; anything else is in metres.
bool looks_lon_lat(const std::vector<FeaturePositions>& features, const fs::path& path) {
  std::vector<Place> places = raw_places(features);
  bool whole = true;  // every coordinate a whole number: metres drawn by hand, however small
  for (const Place& place : places)
    for (geom::Vec2 p : place.lonlat) {
      if (!in_lon_lat_ranges(p)) return false;
      whole = whole && p.x == std::floor(p.x) && p.y == std::floor(p.y);
    }
  if (whole) return false;
  unwrap(places);
  const geom::Box box = box_of(places);
  if (box.width() < kLonLatSpan && box.height() < kLonLatSpan) return true;
  std::vector<double> sizes;  // each feature's extent, its width or height, whichever is more
  for (const Place& place : places) {
    const geom::Box own = box_of({place});
    sizes.push_back(std::max(own.width(), own.height()));
  }
  if (places.size() >= 2) {
    std::vector<Place> rest = places;
    geom::Vec2 where;
    rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(farthest(rest, where)));
    unwrap(rest);
    const geom::Box rest_box = box_of(rest);
    if (rest_box.width() < 1 && rest_box.height() < 1) return true;
  }
  if (median(sizes) >= 1) return false;
  throw UserError(path.string() + ": has no crs, and its coordinates lie within longitude and latitude ranges but span " +
                  fixed(box.width(), 1) + "° of longitude and " + fixed(box.height(), 1) +
                  "° of latitude, while its features are mostly under a degree across: places too far apart for one "
                  "map, or a CRS Exacity cannot guess; add a \"crs\" member naming its CRS, like {\"type\": \"name\", "
                  "\"properties\": {\"name\": \"EPSG:4326\"}} for longitude and latitude");
}

bool in_degrees(const OGRSpatialReference& crs) {
  return crs.IsGeographic() && std::abs(crs.GetAngularUnits() - M_PI / 180) < 1e-12;
}

// Tools that cut features at the antimeridian (ogr2ogr -wrapdateline, GeoJSON's
// recommendation) compute each part's crossing on its own: the halves of one polygon or
// road end at latitudes some 1e-10 degrees apart (tens of micrometres) and at longitude 180
// on one side, -180 on the other. Exactly, those are different points, and the city would
// have a seam of slivers and roads ending a hair short. Positions on the antimeridian whose
// latitudes are within kSeamTolerance of the next one's are made one point: the lowest
// latitude of their run, at longitude 180.
constexpr double kSeamTolerance = 1e-7;  // degrees of latitude, about a centimetre

void node_the_antimeridian(const std::vector<std::vector<FeaturePositions>>& features,
                           const std::vector<std::optional<OGRSpatialReference>>& crs) {
  std::vector<ordered_json*> seam;
  for (std::size_t i = 0; i < features.size(); ++i) {
    if (!crs[i] || !in_degrees(*crs[i])) continue;
    for (const FeaturePositions& f : features[i])
      for (ordered_json* p : f.positions)
        if (std::abs(std::abs((*p)[0].get<double>()) - 180) <= 1e-9) seam.push_back(p);
  }
  std::stable_sort(seam.begin(), seam.end(),
                   [](const ordered_json* a, const ordered_json* b) { return (*a)[1].get<double>() < (*b)[1].get<double>(); });
  double run_start = 0, previous = -1000;
  for (ordered_json* p : seam) {
    const double lat = (*p)[1].get<double>();
    if (lat - previous > kSeamTolerance) run_start = lat;
    previous = lat;
    (*p)[0] = 180.0, (*p)[1] = run_start;
  }
}

// The CRS a crs member names, as PROJ knows it.
OGRSpatialReference named_crs(const ordered_json& crs, const fs::path& path) {
  const std::string name = crs_name(crs);
  OGRSpatialReference srs;
  if (name.empty() || srs.SetFromUserInput(name.c_str()) != OGRERR_NONE)
    throw UserError(path.string() + ": crs: " + crs.dump() +
                    " is not a CRS PROJ knows; name one like {\"type\": \"name\", \"properties\": {\"name\": \"EPSG:32633\"}}");
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // GeoJSON's x is the easting or longitude
  return srs;
}

std::string crs_text(const OGRSpatialReference& srs) {
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (authority && code) return std::string(authority) + ":" + code;
  return srs.GetName() ? srs.GetName() : "its CRS";
}

// A projected coordinate to the nearest micrometre. The same place read from files in
// different CRSs (lon/lat, Web Mercator, feet) comes out of PROJ a few nanometres apart,
// and the city follows every bit of its sketch (lots and buildings draw from streams of
// their exact cells): rounded, it is one city. PROJ's transformations are good to a
// millimetre at best, so nothing is lost.
double to_micrometre(double v) { return std::round(v * 1e6) / 1e6; }

// Moves the positions (and the bounds of the settings' images) of one part from `from`
// to `to`, in place.
void transform_part(SketchPart& part, const std::vector<FeaturePositions>& features, const OGRSpatialReference& from,
                    const OGRSpatialReference& to) {
  std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&from, &to));
  if (!t)
    throw UserError(part.path.string() + ": PROJ cannot bring " + crs_text(from) + " to " + crs_text(to) + " (" +
                    CPLGetLastErrorMsg() + "); reproject the file with ogr2ogr -t_srs");
  for (const FeaturePositions& f : features)
    for (ordered_json* p : f.positions) {
      double x = (*p)[0], y = (*p)[1];
      if (!t->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y))
        throw UserError(f.name + ": position " + p->dump() + " could not be projected to " + crs_text(to) +
                        "; check its coordinates");
      (*p)[0] = to_micrometre(x), (*p)[1] = to_micrometre(y);
    }
  if (part.doc.contains("exacity") && part.doc["exacity"].is_object()) {
    ordered_json& ex = part.doc["exacity"];
    if (ex.contains("terrain")) project_bounds(ex["terrain"], *t);
    if (ex.contains("channels") && ex["channels"].is_object())
      for (auto& [name, channel] : ex["channels"].items()) project_bounds(channel, *t);
  }
}

// Every part's features in lon/lat, unwrapped, for the sketch's extent.
std::vector<Place> places_of(const std::vector<std::vector<FeaturePositions>>& features,
                             const std::vector<std::optional<OGRSpatialReference>>& crs,
                             const std::vector<SketchPart>& parts) {
  std::vector<Place> places;
  const OGRSpatialReference wgs84 = lon_lat();
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (!crs[i] || features[i].empty()) continue;
    std::vector<Place> part = raw_places(features[i]);
    // A geographic CRS's degrees are lon/lat enough for an extent, whatever its datum.
    if (in_degrees(*crs[i])) {
      for (const Place& place : part)
        for (geom::Vec2 p : place.lonlat)
          if (!in_lon_lat_ranges(p))
            throw UserError(*place.feature + ": position [" + format_number(p.x) + ", " + format_number(p.y) +
                            "] is no longitude and latitude, though " + parts[i].path.string() + "'s CRS, " +
                            crs_text(*crs[i]) +
                            ", counts in degrees: the file's CRS is wrong (ogr2ogr gives a GeoJSON without a crs "
                            "EPSG:4326); assign the right one with ogr2ogr -a_srs EPSG:<code>");
    } else {
      std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&*crs[i], &wgs84));
      if (!t)
        throw UserError(parts[i].path.string() + ": PROJ cannot bring " + crs_text(*crs[i]) +
                        " to longitude and latitude; reproject the file with ogr2ogr -t_srs");
      for (Place& place : part)
        for (geom::Vec2& p : place.lonlat)
          if (!t->Transform(1, &p.x, &p.y) || !std::isfinite(p.x) || !std::isfinite(p.y))
            throw UserError(*place.feature + ": a position lies outside the area of " + crs_text(*crs[i]) +
                            "; check its coordinates, or the file's CRS");
    }
    for (Place& place : part) places.push_back(std::move(place));
  }
  unwrap(places);
  return places;
}

// Refuses an extent that `map` does not hold true to scale within kMaxScaleError: checked
// at its corners, the middles of its sides and, where it spans the equator, the points
// there (where a transverse Mercator's error on the box is largest).
void expect_true_to_scale(const std::vector<Place>& places, const OGRSpatialReference& map,
                          const std::vector<SketchPart>& parts) {
  const geom::Box box = box_of(places);
  const MapCrs crs(map);
  const double mid_x = (box.min_x + box.max_x) / 2, mid_y = (box.min_y + box.max_y) / 2;
  const double equator = std::clamp(0.0, box.min_y, box.max_y);
  double worst = 0;
  bool unmapped = false;
  for (geom::Vec2 p : {geom::Vec2{box.min_x, box.min_y}, {box.max_x, box.min_y}, {box.max_x, box.max_y},
                       {box.min_x, box.max_y}, {mid_x, box.min_y}, {mid_x, box.max_y}, {box.min_x, mid_y},
                       {box.max_x, mid_y}, {box.min_x, equator}, {box.max_x, equator}}) {
    const std::optional<double> error = crs.scale_error(p);
    if (!error) unmapped = true;
    else worst = std::max(worst, *error);
  }
  if (!unmapped && worst <= kMaxScaleError) return;
  std::string files;
  for (const SketchPart& part : parts) files += (files.empty() ? "" : ", ") + part.path.string();
  geom::Vec2 stray;
  const std::string& feature = *places[farthest(places, stray)].feature;
  const double km = std::max(box.width() * std::cos(mid_y * M_PI / 180), box.height()) * 111.32;
  throw UserError(files + ": the sketch spans longitude " + fixed(std::remainder(box.min_x, 360), 3) + " to " +
                  fixed(std::remainder(box.max_x, 360), 3) + " and latitude " + fixed(box.min_y, 3) + " to " +
                  fixed(box.max_y, 3) + " (about " + fixed(km, 0) + " km), more than one map holds true to scale: " +
                  crs_text(map) +
                  (unmapped ? " does not reach all of it" : "'s scale is " + fixed(worst * 100, 1) + "% off at its edge") +
                  " (Exacity allows 1%); " + feature + " lies farthest from the rest, at longitude " +
                  fixed(std::remainder(stray.x, 360), 5) + ", latitude " + fixed(stray.y, 5) +
                  ": move or delete it if it strayed, or cut the sketch into parts a few degrees wide");
}

// project_to_metres, and whether it changed any part's positions.
ordered_json bring_to_one_crs(std::vector<SketchPart>& parts, bool& changed) {
  start_gdal();  // PROJ's messages go through GDAL's handler: kept off the terminal
  std::vector<std::vector<FeaturePositions>> features;
  std::vector<std::optional<OGRSpatialReference>> crs(parts.size());
  std::vector<ordered_json> members(parts.size());
  std::optional<std::size_t> first_named;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    ordered_json& doc = parts[i].doc;
    features.push_back(features_of(doc, parts[i].path));
    if (doc.is_object() && doc.contains("crs") && !doc["crs"].is_null()) {
      crs[i] = named_crs(doc["crs"], parts[i].path), members[i] = doc["crs"];
      if (!first_named) first_named = i;
    } else if (!features[i].empty() && looks_lon_lat(features[i], parts[i].path)) {
      crs[i] = lon_lat();
    }
  }
  // A part without a crs in metres is in the others' CRS; with none, it has no place.
  std::optional<std::size_t> first = first_named;
  for (std::size_t i = 0; i < parts.size() && !first; ++i)
    if (crs[i]) first = i;
  if (!first) return nullptr;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (crs[i] || features[i].empty()) continue;
    if (!first_named || crs[*first_named]->IsGeographic())
      throw UserError(parts[i].path.string() + ": has no crs and its coordinates are not longitude and latitude, while " +
                      parts[*first].path.string() + "'s are; give it a crs (ogr2ogr -a_srs EPSG:<code>)");
    crs[i] = crs[*first_named], members[i] = members[*first_named];
  }

  node_the_antimeridian(features, crs);
  const std::vector<Place> places = places_of(features, crs, parts);
  if (places.empty()) return members[*first];  // no positions: the sketch reader says so
  const geom::Box box = box_of(places);
  const geom::Vec2 centre{std::remainder((box.min_x + box.max_x) / 2, 360.0), (box.min_y + box.max_y) / 2};

  // The first CRS that is a map in metres true to scale at the sketch's centre, else UTM.
  std::optional<std::size_t> kept;
  for (std::size_t i = 0; i < parts.size() && !kept; ++i) {
    if (!crs[i] || features[i].empty()) continue;
    const MapCrs map(*crs[i]);
    if (!map.projected() || std::abs(map.unit() - 1) > 1e-12 || map.web_mercator()) continue;
    if (const std::optional<double> error = map.scale_error(centre); error && *error <= kMaxScaleError) kept = i;
  }
  OGRSpatialReference target;
  ordered_json member;
  if (kept) {
    target = *crs[*kept], member = members[*kept];
  } else {
    if (box.min_y < -80 || box.max_y > 84)
      throw UserError(parts[*first].path.string() + ": the sketch lies beyond 80°S–84°N, where UTM does not reach; "
                      "project it to a polar CRS in metres first");
    const int epsg = utm_epsg(centre.x, centre.y);
    target = from_epsg(epsg), member = crs_member(epsg);
  }
  expect_true_to_scale(places, target, parts);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (!crs[i]) continue;
    if (!crs[i]->IsSame(&target)) {
      transform_part(parts[i], features[i], *crs[i], target);
      changed = true;
    }
    parts[i].doc["crs"] = member;
  }
  return member;
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

ordered_json project_to_metres(std::vector<SketchPart>& parts) {
  bool changed = false;
  return bring_to_one_crs(parts, changed);
}

bool project_to_metres(ordered_json& doc, const std::filesystem::path& path) {
  std::vector<SketchPart> parts{{std::move(doc), path}};
  bool changed = false;
  bring_to_one_crs(parts, changed);
  doc = std::move(parts[0].doc);
  return changed;
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
