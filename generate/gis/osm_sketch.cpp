// OpenStreetMap extracts as sketches (docs/design.md, The sketch, GIS and OSM), read with
// libosmium: multipolygon relations and closed ways assembled into areas by its
// MultipolygonManager, way node locations from a node index.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

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
#include "generate/gis/osm_tags.h"
#include "generate/gis/projection.h"
#include "generate/gis/sketch_sources.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace {

using LonLat = std::vector<std::pair<double, double>>;

OsmTags lookup(const osmium::TagList& tags) {
  return [&tags](const std::string& key) -> std::optional<std::string> {
    const char* v = tags[key.c_str()];
    return v ? std::optional<std::string>(v) : std::nullopt;
  };
}

// A feature as OSM has it: its tags among osm_keys(), its name and where it came from;
// apply_osm_tags makes zones and roads of them, as of any OSM-tagged feature.
struct OsmFeature {
  ordered_json properties;
  std::vector<std::pair<LonLat, std::vector<LonLat>>> polygons;  // areas: outer ring, holes
  LonLat line;                                                    // ways
};

// What the extract makes, and what it leaves out and why (the document's "osm" member).
class Collector : public osmium::handler::Handler {
 public:
  explicit Collector(std::string file) : file_(std::move(file)) {}

  void way(const osmium::Way& way) {
    const osmium::TagList& tags = way.tags();
    // A closed way tagged only as an area (waterway=riverbank) is the area handler's.
    if (!tags["highway"] && !(tags["waterway"] && !way.is_closed())) return;
    const OsmMeaning meaning = osm_line_meaning(lookup(tags));
    if (meaning.kind == OsmMeaning::LeftOut) return ++skipped_[meaning.why], void();
    OsmFeature f{properties(tags, " way " + std::to_string(way.id())), {}, points(way.nodes())};
    if (f.line.size() < 2) return ++skipped_["ways without located nodes"], void();
    (meaning.kind == OsmMeaning::River ? rivers_ : roads_).push_back(std::move(f));
  }

  void area(const osmium::Area& area) {
    const OsmMeaning meaning = osm_area_meaning(lookup(area.tags()));
    if (meaning.kind == OsmMeaning::LeftOut) return ++skipped_[meaning.why], void();
    if (meaning.kind != OsmMeaning::Zone) return;
    OsmFeature f{properties(area.tags(), (area.from_way() ? " way " : " relation ") + std::to_string(area.orig_id())), {}, {}};
    for (const osmium::OuterRing& outer : area.outer_rings()) {
      f.polygons.push_back({points(outer), {}});
      for (const osmium::InnerRing& inner : area.inner_rings(outer)) f.polygons.back().second.push_back(points(inner));
    }
    if (!f.polygons.empty()) zones_.push_back(std::move(f));
  }

  std::vector<OsmFeature> zones_, roads_, rivers_;
  std::map<std::string, int> skipped_;

 private:
  ordered_json properties(const osmium::TagList& tags, const std::string& what) const {
    ordered_json p = ordered_json::object();
    for (const std::string& key : osm_keys())
      if (const char* v = tags[key.c_str()]) p[key] = v;
    if (const char* name = tags["name"]) p["name"] = name;
    p["source"] = file_ + what;
    return p;
  }
  template <typename Nodes>
  static LonLat points(const Nodes& nodes) {
    LonLat out;
    for (const osmium::NodeRef& n : nodes)
      if (n.location().valid()) out.push_back({n.location().lon(), n.location().lat()});
    return out;
  }

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
  for (OsmFeature& f : collector.zones_) {
    ordered_json polygons = ordered_json::array();
    for (auto& [outer, holes] : f.polygons) {
      ordered_json rings = ordered_json::array({ring_json(outer)});
      for (const LonLat& h : holes) rings.push_back(ring_json(h));
      polygons.push_back(std::move(rings));
    }
    features.push_back({{"type", "Feature"}, {"properties", std::move(f.properties)},
                        {"geometry", {{"type", "MultiPolygon"}, {"coordinates", std::move(polygons)}}}});
  }
  for (auto* lines : {&collector.rivers_, &collector.roads_})
    for (OsmFeature& f : *lines)
      features.push_back({{"type", "Feature"}, {"properties", std::move(f.properties)},
                          {"geometry", {{"type", "LineString"}, {"coordinates", ring_json(f.line)}}}});
  ordered_json skipped = ordered_json::object();
  for (const auto& [what, count] : collector.skipped_) skipped[what] = count;
  return {{"type", "FeatureCollection"},
          {"crs", crs_member(4326)},
          {"osm", {{"file", file}, {"skipped", skipped}}},
          {"features", std::move(features)}};
}

}  // namespace exacity
