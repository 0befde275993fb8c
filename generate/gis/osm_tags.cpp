#include "generate/gis/osm_tags.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <set>

#include <ogr_geometry.h>

namespace exacity {
using nlohmann::ordered_json;

namespace {

// What a highway tag makes: a road class, or nothing (paths, tracks, planned roads).
std::optional<std::string> road_class(const std::string& highway) {
  static const std::map<std::string, std::string> classes{
      {"motorway", "highway"},  {"motorway_link", "highway"}, {"trunk", "highway"},      {"trunk_link", "highway"},
      {"primary", "highway"},   {"primary_link", "highway"},  {"secondary", "main"},     {"secondary_link", "main"},
      {"tertiary", "main"},     {"tertiary_link", "main"},    {"unclassified", "local"}, {"residential", "local"},
      {"living_street", "local"}, {"service", "local"},       {"road", "local"},         {"pedestrian", "local"}};
  auto it = classes.find(highway);
  if (it == classes.end()) return std::nullopt;
  return it->second;
}

// Metres from a width tag ("7", "7.5 m", "7m"); nothing for other units or junk.
std::optional<double> metres(const std::optional<std::string>& tag) {
  if (!tag) return std::nullopt;
  const char* text = tag->c_str();
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  while (end && *end == ' ') ++end;
  if (end == text || !std::isfinite(v) || v <= 0 || (*end && std::string(end) != "m")) return std::nullopt;
  return v;
}

double default_width(const std::string& road) { return road == "highway" ? 20 : road == "main" ? 12 : 8; }

// Where osm_keys' main tags that name a feature left out begin.
constexpr std::ptrdiff_t kReadKeys = 15;

// Pedestrian streets and alleys are local streets, narrower than the class's default; so
// are footways that bound land. A lane's width multiplies `lanes`.
constexpr double kPedestrianWidth = 6, kAlleyWidth = 4, kFootwayWidth = 3, kLaneWidth = 3.5;

OsmMeaning left_out(const std::string& why) { return {OsmMeaning::LeftOut, "", 0, why}; }

// The first of `keys` that is tagged, as "key=value".
std::optional<std::string> first_tag(const OsmTags& tags, std::initializer_list<const char*> keys) {
  for (const char* key : keys)
    if (std::optional<std::string> v = tags(key)) return std::string(key) + "=" + *v;
  return std::nullopt;
}

// GDAL's OSM driver keeps the tags it has no column for as one hstore text:
// "lanes"=>"2","tunnel"=>"yes".
std::map<std::string, std::string> hstore(const std::string& text) {
  std::map<std::string, std::string> out;
  std::size_t i = 0;
  auto quoted = [&](std::string& s) {
    while (i < text.size() && text[i] != '"') ++i;
    if (i++ >= text.size()) return false;
    for (; i < text.size() && text[i] != '"'; ++i) s += text[i] == '\\' && i + 1 < text.size() ? text[++i] : text[i];
    return i++ < text.size();
  };
  for (std::string k, v; quoted(k) && text.compare(i, 2, "=>") == 0 && quoted(v); k.clear(), v.clear()) out[k] = v;
  return out;
}

std::optional<std::string> text_value(const ordered_json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number() || v.is_boolean()) return v.dump();
  return std::nullopt;
}

bool is_polygonal(const std::string& type) { return type == "Polygon" || type == "MultiPolygon"; }
bool is_linear(const std::string& type) { return type == "LineString" || type == "MultiLineString"; }

// Land use mapped to the block's edge leaves the pavement between it and the street to no
// zone, and a block no street reaches gets no lots (docs/design.md, The sketch, GIS and OSM):
// a built-up zone is widened by this much where OSM's streets come with it.
constexpr double kLandUseReach = 8;

// `geometry` grown by `distance` (GEOS, through OGR), in the document's metres.
std::optional<ordered_json> buffered(const ordered_json& geometry, double distance) {
  std::unique_ptr<OGRGeometry> g(OGRGeometryFactory::createFromGeoJson(geometry.dump().c_str()));
  if (!g) return std::nullopt;
  std::unique_ptr<OGRGeometry> area(g->Buffer(distance, 4));
  if (!area || area->IsEmpty()) return std::nullopt;
  char* text = area->exportToJson();
  ordered_json out = ordered_json::parse(text ? text : "null", nullptr, false);
  CPLFree(text);
  if (out.is_discarded() || out.is_null()) return std::nullopt;
  return out;
}

// An area without its rings of fewer than 3 distinct points (OSM exports hold closed ways of
// two nodes), a polygon whose outer ring is one dropped whole; whether any polygon is left.
bool drop_degenerate_rings(ordered_json& geometry) {
  auto distinct = [](const ordered_json& ring) {
    std::vector<std::pair<double, double>> points;
    if (ring.is_array())
      for (const ordered_json& p : ring)
        if (p.is_array() && p.size() >= 2 && p[0].is_number() && p[1].is_number()) points.push_back({p[0], p[1]});
    std::sort(points.begin(), points.end());
    return std::unique(points.begin(), points.end()) - points.begin();
  };
  auto clean = [&](ordered_json& polygon) {
    if (!polygon.is_array() || polygon.empty() || distinct(polygon[0]) < 3) return false;
    ordered_json rings = ordered_json::array({polygon[0]});
    for (std::size_t i = 1; i < polygon.size(); ++i)
      if (distinct(polygon[i]) >= 3) rings.push_back(polygon[i]);
    polygon = std::move(rings);
    return true;
  };
  ordered_json& coords = geometry["coordinates"];
  if (geometry["type"] == "Polygon") return clean(coords);
  if (!coords.is_array()) return false;
  ordered_json kept = ordered_json::array();
  for (ordered_json& polygon : coords)
    if (clean(polygon)) kept.push_back(std::move(polygon));
  coords = std::move(kept);
  return !coords.empty();
}

// The footways (road_where_it_bounds_land) that share a segment with a zone's ring, as OSM
// maps a path along the edge of land use (the same nodes, so the same positions), become
// local streets; the others stay left out.
void make_roads_of_footways_that_bound_land(const ordered_json& features, std::vector<OsmMeaning>& meanings) {
  using Position = std::pair<double, double>;
  auto position = [](const ordered_json& p) -> std::optional<Position> {
    if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number()) return std::nullopt;
    return Position{p[0].get<double>(), p[1].get<double>()};
  };
  // Each line's segments, either way round.
  auto for_each_segment = [&](const ordered_json& line, const std::function<void(Position, Position)>& f) {
    if (!line.is_array()) return;
    for (std::size_t i = 1; i < line.size(); ++i)
      if (auto a = position(line[i - 1]), b = position(line[i]); a && b) f(std::min(*a, *b), std::max(*a, *b));
  };
  // A geometry's lines: a LineString's, a MultiLineString's or a Polygon's rings, a MultiPolygon's.
  auto lines_of = [](const ordered_json& geometry) {
    std::vector<const ordered_json*> out;
    if (!geometry.is_object() || !geometry.contains("coordinates") || !geometry["coordinates"].is_array()) return out;
    const ordered_json& c = geometry["coordinates"];
    const std::string type = geometry.value("type", "");
    if (type == "LineString") out.push_back(&c);
    if (type == "MultiLineString" || type == "Polygon")
      for (const ordered_json& l : c) out.push_back(&l);
    if (type == "MultiPolygon")
      for (const ordered_json& polygon : c)
        if (polygon.is_array())
          for (const ordered_json& ring : polygon) out.push_back(&ring);
    return out;
  };
  if (std::none_of(meanings.begin(), meanings.end(), [](const OsmMeaning& m) { return m.road_where_it_bounds_land; })) return;
  std::set<std::pair<Position, Position>> edges;
  for (std::size_t i = 0; i < features.size(); ++i)
    if (meanings[i].kind == OsmMeaning::Zone)
      for (const ordered_json* ring : lines_of(features[i]["geometry"]))
        for_each_segment(*ring, [&](Position a, Position b) { edges.insert({a, b}); });
  for (std::size_t i = 0; i < features.size(); ++i) {
    if (!meanings[i].road_where_it_bounds_land) continue;
    bool bounds = false;
    for (const ordered_json* line : lines_of(features[i]["geometry"]))
      for_each_segment(*line, [&](Position a, Position b) { bounds = bounds || edges.count({a, b}); });
    if (bounds) meanings[i] = {OsmMeaning::Road, meanings[i].type, meanings[i].width, ""};
  }
}

}  // namespace

const std::vector<std::string>& osm_keys() {
  // The keys read, then the OSM ids GIS exports carry and the main tags of what Exacity
  // makes nothing of (kReadKeys on), which name what is left out.
  static const std::vector<std::string> keys{
      "highway",  "waterway", "landuse", "natural", "leisure",  "water",    "width",    "lanes",   "tunnel",
      "service",  "footway",  "indoor",  "other_tags", "osm_id", "osm_way_id", "building", "amenity", "shop", "tourism", "man_made",
      "railway",  "aeroway",  "barrier", "boundary", "place",    "power",    "historic", "military", "sport", "office"};
  return keys;
}

const std::vector<std::string>& osm_building_keys() {
  static const std::vector<std::string> keys{"height",      "building:levels",    "roof:shape",
                                             "roof:height", "min_height", "building:min_level"};
  return keys;
}

const std::vector<std::string>& osm_road_keys() {
  static const std::vector<std::string> keys{"highway", "name",     "ref",    "lanes", "oneway", "maxspeed",
                                             "surface", "service",  "sidewalk", "sidewalk:both", "sidewalk:left",
                                             "sidewalk:right", "sidewalk:width", "sidewalk:both:width",
                                             "sidewalk:left:width", "sidewalk:right:width", "bridge", "layer", "tunnel"};
  return keys;
}

std::pair<double, double> osm_sidewalks(const std::vector<std::pair<std::string, std::string>>& tags, double untagged,
                                        double tagged) {
  const std::map<std::string, std::string> tag(tags.begin(), tags.end());
  auto value = [&](const std::string& key) -> std::optional<std::string> {
    if (auto it = tag.find(key); it != tag.end()) return it->second;
    return std::nullopt;
  };
  auto width = [&](const std::string& side) {
    for (const std::string& key : {"sidewalk:" + side + ":width", std::string("sidewalk:both:width"), std::string("sidewalk:width")})
      if (std::optional<double> w = metres(value(key)); w && *w <= 50) return *w;
    return tagged;
  };
  // Whether a value puts a sidewalk on a side; nothing for one it cannot read.
  auto present = [](const std::optional<std::string>& v) -> std::optional<bool> {
    if (!v) return std::nullopt;
    if (*v == "yes" || *v == "both") return true;
    if (*v == "no" || *v == "none" || *v == "separate") return false;
    return std::nullopt;
  };
  std::optional<bool> left, right;
  if (const std::optional<std::string> both = value("sidewalk")) {
    if (*both == "left" || *both == "right") {
      left = *both == "left";
      right = *both == "right";
    } else {
      left = right = present(both);
    }
  }
  if (const std::optional<bool> both = present(value("sidewalk:both"))) left = right = both;
  if (const std::optional<bool> l = present(value("sidewalk:left"))) left = l;
  if (const std::optional<bool> r = present(value("sidewalk:right"))) right = r;
  auto side = [&](const std::optional<bool>& has, const std::string& name) { return !has ? untagged : *has ? width(name) : 0.0; };
  return {side(left, "left"), side(right, "right")};
}

std::vector<std::pair<std::string, std::string>> osm_road_tags(const ordered_json& properties) {
  std::vector<std::pair<std::string, std::string>> out;
  if (!properties.is_object()) return out;
  std::map<std::string, std::string> other;
  if (properties.contains("other_tags") && properties["other_tags"].is_string())
    other = hstore(properties["other_tags"].get<std::string>());
  // Its way as "way/N": an extract's; GDAL's OSM driver's and pyrosm's lines have the way's
  // number in osm_id.
  if (std::optional<std::string> id = properties.contains("osm_id") ? text_value(properties.at("osm_id")) : std::nullopt;
      id && !id->empty())
    out.push_back({"osm_id", id->find('/') == std::string::npos ? "way/" + *id : *id});
  for (const std::string& key : osm_road_keys()) {
    std::optional<std::string> value = properties.contains(key) ? text_value(properties.at(key)) : std::nullopt;
    if (auto it = other.find(key); !value && it != other.end()) value = it->second;
    if (value && !value->empty()) out.push_back({key, *value});
  }
  return out;
}

OsmMeaning osm_line_meaning(const OsmTags& tags) {
  if (std::optional<std::string> waterway = tags("waterway")) {
    if (*waterway == "river" || *waterway == "canal") return {OsmMeaning::River, "water", std::clamp(metres(tags("width")).value_or(10), 1.0, 5000.0), ""};
    return left_out("waterway=" + *waterway);
  }
  const std::optional<std::string> highway = tags("highway");
  if (!highway) {
    if (std::optional<std::string> area_tag = first_tag(tags, {"landuse", "natural", "leisure", "water"}))
      return left_out(*area_tag + " drawn as a line");
    return {};
  }
  const std::optional<std::string> road = road_class(*highway);
  // A footway between two pieces of land (a passage between blocks, a path along a park) is
  // a block's edge; one beside a street (footway=sidewalk), across it or in a tunnel is not.
  if (*highway == "footway" && !tags("tunnel") && !tags("indoor") &&
      !std::set<std::string>{"sidewalk", "crossing", "traffic_island", "access_aisle"}.count(tags("footway").value_or(""))) {
    OsmMeaning footway = left_out("highway=footway");
    footway.type = "local", footway.width = kFootwayWidth, footway.road_where_it_bounds_land = true;
    return footway;
  }
  if (!road) return left_out("highway=" + *highway);
  if (tags("tunnel") == std::optional<std::string>("yes")) return left_out("tunnel");
  double width = default_width(*road);
  if (*highway == "pedestrian") width = kPedestrianWidth;
  if (*highway == "service")
    if (std::optional<std::string> service = tags("service")) {
      if (*service != "alley") return left_out("service=" + *service);
      width = kAlleyWidth;
    }
  bool mapped = true;
  if (std::optional<double> w = metres(tags("width"))) width = *w;
  else if (std::optional<std::string> lanes = tags("lanes"); lanes && std::atoi(lanes->c_str()) > 0)
    width = kLaneWidth * std::atoi(lanes->c_str());
  else mapped = false;
  OsmMeaning out{OsmMeaning::Road, *road, std::clamp(width, 1.0, 100.0), ""};
  out.width_mapped = mapped;
  return out;
}

OsmMeaning osm_area_meaning(const OsmTags& tags) {
  auto is = [&](const char* key, const char* value) { return tags(key) == std::optional<std::string>(value); };
  const std::string l = tags("landuse").value_or("");
  auto zone = [](const char* type) { return OsmMeaning{OsmMeaning::Zone, type, 0, ""}; };
  if (l == "residential") return zone("residential");
  if (l == "commercial" || l == "retail") return zone("commercial");
  if (l == "industrial") return zone("industrial");
  if (l == "reservoir" || l == "basin" || is("natural", "water") || tags("water") || is("waterway", "riverbank"))
    return zone("water");
  if (l == "grass" || l == "meadow" || l == "forest" || l == "recreation_ground" || l == "village_green" ||
      is("leisure", "park") || is("leisure", "garden") || is("natural", "wood"))
    return zone("park");
  // A building mapped with the land use it stands on, a school's or a sports centre's,
  // is still a building.
  if (std::optional<std::string> building = tags("building"); building && *building != "no")
    return {OsmMeaning::Building, *building, 0, ""};
  if (std::optional<std::string> part = tags("building:part"); part && *part != "no")
    return {OsmMeaning::BuildingPart, *part, 0, ""};
  if (std::optional<std::string> tag = first_tag(tags, {"landuse", "leisure", "natural", "waterway", "highway"}))
    return left_out(*tag);
  return {};
}

std::vector<const ordered_json*> osm_file_counts(const ordered_json& osm) {
  std::vector<const ordered_json*> out;
  if (!osm.is_object()) return out;
  if (!osm.contains("files")) return {&osm};
  if (osm["files"].is_array())
    for (const ordered_json& file : osm["files"])
      if (file.is_object()) out.push_back(&file);
  return out;
}

bool apply_osm_tags(ordered_json& doc, const std::vector<SketchFile>& files) {
  if (!doc.is_object() || !doc.contains("features") || !doc["features"].is_array()) return false;
  ordered_json& features = doc["features"];
  std::vector<OsmMeaning> meanings;
  for (ordered_json& f : features) {
    meanings.emplace_back();
    if (!f.is_object() || !f.contains("properties") || !f["properties"].is_object() || !f.contains("geometry") ||
        !f["geometry"].is_object())
      continue;
    const ordered_json& p = f["properties"];
    if (p.contains("zone") || p.contains("road")) continue;
    std::map<std::string, std::string> other;
    if (p.contains("other_tags") && p["other_tags"].is_string()) other = hstore(p["other_tags"].get<std::string>());
    const OsmTags tags = [&](const std::string& key) -> std::optional<std::string> {
      if (p.contains(key))
        if (std::optional<std::string> v = text_value(p[key])) return v;
      if (auto it = other.find(key); it != other.end()) return it->second;
      return std::nullopt;
    };
    const std::string type = f["geometry"].value("type", "");
    if (is_polygonal(type)) meanings.back() = osm_area_meaning(tags);
    else if (is_linear(type)) meanings.back() = osm_line_meaning(tags);
    else if (std::optional<std::string> tag = first_tag(tags, {"highway", "waterway", "landuse", "natural", "leisure", "water"}))
      meanings.back() = left_out(*tag + " as a point");  // a crossing, a bus stop, a tree
    // A feature GDAL's OSM driver or pyrosm exported (it has their OSM id columns) whose tags
    // are none of those read: a building, a school's grounds. Left out and counted by its
    // main tag, as an extract's would be; a feature drawn by hand without a zone or road
    // is still the sketch reader's to refuse.
    if (meanings.back().kind == OsmMeaning::Untagged && (tags("osm_id") || tags("osm_way_id"))) {
      std::optional<std::string> tag;
      for (auto key = osm_keys().begin() + kReadKeys; key != osm_keys().end() && !tag; ++key)
        if (std::optional<std::string> v = tags(*key)) tag = *key + "=" + *v;
      meanings.back() = left_out(tag ? *tag : "OpenStreetMap features without a tag Exacity reads");
    }
  }
  if (std::all_of(meanings.begin(), meanings.end(), [](const OsmMeaning& m) { return m.kind == OsmMeaning::Untagged; }))
    return false;
  make_roads_of_footways_that_bound_land(features, meanings);

  std::map<std::string, int> taken{{"zones", 0}, {"roads", 0}, {"rivers", 0}};
  std::vector<std::map<std::string, int>> skipped(files.size());  // by file
  std::vector<std::size_t> zones;  // places of the features whose tags made zones
  ordered_json kept = ordered_json::array();
  std::size_t file = 0, first = 0;  // the file of feature i, and the place of its first feature
  for (std::size_t i = 0; i < features.size(); ++i) {
    while (file + 1 < files.size() && i >= first + files[file].features) first += files[file++].features;
    ordered_json& f = features[i];
    const OsmMeaning& meaning = meanings[i];
    // Features are taken out below: each keeps its place in the user's file for messages.
    if (f.is_object() && f.contains("properties") && f["properties"].is_object() && !f["properties"].contains("source"))
      f["properties"]["source"] = files[file].path.string() + " features[" + std::to_string(i - first) + "]";
    if (meaning.kind == OsmMeaning::LeftOut) {
      ++skipped[file][meaning.why];
      continue;
    }
    if (meaning.kind == OsmMeaning::River) {
      std::optional<ordered_json> water = buffered(f["geometry"], meaning.width / 2);
      if (!water) {
        ++skipped[file]["rivers GEOS could not widen"];
        continue;
      }
      f["geometry"] = std::move(*water);
    }
    if (meaning.kind == OsmMeaning::Building || meaning.kind == OsmMeaning::BuildingPart) {
      // What the sketch reader raises it from, where a GIS export keeps it in other_tags,
      // and its OSM id as a type and number where the export says which.
      const bool part = meaning.kind == OsmMeaning::BuildingPart;
      ++taken[part ? "building parts" : "buildings"];
      ordered_json& p = f["properties"];
      std::map<std::string, std::string> other;
      if (p.contains("other_tags") && p["other_tags"].is_string()) other = hstore(p["other_tags"].get<std::string>());
      p[part ? "building:part" : "building"] = meaning.type;
      for (const std::string& key : osm_building_keys())
        if (auto it = other.find(key); !p.contains(key) && it != other.end()) p[key] = it->second;
      // GDAL's OSM driver fills osm_way_id for a closed way and osm_id for a relation;
      // other exports (pyrosm's) have only osm_id, of either.
      const std::optional<std::string> way = p.contains("osm_way_id") ? text_value(p["osm_way_id"]) : std::nullopt;
      const std::optional<std::string> id = p.contains("osm_id") ? text_value(p["osm_id"]) : std::nullopt;
      if (way) p["osm_id"] = "way/" + *way;
      else if (id && id->find('/') == std::string::npos) p["osm_id"] = (p.contains("osm_way_id") ? "relation/" : "") + *id;
      kept.push_back(std::move(f));
      continue;
    }
    if (meaning.kind == OsmMeaning::Zone && !drop_degenerate_rings(f["geometry"])) {
      ++skipped[file]["areas of fewer than 3 distinct points"];
      continue;
    }
    if (meaning.kind != OsmMeaning::Untagged) {
      ++taken[meaning.kind == OsmMeaning::Zone ? "zones" : meaning.kind == OsmMeaning::Road ? "roads" : "rivers"];
      const bool zone = meaning.kind != OsmMeaning::Road;
      ordered_json& p = f["properties"];
      p[zone ? "zone" : "road"] = meaning.type;
      if (!zone) p["width"] = meaning.width;
      // The carriageway as mapped, which a road narrowed for a mapped building keeps
      // (generate/placement/mapped_buildings.h).
      if (meaning.width_mapped) p["carriageway"] = meaning.width;
      if (zone) zones.push_back(kept.size());
    }
    kept.push_back(std::move(f));
  }
  if (taken["roads"] > 0)
    for (std::size_t z : zones) {
      ordered_json& f = kept[z];
      const std::string type = f["properties"]["zone"];
      if (type == "water" || type == "park") continue;
      if (std::optional<ordered_json> wide = buffered(f["geometry"], kLandUseReach)) f["geometry"] = std::move(*wide);
    }
  // Land use first, then parks, then water, in the places the tagged zones had: where areas
  // overlap the later wins, so water keeps its banks and a park inside a residential area
  // stays a park. The user's own zones keep their places.
  auto rank = [](const ordered_json& f) {
    const std::string t = f["properties"]["zone"];
    return t == "water" ? 2 : t == "park" ? 1 : 0;
  };
  std::vector<ordered_json> ordered;
  for (std::size_t z : zones) ordered.push_back(kept[z]);
  std::stable_sort(ordered.begin(), ordered.end(), [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
  for (std::size_t k = 0; k < zones.size(); ++k) kept[zones[k]] = std::move(ordered[k]);
  features = std::move(kept);

  ordered_json& osm = doc["osm"];
  if (!osm.is_object()) osm = files.size() == 1 ? ordered_json{{"file", files[0].path.string()}} : ordered_json::object();
  // Named only where the files map some.
  for (const char* what : {"buildings", "building parts"})
    if (taken[what] == 0) taken.erase(what);
  osm["taken"] = taken;
  // Each file's counts: the member itself for one file, its "files" for several (an
  // extract's own counts, from reading it, already there).
  if (files.size() > 1 && !(osm.contains("files") && osm["files"].is_array() && osm["files"].size() == files.size())) {
    osm["files"] = ordered_json::array();
    for (const SketchFile& f : files) osm["files"].push_back({{"file", f.path.string()}});
  }
  for (std::size_t k = 0; k < files.size(); ++k) {
    ordered_json& counts = files.size() > 1 ? osm["files"][k] : osm;
    if (!counts.contains("file")) counts["file"] = files[k].path.string();
    if (!counts.contains("skipped") || !counts["skipped"].is_object()) counts["skipped"] = ordered_json::object();
    // By why, as the extract's own counts are: a footway is counted here, after them.
    std::map<std::string, ordered_json> merged;
    for (const auto& [why, count] : counts["skipped"].items()) merged[why] = count;
    for (const auto& [why, count] : skipped[k]) merged[why] = counts["skipped"].value(why, 0) + count;
    counts["skipped"] = ordered_json::object();
    for (auto& [why, count] : merged) counts["skipped"][why] = std::move(count);
  }
  return true;
}

}  // namespace exacity
