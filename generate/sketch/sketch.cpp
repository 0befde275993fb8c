#include "generate/sketch/sketch.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <tuple>

#include "generate/sketch/grid_map.h"
#include "generate/sketch/sketch_document.h"
#include "generate/gis/osm_tags.h"
#include "generate/errors.h"
#include "generate/input_file.h"
#include "generate/layout/road_settings.h"
#include "generate/parcels/parcel_settings.h"
#include "generate/placement/building_settings.h"
#include "generate/city/street_graph.h"
#include "geom/crowding.h"
#include "geom/measure.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::json;

ZoneSettings default_zone_settings(ZoneType type) {
  return {default_road_settings(type), {}, default_lot_settings(type), default_building_settings(type)};
}

ZoneSettings read_zone_settings(const SettingsReader& settings, ZoneType type, bool read_grammars) {
  const ZoneSettings defaults = default_zone_settings(type);
  ZoneSettings z;
  z.roads = read_road_settings(settings, defaults.roads, read_grammars);
  z.blocks = read_block_settings(settings, defaults.blocks);
  z.lots = read_lot_settings(settings, type, defaults.lots, *z.roads.layout);
  z.buildings = read_building_settings(settings, type, defaults.buildings);
  return z;
}

double default_width(RoadClass road_class) {
  switch (road_class) {
    case RoadClass::Highway: return 24;
    case RoadClass::Main: return 12;
    case RoadClass::Local: return 8;
  }
  return 8;
}

void default_street_zones(nlohmann::ordered_json& ex, const nlohmann::ordered_json& defaults) {
  if (!ex.is_object()) return;  // refused when the settings are read
  if (!ex.contains("zones")) ex["zones"] = nlohmann::ordered_json::object();
  if (!ex["zones"].is_object()) return;
  for (const char* type : kGridMapStreetZones) {
    nlohmann::ordered_json& zone = ex["zones"][type];
    if (zone.is_null()) zone = nlohmann::ordered_json::object();
    if (!zone.is_object()) continue;
    for (const auto& [key, value] : defaults.items())
      if (!zone.contains(key)) zone[key] = value;
  }
}

std::string document_text(const nlohmann::ordered_json& doc) {
  std::string out = "{";
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    out += (it == doc.begin() ? "\n " : ",\n ") + json(it.key()).dump() + ": ";
    if (it.key() != "features" || !it->is_array() || it->empty()) {
      out += it->dump();
      continue;
    }
    for (std::size_t i = 0; i < it->size(); ++i) out += (i ? ",\n  " : "[\n  ") + (*it)[i].dump();
    out += "\n ]";
  }
  return out + "\n}\n";
}

namespace {

std::string quote(std::string_view s) { return "\"" + std::string(s) + "\""; }

// A member's text, or its JSON when it is not a string: what to compare and quote.
std::string text_of(const json& obj, const char* key) {
  auto it = obj.find(key);
  if (it == obj.end()) return "";
  return it->is_string() ? it->get<std::string>() : it->dump();
}

template <std::size_t N>
std::string list(const std::array<std::string_view, N>& names) {
  std::string r;
  for (auto n : names) r += (r.empty() ? "" : ", ") + std::string(n);
  return r;
}


class Parser {
 public:
  Parser(const fs::path& path, bool read_grammars) : file_(path.string()), read_grammars_(read_grammars) {}

  // A feature named by its "source" is named with its file already.
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw UserError((source_of(where) ? "" : file_ + ": ") + where + ": " + what);
  }

  double number(const json& j, const std::string& where, double min, double max) const {
    if (const std::string* source = source_of(where))
      return read_number(j, *source, where.substr(std::min(where.size(), source->size() + 1)), min, max);
    return read_number(j, file_, where, min, max);
  }

  void known_keys(const json& obj, const std::string& where, const std::set<std::string>& keys) const {
    SettingsReader(obj, file_, where).expect_keys(keys);
  }


  geom::Vec2 position(const json& j, const std::string& where) const {
    if (j.is_array() && j.size() >= 2)
      for (const json& c : {j[0], j[1]})
        if (auto literal = overflowed_literal(c))
          fail(where, "coordinate " + *literal + " is not a finite number; use finite coordinates in metres");
    if (!j.is_array() || j.size() < 2 || !j[0].is_number() || !j[1].is_number())
      fail(where, "a position must be an array [x, y] of numbers");
    double x = j[0].get<double>(), y = j[1].get<double>();
    if (!std::isfinite(x) || !std::isfinite(y))
      fail(where, "coordinate " + j.dump() + " is not a finite number; use finite coordinates in metres");
    if (std::abs(x) > kMaxCoordinate || std::abs(y) > kMaxCoordinate)
      fail(where, "coordinate " + j.dump() + " is beyond 1e10 m, outside the range Exacity computes exactly in; "
                  "move the sketch nearer the origin (a false easting and northing)");
    return {x, y};
  }

  std::vector<geom::Vec2> positions(const json& j, const std::string& where) const {
    if (!j.is_array()) fail(where, "expected an array of positions");
    std::vector<geom::Vec2> pts;
    for (std::size_t i = 0; i < j.size(); ++i) {
      geom::Vec2 p = position(j[i], where + " position " + std::to_string(i));
      if (pts.empty() || !(pts.back() == p)) pts.push_back(p);  // repeated points are legal
    }
    return pts;
  }

  geom::Ring ring(const json& j, const std::string& where) const {
    geom::Ring r = positions(j, where);
    if (r.size() > 1 && r.front() == r.back()) r.pop_back();
    std::set<std::pair<double, double>> distinct;
    for (auto p : r) distinct.insert({p.x, p.y});
    if (distinct.size() < 3)
      fail(where, "ring has " + std::to_string(distinct.size()) +
                      " distinct points; a ring needs at least 3, so add points or delete the ring");
    return r;
  }

  geom::Polygon polygon(const json& j, const std::string& where) const {
    if (!j.is_array() || j.empty()) fail(where, "a Polygon needs at least one ring");
    geom::Polygon p;
    p.outer = ring(j[0], where + " outer ring");
    for (std::size_t i = 1; i < j.size(); ++i) p.holes.push_back(ring(j[i], where + " hole " + std::to_string(i)));
    return p;
  }

  // How messages name a feature: a grid map's by the file, line and column where its region
  // or road begins; the sketch's own by its place among the features the user wrote (a
  // "grid" map's features come before them).
  std::string feature_name(const json& f, int index) const {
    if (f.is_object() && f.contains("properties") && f.at("properties").is_object()) {
      const json& props = f.at("properties");
      if (props.contains("grid_cell") && props.at("grid_cell").is_string())
        return "grid map cell " + props.at("grid_cell").get<std::string>();
      // A feature read from another format (generate/gis/sketch_sources.h): FILE layer L
      // feature N, or FILE way N.
      if (props.contains("source") && props.at("source").is_string())
        return *sources_.insert(props.at("source").get<std::string>()).first;
    }
    return "features[" + std::to_string(index - grid_features_) + "]";
  }

  void feature(const json& f, int index, Sketch& sketch) {
    const std::string where = feature_name(f, index);
    names_.push_back(where);
    if (!f.is_object() || text_of(f, "type") != "Feature") fail(where, "not a GeoJSON Feature");
    if (!f.contains("geometry") || f["geometry"].is_null())
      fail(where, "feature has no geometry; draw a Polygon for a zone or a LineString for a road, or delete it");
    const json& g = f["geometry"];
    if (!g.is_object() || !g.contains("coordinates")) fail(where, "geometry has no coordinates");
    std::string type = text_of(g, "type");
    const json& coords = g["coordinates"];
    const json props = f.contains("properties") && f["properties"].is_object() ? f["properties"] : json::object();
    bool is_zone = props.contains("zone"), is_road = props.contains("road");
    auto tagged = [&](const char* key) {
      return props.contains(key) && !props[key].is_null() && props[key] != "no" && props[key] != false;
    };
    if (!is_zone && !is_road && tagged("building")) return mapped_building(props, type, coords, where, index, sketch, false);
    if (!is_zone && !is_road && tagged("building:part")) return mapped_building(props, type, coords, where, index, sketch, true);
    if (is_zone == is_road)
      fail(where, is_zone ? "feature has both \"zone\" and \"road\"; keep one"
                          : "feature has neither a \"zone\" nor a \"road\" property; add one");

    if (is_zone) {
      const json& z = props["zone"];
      std::string zname = z.is_string() ? z.get<std::string>() : z.dump();
      auto zt = parse_zone_type(zname);
      if (!zt)
        fail(where, "unknown zone type " + quote(zname) + "; did you mean " + quote(nearest_zone_name(zname)) +
                        "? (valid: " + list(kZoneTypeNames) + ")");
      ZoneFeature zf{index, *zt, {}, {}, {}};
      if (where.rfind("grid map cell ", 0) == 0) zf.grid_cell = where.substr(std::string("grid map cell ").size());
      else if (props.contains("source") && props["source"].is_string()) zf.source = where;
      if (type == "Polygon") {
        zf.polygons.push_back(polygon(coords, where));
      } else if (type == "MultiPolygon" && coords.is_array()) {
        for (std::size_t i = 0; i < coords.size(); ++i)
          zf.polygons.push_back(polygon(coords[i], where + " polygon " + std::to_string(i)));
      } else {
        fail(where, "a zone must be a Polygon or MultiPolygon, not " + quote(type));
      }
      sketch.zones.push_back(std::move(zf));
      return;
    }

    const json& r = props["road"];
    std::string rname = r.is_string() ? r.get<std::string>() : r.dump();
    auto rc = parse_road_class(rname);
    if (!rc)
      fail(where, "unknown road class " + quote(rname) + "; did you mean " +
                      quote(nearest_road_class_name(rname)) + "? (valid: " + list(kRoadClassNames) + ")");
    RoadFeature rf{index, *rc, default_width(*rc), {}, osm_road_tags(props)};
    std::tie(rf.sidewalk_left, rf.sidewalk_right) =
        osm_sidewalks(rf.osm_tags, sketch.streets.sidewalk(*rc), sketch.streets.tagged_sidewalk(*rc));
    for (const auto& [key, value] : rf.osm_tags)
      if (key == "highway" && value == "footway") rf.sidewalk_left = rf.sidewalk_right = 0;  // all of it is one
    if (props.contains("width") && !props["width"].is_null())
      rf.width = number(props["width"], where + " width", kMinRoadWidth, kMaxRoadWidth);
    if (props.contains("carriageway") && props["carriageway"].is_number())
      rf.carriageway = std::clamp(props["carriageway"].get<double>(), kMinRoadWidth, rf.width);
    auto line = [&](const json& j, const std::string& w) {
      geom::Polyline l = positions(j, w);
      if (l.size() < 2) fail(w, "a road needs at least 2 distinct points");
      rf.lines.push_back(std::move(l));
    };
    if (type == "LineString") {
      line(coords, where);
    } else if (type == "MultiLineString" && coords.is_array()) {
      for (std::size_t i = 0; i < coords.size(); ++i) line(coords[i], where + " line " + std::to_string(i));
    } else {
      fail(where, "a road must be a LineString or MultiLineString, not " + quote(type));
    }
    sketch.roads.push_back(std::move(rf));
  }

  // A mapped building: each polygon one footprint, kept as drawn; a ring the reader cannot
  // take (fewer than 3 distinct points) is the building's problem, counted when it is
  // refused, not the sketch's. Tags that are not numbers are as if absent. A building:part
  // (`part`) is read the same, into the parts.
  void mapped_building(const json& props, const std::string& type, const json& coords, const std::string& where,
                       int index, Sketch& sketch, bool part) const {
    if (type != "Polygon" && type != "MultiPolygon")
      fail(where, std::string(part ? "a building:part" : "a building") + " must be a Polygon or MultiPolygon, not " +
                      quote(type) + "; draw its footprint or delete it");
    MappedBuilding b;
    b.index = index;
    b.name = where;
    const json& tag = props[part ? "building:part" : "building"];
    b.building = tag.is_string() ? tag.get<std::string>() : tag.dump();
    if (props.contains("osm_id") && props["osm_id"].is_string()) b.osm_id = props["osm_id"].get<std::string>();
    else if (props.contains("osm_id") && props["osm_id"].is_number_integer()) b.osm_id = props["osm_id"].dump();
    for (const char* key : {"identificatie", "fid"})
      if (props.contains(key) && b.source_id.first.empty() && (props[key].is_string() || props[key].is_number_integer()))
        b.source_id = {key, props[key].is_string() ? props[key].get<std::string>() : props[key].dump()};
    b.height = tagged_number(props, "height");
    b.levels = tagged_number(props, "building:levels");
    b.roof_height = tagged_number(props, "roof:height");
    b.min_height = tagged_number(props, "min_height");
    b.min_level = tagged_number(props, "building:min_level");
    if (props.contains("roof:shape") && props["roof:shape"].is_string()) b.roof_shape = props["roof:shape"].get<std::string>();
    auto add = [&](const json& rings, const std::string& w) {
      MappedBuilding polygon = b;
      if (!rings.is_array() || rings.empty()) fail(w, "a Polygon needs at least one ring");
      for (std::size_t i = 0; i < rings.size(); ++i) {
        geom::Ring r = positions(rings[i], w + (i ? " hole " + std::to_string(i) : std::string(" outer ring")));
        if (r.size() > 1 && r.front() == r.back()) r.pop_back();
        std::set<std::pair<double, double>> distinct;
        for (geom::Vec2 p : r) distinct.insert({p.x, p.y});
        if (distinct.size() < 3) polygon.problem = "a ring of fewer than 3 distinct points";
        (i ? polygon.polygon.holes.emplace_back() : polygon.polygon.outer) = std::move(r);
      }
      if (w != where) polygon.name = w;
      (part ? sketch.building_parts : sketch.buildings).push_back(std::move(polygon));
    };
    if (type == "Polygon") return add(coords, where);
    if (!coords.is_array()) fail(where, "a MultiPolygon's coordinates must be an array of polygons");
    for (std::size_t i = 0; i < coords.size(); ++i) add(coords[i], coords.size() == 1 ? where : where + " polygon " + std::to_string(i));
  }

  // A tag's positive number in metres or storeys ("12", "12 m", 12); nothing otherwise.
  static std::optional<double> tagged_number(const json& props, const char* key) {
    if (!props.contains(key)) return std::nullopt;
    const json& v = props[key];
    double x = 0;
    if (v.is_number()) {
      x = v.get<double>();
    } else if (v.is_string()) {
      const std::string text = v.get<std::string>();
      char* end = nullptr;
      x = std::strtod(text.c_str(), &end);
      while (end && *end == ' ') ++end;
      if (end == text.c_str() || (*end && std::string(end) != "m")) return std::nullopt;
    } else {
      return std::nullopt;
    }
    if (!std::isfinite(x) || x <= 0 || x > 1000) return std::nullopt;
    return x;
  }

  // Coordinates are metres. Longitude/latitude (the GeoJSON default) would make a city a
  // fraction of a metre wide, so say so before anything is built.
  void expect_metres(const Sketch& sketch) const {
    std::string crs = sketch.crs.is_null() ? "" : sketch.crs.dump();
    const std::string fix = "; Exacity needs metres: reproject the sketch first, e.g. "
                            "ogr2ogr -t_srs EPSG:<UTM zone> metres.geojson sketch.geojson";
    for (const char* geographic : {"4326", "CRS84", "4258", "4269"})
      if (crs.find(geographic) != std::string::npos) fail("crs", "the sketch is in longitude/latitude (" + crs + ")" + fix);
    geom::Box b = geom::Box::none();
    for (const auto& z : sketch.zones)
      for (const auto& p : z.polygons)
        for (auto v : p.outer) b.add(v);
    for (const auto& r : sketch.roads)
      for (const auto& l : r.lines)
        for (auto v : l) b.add(v);
    bool degree_sized = b.width() < 1 && b.height() < 1 && b.min_x >= -180 && b.max_x <= 180 && b.min_y >= -90 && b.max_y <= 90;
    if (degree_sized)
      fail("features", "the whole sketch spans less than 1 x 1 unit, so its coordinates look like longitude/latitude" + fix);
  }

  // A sketch whose zones would need more blocks than one run can hold is refused before
  // anything is built, naming the zone that needs the most. Every polygon is one block (or
  // park or water face of the map) at least, however small: a hundred thousand tiny zones
  // have little area but make a map of gigabytes.
  void expect_buildable(const Sketch& sketch) const {
    double blocks = 0, most = -1;
    const ZoneFeature* largest = nullptr;
    for (const ZoneFeature& z : sketch.zones) {
      double n = 0;
      for (const auto& p : z.polygons)
        n += grows_roads(z.type)
                 ? std::max(1.0, std::abs(geom::area(p)) / sketch.zone_settings.at(z.type).roads.growth.block_area)
                 : 1.0;
      blocks += n;
      if (n > most) most = n, largest = &z;
    }
    if (blocks > kMaxBlocks)
      fail(names_[largest->index],
           "the zones would make about " + std::to_string(static_cast<long long>(blocks)) +
               " blocks (each polygon one at least), more than the " + std::to_string(static_cast<long long>(kMaxBlocks)) + " one run builds (this " + std::string(name(largest->type)) + " zone alone " +
               std::to_string(static_cast<long long>(most)) + "); draw fewer or smaller zones or raise their \"block_area\"");
  }

  // The exact map holds every road's stroke and every zone's rings, and where two cross it
  // gets vertices: a way that zig-zags across itself, or thousands of zones drawn over one
  // another, make a map quadratic in their points (a 400-point way, gigabytes). The strokes'
  // meetings are counted in doubles first and a sketch with too many refused, naming the
  // feature most of them are on.
  void expect_few_meetings(const Sketch& sketch) const {
    std::vector<geom::FatSegment> segments;
    std::vector<int> feature_of;  // by chain
    auto add_chain = [&](const std::vector<geom::Vec2>& points, double radius, bool ring, int feature) {
      const int chain = static_cast<int>(feature_of.size());
      feature_of.push_back(feature);
      const std::size_t n = ring ? points.size() : points.size() - 1;
      for (std::size_t i = 0; i < n; ++i)
        segments.push_back({points[i], points[(i + 1) % points.size()], radius, chain, static_cast<int>(i),
                            static_cast<int>(n) - 1, ring});
    };
    for (const RoadFeature& r : sketch.roads)
      for (const geom::Polyline& line : r.lines)
        if (line.size() > 1) add_chain(line, r.width / 2 + r.widest_sidewalk(), false, r.index);
    for (const ZoneFeature& z : sketch.zones)
      for (const geom::Polygon& p : z.polygons) {
        if (p.outer.size() > 1) add_chain(p.outer, 0, true, z.index);
        for (const geom::Ring& h : p.holes)
          if (h.size() > 1) add_chain(h, 0, true, z.index);
      }
    // Real maps meet under once a piece (junctions, land use along its streets).
    const std::size_t limit = kMaxMeetings + 4 * segments.size();
    std::vector<std::size_t> per_chain;
    if (geom::count_meetings(segments, limit + 1, per_chain) <= limit) return;
    std::map<int, std::size_t> per_feature;
    for (std::size_t c = 0; c < per_chain.size(); ++c) per_feature[feature_of[c]] += per_chain[c];
    const auto most = std::max_element(per_feature.begin(), per_feature.end(),
                                       [](const auto& x, const auto& y) { return x.second < y.second; });
    fail(names_[most->first],
         "the sketch's roads (with their sidewalks) and zone edges cross or overlap one another more than " +
             std::to_string(limit) + " times (" + std::to_string(kMaxMeetings) + " and 4 for each of their " +
             std::to_string(segments.size()) + " segments), more than one run builds: each crossing is work for "
             "the exact map; this feature is in " + std::to_string(most->second) +
             " of them: draw it without running across itself or over other features so often");
  }

  void settings(const json& ex, Sketch& sketch) const {
    const std::string w = "\"exacity\"";
    known_keys(ex, w,
               {"version", "seed", "terrain", "models", "zones", "roads", "camera", "channels", "channel_sharpness",
                "builtin_models", "like", "infer_zones"});
    if (ex.contains("infer_zones") && !ex["infer_zones"].is_boolean())
      fail(w + ".infer_zones", "expected true or false (true: street faces without land use are zoned from their mapped buildings)");
    if (ex.contains("version") && number(ex["version"], w + ".version", 1, 1) != 1) fail(w, "unsupported version");
    if (ex.contains("seed")) {
      const json& s = ex["seed"];
      if (!s.is_number_integer() || s.get<std::int64_t>() < 0)
        fail(w + ".seed", "the seed must be a non-negative integer");
      sketch.seed = s.get<std::uint64_t>();
    }
    if (ex.contains("models")) {
      if (!ex["models"].is_string()) fail(w + ".models", "expected the path of a model library (a string)");
      sketch.models = sketch.path.parent_path() / ex["models"].get<std::string>();
    }
    if (ex.contains("like")) {
      if (!ex["like"].is_string() || ex["like"].get<std::string>().empty())
        fail(w + ".like", "expected the path of an OSM extract or a file of building footprints (a string)");
      sketch.like = sketch.path.parent_path() / ex["like"].get<std::string>();
    }
    if (ex.contains("camera")) {
      if (!ex["camera"].is_string())
        fail(w + ".camera", "expected a camera such as \"orbit:target=0,0,0,azimuth=225,elevation=35,distance=900\"");
      sketch.camera = ex["camera"].get<std::string>();
    }
    if (ex.contains("builtin_models")) builtin_models(ex["builtin_models"], sketch);
    if (ex.contains("terrain")) sketch.terrain = terrain(ex["terrain"], sketch.path);
    if (ex.contains("channels")) sketch.channels = channels(ex["channels"], sketch.path);
    if (ex.contains("channel_sharpness"))
      sketch.channel_sharpness = number(ex["channel_sharpness"], w + ".channel_sharpness", 0, 1000);
    if (ex.contains("roads")) sketch.streets = streets(ex["roads"]);
    if (ex.contains("zones")) {
      const json& zones = ex["zones"];
      known_keys(zones, w + ".zones", {kZoneTypeNames.begin(), kZoneTypeNames.end()});
      for (auto& [zname, params] : zones.items()) {
        ZoneType zt = *parse_zone_type(zname);
        sketch.zone_settings[zt] = zone_settings(params, zt, w + ".zones." + zname);
        const std::string& height_channel = sketch.zone_settings[zt].buildings.height_channel;
        if (!height_channel.empty() && std::none_of(sketch.channels.begin(), sketch.channels.end(),
                                                    [&](const ChannelSpec& c) { return c.name == height_channel; }))
          fail(w + ".zones." + zname + ".height_channel",
               quote(height_channel) + " is not a channel; define it in \"exacity\".channels, or remove the key");
      }
    }
  }

  // Exacity's own trees and lamps (docs/design.md, Placement: built-in models): a list of
  // the kinds wanted, each once; [] turns them off.
  void builtin_models(const json& j, Sketch& sketch) const {
    const std::string w = "\"exacity\".builtin_models";
    const std::string fix = "give a list of \"tree\" and \"lamp\" (the default is both; [] turns them off)";
    if (!j.is_array()) fail(w, "expected a list; " + fix);
    sketch.builtin_trees = sketch.builtin_lamps = false;
    for (const json& kind : j) {
      const std::string k = kind.is_string() ? kind.get<std::string>() : kind.dump();
      bool& wanted = k == "tree" ? sketch.builtin_trees : sketch.builtin_lamps;
      if (!kind.is_string() || (k != "tree" && k != "lamp")) fail(w, quote(k) + " is not a built-in model; " + fix);
      if (wanted) fail(w, quote(k) + " is listed twice; list each kind once");
      wanted = true;
    }
  }

  // Channels, {"NAME": {"image": FILE, "bounds": [min_x, min_y, max_x, max_y]}}.
  std::vector<ChannelSpec> channels(const json& j, const fs::path& sketch_path) const {
    const std::string w = "\"exacity\".channels";
    if (!j.is_object())
      fail(w, "expected channels by name, like {\"downtown\": {\"image\": \"downtown.png\", \"bounds\": [0, 0, 2000, 1500]}}");
    std::vector<ChannelSpec> out;
    for (const auto& [cname, c] : j.items()) {
      const std::string cw = w + "." + cname;
      if (cname.empty()) fail(w, "a channel has an empty name; name it");
      known_keys(c, cw, {"image", "bounds"});
      ChannelSpec spec;
      spec.name = cname;
      if (!c.contains("image") || !c["image"].is_string() || c["image"].get<std::string>().empty())
        fail(cw + ".image", "name a greyscale image file (PNG, TIFF or EXR)");
      spec.image = sketch_path.parent_path() / c["image"].get<std::string>();
      spec.bounds = box(c, cw, "the area the channel's image covers");
      out.push_back(std::move(spec));
    }
    return out;
  }

  // "bounds": [min_x, min_y, max_x, max_y] of an image stretched over the city.
  geom::Box box(const json& j, const std::string& w, const std::string& what) const {
    if (!j.contains("bounds") || !j["bounds"].is_array() || j["bounds"].size() != 4)
      fail(w + ".bounds", "give " + what + " as [min_x, min_y, max_x, max_y]");
    const json& b = j["bounds"];
    const double big = 1e9;
    geom::Box out{number(b[0], w + ".bounds", -big, big), number(b[1], w + ".bounds", -big, big),
                  number(b[2], w + ".bounds", -big, big), number(b[3], w + ".bounds", -big, big)};
    if (!(out.max_x > out.min_x) || !(out.max_y > out.min_y))
      fail(w + ".bounds", "bounds " + b.dump() + " have zero area; give [min_x, min_y, max_x, max_y] with min < max");
    return out;
  }

  StreetSettings streets(const json& j) const {
    const std::string w = "\"exacity\".roads";
    std::set<std::string> keys{"snap", "dead_ends"};
    keys.insert(kRoadClassNames.begin(), kRoadClassNames.end());
    known_keys(j, w, keys);
    StreetSettings s;
    if (j.contains("snap")) s.snap = number(j["snap"], w + ".snap", 0, 100);
    if (j.contains("dead_ends")) {
      if (j["dead_ends"] != "report" && j["dead_ends"] != "error")
        fail(w + ".dead_ends", "expected \"report\" (list them in report.json) or \"error\" (refuse the sketch)");
      s.dead_ends_are_errors = j["dead_ends"] == "error";
    }
    for (std::string_view c : kRoadClassNames) {
      const std::string cname(c), cw = w + "." + cname;
      if (!j.contains(cname)) continue;
      known_keys(j[cname], cw, {"sidewalk"});
      if (j[cname].contains("sidewalk")) s.sidewalks[*parse_road_class(cname)] = number(j[cname]["sidewalk"], cw + ".sidewalk", 0, 50);
    }
    return s;
  }

  // Joins the roads' near ends and finds their dead ends (generate/city/street_graph.h).
  void join_streets(Sketch& sketch) const {
    sketch.joined_ends = join_near_ends(sketch.roads, sketch.streets.snap);
    sketch.dead_ends = dead_ends(sketch.roads);
    if (sketch.streets.dead_ends_are_errors && !sketch.dead_ends.empty()) {
      const DeadEnd& d = sketch.dead_ends.front();
      fail(names_[d.feature],
           "the road ends at " + json::array({d.at.x, d.at.y}).dump() + " meeting no other road (one of " +
               std::to_string(sketch.dead_ends.size()) +
               " dead ends; \"dead_ends\": \"error\" refuses them); draw it on to another road, or set "
               "\"exacity\".roads.dead_ends to \"report\"");
    }
  }

  TerrainSpec terrain(const json& t, const fs::path& sketch_path) const {
    const std::string w = "\"exacity\".terrain";
    known_keys(t, w, {"heightmap", "bounds", "height"});
    TerrainSpec spec;
    if (!t.contains("heightmap") || !t["heightmap"].is_string())
      fail(w, "\"heightmap\" must name an image file (PNG, TIFF or EXR)");
    spec.heightmap = sketch_path.parent_path() / t["heightmap"].get<std::string>();
    spec.bounds = box(t, w, "the area the heightmap covers");
    if (t.contains("height")) {
      const json& h = t["height"];
      if (!h.is_array() || h.size() != 2) fail(w + ".height", "give [lowest, highest] in metres");
      spec.low = number(h[0], w + ".height", -1e5, 1e5);
      spec.high = number(h[1], w + ".height", -1e5, 1e5);
    }
    return spec;
  }

  // One zone type's settings over its defaults, each step's read by that step; a key no
  // step reads is refused before any value is read.
  ZoneSettings zone_settings(const json& j, ZoneType zt, const std::string& w) const {
    const SettingsReader settings(j, file_, w);
    std::set<std::string> keys = road_setting_keys();
    for (const auto* more : {&parcel_setting_keys(), &building_setting_keys()}) keys.insert(more->begin(), more->end());
    settings.expect_keys(keys);
    return read_zone_settings(settings, zt, read_grammars_);
  }

  // The grid map the sketch's "exacity".grid names, relative to the sketch: its features go
  // before the sketch's own, so that zones the sketch draws win where they overlap it (the
  // later zone wins), and the zone types that get roads are laid out by "streets" and filled
  // by grid filling unless the sketch says otherwise (a planned city). The key is gone from `doc` after.
  void add_grid(nlohmann::ordered_json& doc, const fs::path& sketch_path) {
    nlohmann::ordered_json& ex = doc["exacity"];
    const std::string w = "\"exacity\".grid";
    if (!ex["grid"].is_string()) fail(w, "expected the path of a grid map (a string), relative to the sketch");
    const fs::path file = sketch_path.parent_path() / ex["grid"].get<std::string>();
    std::string text, why;
    if (!read_input(file, kMaxDataFileBytes, text, why))
      fail(w, "cannot read the grid map " + file.string() + " (" + why + "); give the path of a grid map, relative to the sketch");
    nlohmann::ordered_json features = grid_map_features(text, file);
    grid_features_ = static_cast<int>(features.size());
    for (auto& f : doc["features"]) features.push_back(std::move(f));
    doc["features"] = std::move(features);
    ex.erase("grid");
    default_street_zones(ex, {{"layout", "streets"}, {"placement", "grid"}});
  }

 private:
  // The "source" that `where` begins with: the feature's name, with its file.
  const std::string* source_of(const std::string& where) const {
    for (const std::string& s : sources_)  // "... feature 1" is no source of "... feature 12 width"
      if (where.compare(0, s.size(), s) == 0 && (where.size() == s.size() || where[s.size()] == ' ')) return &s;
    return nullptr;
  }

  std::string file_;
  mutable std::set<std::string> sources_;  // the names features have by their "source"
  bool read_grammars_;
  int grid_features_ = 0;          // features a "grid" map put before the sketch's own
  std::vector<std::string> names_;  // each feature as messages name it
};


// The sketch's JSON; `marked` is the text, its numbers beyond a double's range marked
// (settings.h, kOverflowMarker).
json read_json(std::string& marked, const fs::path& path) {
  json doc;
  try {
    for (;;) {
      try {
        doc = json::parse(marked);
        break;
      } catch (const json::out_of_range& e) {
        // "number overflow parsing '1e999'": mark that literal and read again.
        std::string what = e.what();
        auto open = what.find('\''), close = what.rfind('\'');
        if (e.id != 406 || open == std::string::npos || close <= open) throw;
        std::string literal = what.substr(open + 1, close - open - 1);
        auto at = marked.find(literal);
        if (at == std::string::npos) throw;
        marked.replace(at, literal.size(), "\"" + std::string(kOverflowMarker) + literal + "\"");
      }
    }
  } catch (const json::parse_error& e) {
    // e.byte is one past the offending character.
    std::size_t line = 1, column = 1, end = std::min<std::size_t>(e.byte ? e.byte - 1 : 0, marked.size());
    for (std::size_t i = 0; i < end; ++i) {
      if (marked[i] == '\n') ++line, column = 1;
      else ++column;
    }
    std::string what = e.what();
    if (auto colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    throw UserError(path.string() + ":" + std::to_string(line) + ":" + std::to_string(column) +
                    ": malformed JSON (" + what + "); fix the syntax there");
  }
  return doc;
}

}  // namespace

Sketch parse_sketch(const std::string& text, const fs::path& path, bool read_grammars, const fs::path& models) {
  Parser parser(path, read_grammars);
  std::string marked = text;
  json doc = read_json(marked, path);
  if (!doc.is_object() || text_of(doc, "type") != "FeatureCollection")
    parser.fail("top level", "a sketch must be a GeoJSON FeatureCollection");
  if (!doc.contains("features") || !doc["features"].is_array())
    parser.fail("top level", "the FeatureCollection has no \"features\" array");

  Sketch sketch;
  sketch.path = path;
  // A grid map the sketch names, or a model library given in place of its own, make a new
  // document: the one read, and the one OUT/sketch.geojson keeps.
  const bool settings_object = !doc.contains("exacity") || doc["exacity"].is_object();
  const bool grid = doc.contains("exacity") && doc["exacity"].is_object() && doc["exacity"].contains("grid");
  if (settings_object && (grid || !models.empty())) {
    nlohmann::ordered_json made = nlohmann::ordered_json::parse(marked);
    if (grid) parser.add_grid(made, path);
    if (!models.empty()) made["exacity"]["models"] = fs::absolute(models).lexically_normal().string();
    sketch.geojson = document_text(made);
    marked = sketch.geojson;
    doc = json::parse(marked);
  }
  for (ZoneType t : {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial, ZoneType::Park,
                     ZoneType::Water})
    sketch.zone_settings[t] = default_zone_settings(t);
  if (doc.contains("crs")) sketch.crs = nlohmann::ordered_json::parse(marked)["crs"];  // keeps key order
  const nlohmann::ordered_json osm = doc.contains("osm") ? nlohmann::ordered_json(doc["osm"]) : nullptr;
  if (osm.is_object() && osm.contains("taken") && osm["taken"].is_object())
    for (const auto& [what, count] : osm["taken"].items())
      if (count.is_number_integer()) sketch.osm_taken[what] = count.get<int>();
  for (const nlohmann::ordered_json* file : osm_file_counts(osm)) {
    Sketch::OsmCounts& counts = sketch.osm_counts.emplace_back();
    counts.file = file->contains("file") && (*file)["file"].is_string() ? (*file)["file"].get<std::string>() : path.string();
    if (file->contains("skipped") && (*file)["skipped"].is_object())
      for (const auto& [why, count] : (*file)["skipped"].items())
        if (count.is_number_integer()) {
          counts.left_out[why] = count.get<int>();
          if (why.rfind("building:part", 0) == 0) sketch.building_parts_left_out[why] += count.get<int>();
          else if (why.rfind("building", 0) == 0) sketch.buildings_left_out[why] += count.get<int>();
        }
    if (file->contains("buildings_named") && (*file)["buildings_named"].is_array())
      for (const auto& what : (*file)["buildings_named"])
        if (what.is_string()) sketch.buildings_left_out_named.push_back(what.get<std::string>());
    if (file->contains("repaired") && (*file)["repaired"].is_array())
      for (const auto& what : (*file)["repaired"])
        if (what.is_string()) {
          counts.repaired.push_back(what.get<std::string>());
          if (counts.repaired.back().find("closed along the edge") != std::string::npos) ++sketch.land_use.closed_along_bounds;
        }
  }
  if (doc.contains("land_use") && doc["land_use"].is_object()) {
    const json& l = doc["land_use"];
    LandUseTally& t = sketch.land_use;
    t.infer_zones = true;
    t.street_faces = l.value("street_faces", 0), t.faces_with_land_use = l.value("faces_with_land_use", 0);
    t.left_open = l.value("left_open", 0);
    if (l.contains("inferred") && l["inferred"].is_object())
      for (const auto& [zone, n] : l["inferred"].items())
        if (n.is_number_integer()) t.inferred[zone] = n.get<int>();
  }
  if (doc.contains("exacity")) parser.settings(doc["exacity"], sketch);
  json settings = json::object();
  for (const auto& [key, value] : doc.items())
    if (key != "features") settings[key] = value;
  sketch.settings_text = settings.dump();
  const json& features = doc["features"];
  for (std::size_t i = 0; i < features.size(); ++i) parser.feature(features[i], static_cast<int>(i), sketch);
  if (sketch.zones.empty() && sketch.roads.empty())
    parser.fail("features", "the sketch has no zones and no roads; draw at least one zone polygon");
  parser.expect_metres(sketch);
  parser.expect_buildable(sketch);
  parser.join_streets(sketch);
  parser.expect_few_meetings(sketch);
  return sketch;
}

DrawnFeatures read_drawn_features(const nlohmann::ordered_json& doc, const fs::path& path) {
  Parser parser(path, false);
  Sketch sketch;
  sketch.path = path;
  const json plain = json::parse(doc.dump());
  const json& features = plain["features"];
  for (std::size_t i = 0; i < features.size(); ++i) parser.feature(features[i], static_cast<int>(i), sketch);
  return std::move(static_cast<DrawnFeatures&>(sketch));
}

}  // namespace exacity
