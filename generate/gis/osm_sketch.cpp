// OpenStreetMap extracts as sketches (docs/design.md, The sketch, GIS and OSM), read with
// libosmium: multipolygon relations and closed ways assembled into areas by its
// MultipolygonManager, way node locations from a node index.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <osmium/area/assembler.hpp>
#include <osmium/area/multipolygon_manager.hpp>
#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/relations/manager_util.hpp>
#include <osmium/tags/tags_filter.hpp>
#include <osmium/visitor.hpp>

#include "generate/errors.h"
#include "generate/gis/projection.h"
#include "generate/gis/sketch_sources.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

using LonLat = std::vector<std::pair<double, double>>;

// What a highway tag makes: a road class, or nothing (paths, tracks, planned roads).
std::optional<std::string> road_class(const std::string& highway) {
  static const std::map<std::string, std::string> classes{
      {"motorway", "highway"},  {"motorway_link", "highway"}, {"trunk", "highway"},      {"trunk_link", "highway"},
      {"primary", "highway"},   {"primary_link", "highway"},  {"secondary", "main"},     {"secondary_link", "main"},
      {"tertiary", "main"},     {"tertiary_link", "main"},    {"unclassified", "local"}, {"residential", "local"},
      {"living_street", "local"}, {"service", "local"},       {"road", "local"}};
  auto it = classes.find(highway);
  if (it == classes.end()) return std::nullopt;
  return it->second;
}

// A zone type from an area's tags, or nothing.
std::optional<std::string> zone_type(const osmium::TagList& tags) {
  const char* landuse = tags["landuse"];
  const std::string l = landuse ? landuse : "";
  if (l == "residential") return "residential";
  if (l == "commercial" || l == "retail") return "commercial";
  if (l == "industrial") return "industrial";
  if (l == "reservoir" || l == "basin" || tags.has_tag("natural", "water") || tags.has_key("water") ||
      tags.has_tag("waterway", "riverbank"))
    return "water";
  if (l == "grass" || l == "meadow" || l == "forest" || l == "recreation_ground" || l == "village_green" ||
      tags.has_tag("leisure", "park") || tags.has_tag("leisure", "garden") || tags.has_tag("natural", "wood"))
    return "park";
  return std::nullopt;
}

// Metres from a width tag ("7", "7.5 m", "7m"); nothing for other units or junk.
std::optional<double> metres(const char* tag) {
  if (!tag) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(tag, &end);
  while (end && *end == ' ') ++end;
  if (end == tag || !std::isfinite(v) || v <= 0 || (*end && std::string(end) != "m")) return std::nullopt;
  return v;
}

double default_width(const std::string& road) { return road == "highway" ? 20 : road == "main" ? 12 : 8; }

struct OsmFeature {
  std::string kind;   // "zone" or "road"
  std::string type;   // the zone type or road class
  double width = 0;   // roads, and rivers before buffering
  std::string name, source;
  std::vector<std::pair<LonLat, std::vector<LonLat>>> polygons;  // zones: outer ring, holes
  LonLat line;                                                    // roads and rivers
};

// What the extract makes, and what it leaves out and why (the document's "osm" member).
class Collector : public osmium::handler::Handler {
 public:
  explicit Collector(std::string file) : file_(std::move(file)) {}

  void way(const osmium::Way& way) {
    const osmium::TagList& tags = way.tags();
    if (const char* waterway = tags["waterway"]; waterway && (std::string(waterway) == "river" || std::string(waterway) == "canal")) {
      OsmFeature f{"zone", "water", metres(tags["width"]).value_or(10), name(tags), file_ + " way " + std::to_string(way.id()), {}, line(way)};
      if (f.line.size() >= 2) rivers_.push_back(std::move(f));
      return;
    }
    const char* highway = tags["highway"];
    if (!highway) return;
    const std::optional<std::string> road = road_class(highway);
    if (!road) return ++skipped_[std::string("highway=") + highway], void();
    if (tags.has_tag("tunnel", "yes")) return ++skipped_["tunnel"], void();
    if (*road == "local" && std::string(highway) == "service" && tags.has_key("service"))
      return ++skipped_[std::string("service=") + tags["service"]], void();
    double width = default_width(*road);
    if (std::optional<double> w = metres(tags["width"])) width = *w;
    else if (const char* lanes = tags["lanes"]; lanes && std::atoi(lanes) > 0) width = 3.5 * std::atoi(lanes);
    OsmFeature f{"road", *road, std::clamp(width, 1.0, 100.0), name(tags), file_ + " way " + std::to_string(way.id()), {}, line(way)};
    if (f.line.size() < 2) return ++skipped_["ways without located nodes"], void();
    roads_.push_back(std::move(f));
  }

  void area(const osmium::Area& area) {
    const std::optional<std::string> zone = zone_type(area.tags());
    if (!zone) return;
    OsmFeature f{"zone", *zone, 0, name(area.tags()),
                 file_ + (area.from_way() ? " way " : " relation ") + std::to_string(area.orig_id()), {}, {}};
    for (const osmium::OuterRing& outer : area.outer_rings()) {
      f.polygons.push_back({ring(outer), {}});
      for (const osmium::InnerRing& inner : area.inner_rings(outer)) f.polygons.back().second.push_back(ring(inner));
    }
    if (!f.polygons.empty()) zones_.push_back(std::move(f));
  }

  std::vector<OsmFeature> zones_, roads_, rivers_;
  std::map<std::string, int> skipped_;

 private:
  static std::string name(const osmium::TagList& tags) { return tags["name"] ? tags["name"] : ""; }
  template <typename Nodes>
  static LonLat points(const Nodes& nodes) {
    LonLat out;
    for (const osmium::NodeRef& n : nodes)
      if (n.location().valid()) out.push_back({n.location().lon(), n.location().lat()});
    return out;
  }
  static LonLat line(const osmium::Way& way) { return points(way.nodes()); }
  template <typename Ring>
  static LonLat ring(const Ring& r) { return points(r); }

  std::string file_;
};

ordered_json position(std::pair<double, double> p) { return {p.first, p.second}; }

ordered_json ring_json(const LonLat& r) {
  ordered_json out = ordered_json::array();
  for (const auto& p : r) out.push_back(position(p));
  return out;
}

}  // namespace

ordered_json osm_sketch_document(const fs::path& path) {
  const std::string file = path.string();
  Collector collector(file);
  try {
    const osmium::io::File input(file);
    osmium::area::Assembler::config_type config;
    osmium::TagsFilter areas{false};
    for (const char* key : {"landuse", "natural", "water", "waterway", "leisure"}) areas.add_rule(true, osmium::TagMatcher{key});
    osmium::area::MultipolygonManager<osmium::area::Assembler> multipolygons{config, areas};
    osmium::relations::read_relations(input, multipolygons);
    using Index = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
    Index index;
    osmium::handler::NodeLocationsForWays<Index> locations{index};
    locations.ignore_errors();  // an extract cut at its edge lacks some nodes
    osmium::io::Reader reader{input, osmium::osm_entity_bits::node | osmium::osm_entity_bits::way |
                                         osmium::osm_entity_bits::relation};
    osmium::apply(reader, locations, collector, multipolygons.handler([&](osmium::memory::Buffer&& buffer) {
      osmium::apply(buffer, collector);
    }));
    reader.close();
  } catch (const std::exception& e) {
    throw UserError(file + ": not a readable OpenStreetMap extract (" + e.what() + "); give an .osm or .osm.pbf file");
  }
  if (collector.zones_.empty() && collector.roads_.empty() && collector.rivers_.empty())
    throw UserError(file + ": the extract has no highways, land use or water Exacity reads; see the README's OpenStreetMap section");

  ordered_json features = ordered_json::array();
  auto properties = [](const OsmFeature& f) {
    ordered_json p = {{f.kind, f.type}};
    if (f.kind == "road") p["width"] = f.width;
    if (!f.name.empty()) p["name"] = f.name;
    p["source"] = f.source;
    return p;
  };
  // Land use first, then parks, then water: where areas overlap the later wins, so water
  // keeps its banks and a park inside a residential area stays a park.
  std::stable_sort(collector.zones_.begin(), collector.zones_.end(), [](const OsmFeature& a, const OsmFeature& b) {
    auto rank = [](const std::string& t) { return t == "water" ? 2 : t == "park" ? 1 : 0; };
    return rank(a.type) < rank(b.type);
  });
  for (OsmFeature& f : collector.zones_) {
    ordered_json polygons = ordered_json::array();
    for (auto& [outer, holes] : f.polygons) {
      ordered_json rings = ordered_json::array({ring_json(outer)});
      for (const LonLat& h : holes) rings.push_back(ring_json(h));
      polygons.push_back(std::move(rings));
    }
    features.push_back({{"type", "Feature"}, {"properties", properties(f)},
                        {"geometry", {{"type", "MultiPolygon"}, {"coordinates", std::move(polygons)}}}});
  }
  // A river is its centre line made as wide as it is (GEOS, through OGR), in metres: in
  // the UTM zone of its middle, and back.
  for (OsmFeature& f : collector.rivers_) {
    OGRLineString line;
    for (auto [lon, lat] : f.line) line.addPoint(lon, lat);
    OGREnvelope box;
    line.getEnvelope(&box);
    OGRSpatialReference wgs84, utm;
    wgs84.importFromEPSG(4326), utm.importFromEPSG(utm_epsg((box.MinX + box.MaxX) / 2, (box.MinY + box.MaxY) / 2));
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER), utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> to_utm(OGRCreateCoordinateTransformation(&wgs84, &utm));
    std::unique_ptr<OGRCoordinateTransformation> back(OGRCreateCoordinateTransformation(&utm, &wgs84));
    std::unique_ptr<OGRGeometry> water;
    if (to_utm && back && line.transform(to_utm.get()) == OGRERR_NONE) water.reset(line.Buffer(f.width / 2, 4));
    if (!water || water->IsEmpty() || water->transform(back.get()) != OGRERR_NONE) {
      ++collector.skipped_["rivers PROJ or GEOS could not widen"];
      continue;
    }
    char* text = water->exportToJson();
    features.push_back({{"type", "Feature"}, {"properties", properties(f)}, {"geometry", ordered_json::parse(text)}});
    CPLFree(text);
  }
  for (const OsmFeature& f : collector.roads_)
    features.push_back({{"type", "Feature"}, {"properties", properties(f)},
                        {"geometry", {{"type", "LineString"}, {"coordinates", ring_json(f.line)}}}});
  ordered_json taken = {{"zones", collector.zones_.size()}, {"roads", collector.roads_.size()}, {"rivers", collector.rivers_.size()}};
  ordered_json skipped = ordered_json::object();
  for (const auto& [what, count] : collector.skipped_) skipped[what] = count;
  return {{"type", "FeatureCollection"},
          {"crs", crs_member(4326)},
          {"osm", {{"file", file}, {"taken", taken}, {"skipped", skipped}}},
          {"features", std::move(features)}};
}

}  // namespace exacity
