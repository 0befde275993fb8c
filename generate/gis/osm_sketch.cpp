// OpenStreetMap extracts as sketches (docs/design.md, The sketch, GIS and OSM), read with
// libosmium: multipolygon relations and closed ways assembled into areas by its
// MultipolygonManager, way node locations from a node index.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string_view>
#include <tuple>
#include <vector>

#include <osmium/area/assembler.hpp>
#include <osmium/area/multipolygon_manager.hpp>
#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/object_pointer_collection.hpp>
#include <osmium/osm/box.hpp>
#include <osmium/osm/object_comparisons.hpp>
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

// A way's located nodes: node ids, to chain ways into rings, and positions.
struct WayNodes {
  std::vector<osmium::object_id_type> ids;
  LonLat points;
};

// A feature's properties: its tags among osm_keys() (a road's among osm_road_keys() too)
// and its name.
ordered_json osm_properties(const osmium::TagList& tags, bool road) {
  ordered_json p = ordered_json::object();
  for (const std::string& key : osm_keys())
    if (const char* v = tags[key.c_str()]) p[key] = v;
  for (const std::string& key : road ? osm_road_keys() : std::vector<std::string>{"name"})
    if (const char* v = tags[key.c_str()]; v && !p.contains(key)) p[key] = v;
  return p;
}

// A multipolygon relation whose tags make a zone, or a way with such tags that is not
// closed: kept in case osmium cannot assemble its area (the extract cut its outer way, or
// left members out).
struct ZoneRelation {
  ordered_json properties;
  std::vector<osmium::object_id_type> outer, inner;
};

// The first pass: the multipolygon relations whose tags make a zone.
class ZoneRelations : public osmium::handler::Handler {
 public:
  void relation(const osmium::Relation& relation) {
    const osmium::TagList& tags = relation.tags();
    if (!tags.has_tag("type", "multipolygon") || osm_area_meaning(lookup(tags)).kind != OsmMeaning::Zone) return;
    ZoneRelation& r = relations_[relation.id()];
    r.properties = osm_properties(tags, false);
    for (const osmium::RelationMember& m : relation.members()) {
      if (m.type() != osmium::item_type::way) continue;
      (std::string(m.role()) == "inner" ? r.inner : r.outer).push_back(m.ref());
      member_ways_.insert(m.ref());
    }
  }
  std::map<osmium::object_id_type, ZoneRelation> relations_;
  std::set<osmium::object_id_type> member_ways_;
};

// Chains ways into rings by their shared end nodes: closed rings, and open chains.
std::vector<WayNodes> chained(std::vector<WayNodes> ways) {
  std::vector<WayNodes> out;
  while (!ways.empty()) {
    WayNodes chain = std::move(ways.back());
    ways.pop_back();
    for (bool grown = true; grown && chain.ids.front() != chain.ids.back();) {
      grown = false;
      for (std::size_t i = 0; i < ways.size(); ++i) {
        WayNodes& w = ways[i];
        if (w.ids.front() != chain.ids.back() && w.ids.back() != chain.ids.back()) {
          if (w.ids.front() != chain.ids.front() && w.ids.back() != chain.ids.front()) continue;
          std::reverse(chain.ids.begin(), chain.ids.end());  // grow at the other end
          std::reverse(chain.points.begin(), chain.points.end());
        }
        if (w.ids.front() != chain.ids.back()) {
          std::reverse(w.ids.begin(), w.ids.end());
          std::reverse(w.points.begin(), w.points.end());
        }
        chain.ids.insert(chain.ids.end(), w.ids.begin() + 1, w.ids.end());
        chain.points.insert(chain.points.end(), w.points.begin() + 1, w.points.end());
        ways.erase(ways.begin() + static_cast<std::ptrdiff_t>(i));
        grown = true;
        break;
      }
    }
    out.push_back(std::move(chain));
  }
  return out;
}

double ring_area(const LonLat& r) {
  double a = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const auto &u = r[i], &v = r[(i + 1) % r.size()];
    a += (u.first - r[0].first) * (v.second - r[0].second) - (v.first - r[0].first) * (u.second - r[0].second);
  }
  return a / 2;
}

// An open chain the extract's edge cut, closed along the edge (`box`) both ways: each end
// goes on in its last segment's direction to the box, and the box's outline joins the two
// points there, round one side or the other (OSM's rings have no orientation to say which
// side the area lies on, and the extract holds the area only up to its edge).
std::array<LonLat, 2> closed_along(const LonLat& chain, const osmium::Box& box) {
  const double x0 = box.bottom_left().lon(), y0 = box.bottom_left().lat(), x1 = box.top_right().lon(),
               y1 = box.top_right().lat();
  const double w = x1 - x0, h = y1 - y0;
  // Where a ray from `from` through `end` leaves the box (from the nearest point of the box
  // to `end`, if outside it), exactly on the side it leaves by.
  auto exit = [&](std::pair<double, double> from, std::pair<double, double> end) {
    const double x = std::clamp(end.first, x0, x1), y = std::clamp(end.second, y0, y1);
    const double dx = end.first - from.first, dy = end.second - from.second;
    // The sides by their distance along the ray: bottom, right, top, left.
    const double t[] = {dy < 0 ? (y0 - y) / dy : INFINITY, dx > 0 ? (x1 - x) / dx : INFINITY,
                        dy > 0 ? (y1 - y) / dy : INFINITY, dx < 0 ? (x0 - x) / dx : INFINITY};
    const int side = static_cast<int>(std::min_element(std::begin(t), std::end(t)) - std::begin(t));
    const double s = std::isfinite(t[side]) ? t[side] : 0;
    std::pair<double, double> p{std::clamp(x + s * dx, x0, x1), std::clamp(y + s * dy, y0, y1)};
    if (side == 0) p.second = y0;
    else if (side == 1) p.first = x1;
    else if (side == 2) p.second = y1;
    else p.first = x0;
    return p;
  };
  // A point of the outline's place along it, counter-clockwise from the lower left corner.
  auto along = [&](std::pair<double, double> p) {
    const auto [x, y] = p;
    if (y == y0) return x - x0;
    if (x == x1) return w + (y - y0);
    if (y == y1) return w + h + (x1 - x);
    return 2 * w + h + (y1 - y);
  };
  const std::pair<double, double> corners[] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  const double corner_at[] = {0, w, w + h, 2 * w + h}, perimeter = 2 * (w + h);
  const auto from = exit(chain[chain.size() - 2], chain.back()), to = exit(chain[1], chain.front());
  std::array<LonLat, 2> rings;
  for (const int direction : {1, -1}) {
    LonLat& ring = rings[direction > 0 ? 0 : 1];
    ring = chain;
    if (from != chain.back()) ring.push_back(from);
    // The corners passed going from `from` to `to` that way round.
    const double a = along(from), b = along(to);
    double span = direction > 0 ? b - a : a - b;
    if (span < 0) span += perimeter;
    std::vector<std::pair<double, std::pair<double, double>>> passed;
    for (int c = 0; c < 4; ++c) {
      double d = direction > 0 ? corner_at[c] - a : a - corner_at[c];
      if (d < 0) d += perimeter;
      if (d > 0 && d < span) passed.push_back({d, corners[c]});
    }
    std::sort(passed.begin(), passed.end());
    for (const auto& [d, corner] : passed) ring.push_back(corner);
    if (to != chain.front()) ring.push_back(to);
    ring.push_back(chain.front());
  }
  return rings;
}

bool inside(std::pair<double, double> p, const LonLat& ring) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const auto &a = ring[i], &b = ring[j];
    if ((a.second > p.second) != (b.second > p.second) &&
        p.first < (b.first - a.first) * (p.second - a.second) / (b.second - a.second) + a.first)
      in = !in;
  }
  return in;
}

// What the extract makes, and what it leaves out and why (the document's "osm" member).
class Collector : public osmium::handler::Handler {
 public:
  Collector(std::string file, const ZoneRelations& relations) : file_(std::move(file)), relations_(relations) {}

  void node(const osmium::Node& node) {
    const osmium::Location l = node.location();
    if (!l) return;
    if (!l.valid())
      throw UserError(file_ + ": node " + std::to_string(node.id()) + " lies at lon " + std::to_string(l.lon_without_check()) +
                      ", lat " + std::to_string(l.lat_without_check()) +
                      ", outside -180 to 180 and -90 to 90; correct or delete the node");
    nodes_box_.extend(l);
  }

  void way(const osmium::Way& way) {
    const osmium::TagList& tags = way.tags();
    if (way.nodes().empty()) return;
    const bool member = relations_.member_ways_.count(way.id()) > 0;
    if (member) member_ways_[way.id()] = way_nodes(way);
    // An area tag on a way the extract cut open: closed along its edge, as a relation's ring.
    if (!member && !tags["highway"] && !tags["waterway"] && !way.is_closed() &&
        osm_area_meaning(lookup(tags)).kind == OsmMeaning::Zone)
      return cut_ways_.push_back({way.id(), {osm_properties(tags, false), {}, {}}, way_nodes(way)}), void();
    // A building way is its footprint, node for node, whatever osmium's assembler makes of
    // its ring (it gives none for a self-intersecting one, which the city repairs or refuses);
    // a building:part's the same.
    if (const OsmMeaning::Kind kind = osm_area_meaning(lookup(tags)).kind;
        !tags["highway"] && (kind == OsmMeaning::Building || kind == OsmMeaning::BuildingPart)) {
      const bool part = kind == OsmMeaning::BuildingPart;
      const std::string buildings = part ? "building:parts" : "buildings";
      if (!way.is_closed()) return ++skipped_[buildings + " whose way is not closed"], void();
      const std::string what = "way " + std::to_string(way.id());
      OsmFeature f{building_properties(tags, what, part), {{points(way.nodes()), {}}}, {}};
      if (f.polygons[0].first.size() != way.nodes().size()) return ++skipped_[buildings + " with nodes the extract lacks"], void();
      if (!part) also_a_part(tags, f);
      return (part ? parts_ : buildings_).push_back(std::move(f));
    }
    // A closed way tagged only as an area (waterway=riverbank) is the area handler's.
    if (!tags["highway"] && !(tags["waterway"] && !way.is_closed())) return;
    const OsmMeaning meaning = osm_line_meaning(lookup(tags));
    // A footway is kept for apply_osm_tags to see whether it bounds land.
    if (meaning.kind == OsmMeaning::LeftOut && !meaning.road_where_it_bounds_land) return ++skipped_[meaning.why], void();
    OsmFeature f{properties(tags, " way " + std::to_string(way.id()), true), {}, points(way.nodes())};
    f.properties["osm_id"] = "way/" + std::to_string(way.id());
    if (f.line.size() < 2) return ++skipped_["ways without located nodes"], void();
    (meaning.kind == OsmMeaning::River ? rivers_ : roads_).push_back(std::move(f));
  }

  void area(const osmium::Area& area) {
    const OsmMeaning meaning = osm_area_meaning(lookup(area.tags()));
    if (meaning.kind == OsmMeaning::LeftOut) return ++skipped_[meaning.why], void();
    const bool building = meaning.kind == OsmMeaning::Building || meaning.kind == OsmMeaning::BuildingPart;
    if (meaning.kind != OsmMeaning::Zone && !building) return;
    if (building && area.from_way()) return;  // the way handler's
    const std::string what = (area.from_way() ? "way " : "relation ") + std::to_string(area.orig_id());
    OsmFeature f{properties(area.tags(), " " + what), {}, {}};
    if (building) f.properties = building_properties(area.tags(), what, meaning.kind == OsmMeaning::BuildingPart);
    for (const osmium::OuterRing& outer : area.outer_rings()) {
      f.polygons.push_back({points(outer), {}});
      for (const osmium::InnerRing& inner : area.inner_rings(outer)) f.polygons.back().second.push_back(points(inner));
    }
    if (f.polygons.empty()) {
      // A relation is mended from its member ways below; a way's rings are beyond that.
      if (building)
        ++skipped_[(meaning.kind == OsmMeaning::Building ? "building" : "building:part") +
                   std::string(" relations whose rings osmium could not assemble")];
      else if (area.from_way()) ++skipped_["areas whose rings osmium could not assemble"];
      return;
    }
    if (meaning.kind == OsmMeaning::Building) {
      also_a_part(area.tags(), f);
      return buildings_.push_back(std::move(f));
    }
    if (meaning.kind == OsmMeaning::BuildingPart) return parts_.push_back(std::move(f));
    if (!area.from_way()) assembled_.insert(area.orig_id());
    zones_.push_back(std::move(f));
  }

  // The relations osmium could not assemble (a ring left open where the extract cut its
  // outer way, or members the extract left out) and the area ways it cut open, closed along
  // the extract's edge (`box`): each named in `repaired_`, or counted in `skipped_`.
  void mend(const osmium::Box& box) {
    for (const auto& [id, relation] : relations_.relations_) {
      if (assembled_.count(id)) continue;
      std::vector<WayNodes> outer, inner;
      for (const auto& [ids, rings] : {std::pair{&relation.outer, &outer}, std::pair{&relation.inner, &inner}})
        for (osmium::object_id_type way : *ids)
          if (auto it = member_ways_.find(way); it != member_ways_.end() && it->second.ids.size() >= 2) rings->push_back(it->second);
      mend_rings("relation " + std::to_string(id), relation.properties, std::move(outer), std::move(inner), box);
    }
    for (auto& [id, way, nodes] : cut_ways_)
      if (nodes.ids.size() >= 2) mend_rings("way " + std::to_string(id), way.properties, {std::move(nodes)}, {}, box);
  }

  std::vector<OsmFeature> zones_, roads_, rivers_, buildings_, parts_;
  std::map<std::string, int> skipped_;
  std::vector<std::string> repaired_;
  osmium::Box nodes_box_;

 private:
  void mend_rings(const std::string& what, const ordered_json& tags, std::vector<WayNodes> outer, std::vector<WayNodes> inner,
                  const osmium::Box& box) {
    OsmFeature f{tags, {}, {}};
    f.properties["source"] = file_ + " " + what;
    int cut = 0;
    for (WayNodes& ring : chained(std::move(outer))) {
      if (ring.ids.front() == ring.ids.back()) {
        if (ring.points.size() >= 4) f.polygons.push_back({std::move(ring.points), {}});
      } else if (box.valid() && ring.points.size() >= 2) {
        f.polygons.push_back({side_of(tags, closed_along(ring.points, box)), {}});
        ++cut;
      }
    }
    for (WayNodes& ring : chained(std::move(inner)))
      if (ring.ids.front() == ring.ids.back() && ring.points.size() >= 4)
        for (auto& polygon : f.polygons)
          if (inside(ring.points.front(), polygon.first)) {
            polygon.second.push_back(std::move(ring.points));
            break;
          }
    if (f.polygons.empty()) return ++skipped_["multipolygons without a way in the extract"], void();
    repaired_.push_back(what + " (" + zone_tag(tags) + "): " +
                        (cut ? "its outer ring, cut by the extract's edge, closed along the edge"
                             : "its rings assembled from the member ways the extract holds"));
    zones_.push_back(std::move(f));
  }

  // Which of a cut ring's two closings is the area's: built-up land use (residential,
  // commercial, industrial) lies where the mapped buildings stand, a park, forest or water
  // where they do not; where the buildings do not tell (none on either side, or as many),
  // the side that encloses less. In the extract a village's residential land and the forest
  // beside it, cut by the same edge, share one boundary and lie on its two sides.
  LonLat side_of(const ordered_json& tags, std::array<LonLat, 2> closings) const {
    const OsmMeaning meaning = osm_area_meaning([&](const std::string& key) -> std::optional<std::string> {
      if (tags.contains(key) && tags[key].is_string()) return tags[key].get<std::string>();
      return std::nullopt;
    });
    const bool built_up = meaning.type == "residential" || meaning.type == "commercial" || meaning.type == "industrial";
    int held[2] = {0, 0};
    for (const OsmFeature& b : buildings_)
      for (const auto& [outer, holes] : b.polygons) {
        if (outer.empty()) continue;
        std::pair<double, double> centre{0, 0};
        for (const auto& [x, y] : outer) centre.first += x / outer.size(), centre.second += y / outer.size();
        for (int k = 0; k < 2; ++k) held[k] += inside(centre, closings[k]);
      }
    int pick = std::abs(ring_area(closings[1])) < std::abs(ring_area(closings[0]));
    if (held[0] != held[1]) pick = (held[1] > held[0]) == built_up;
    return std::move(closings[pick]);
  }

  // A building tagged building:part too is one of its own parts (Simple 3D Buildings: its
  // volume beside the parts mapped in it).
  void also_a_part(const osmium::TagList& tags, const OsmFeature& building) {
    const char* part = tags["building:part"];
    if (!part || std::string(part) == "no") return;
    OsmFeature f = building;
    f.properties.erase("building");
    f.properties["building:part"] = part;
    parts_.push_back(std::move(f));
  }

  static std::string zone_tag(const ordered_json& tags) {
    for (const char* key : {"landuse", "leisure", "natural", "water", "waterway"})
      if (tags.contains(key) && tags[key].is_string()) return std::string(key) + "=" + tags[key].get<std::string>();
    return "area";
  }

  // A building's: its building tag (a part's building:part tag), the tags it is raised
  // from, its name and its OSM id.
  ordered_json building_properties(const osmium::TagList& tags, const std::string& what, bool part) const {
    const char* key = part ? "building:part" : "building";
    ordered_json p{{key, tags[key]}};
    for (const std::string& key : osm_building_keys())
      if (const char* v = tags[key.c_str()]) p[key] = v;
    if (const char* name = tags["name"]) p["name"] = name;
    std::string id = what;
    id[id.find(' ')] = '/';
    p["osm_id"] = id;
    p["source"] = file_ + " " + what;
    return p;
  }
  ordered_json properties(const osmium::TagList& tags, const std::string& what, bool road = false) const {
    ordered_json p = osm_properties(tags, road);
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
  WayNodes way_nodes(const osmium::Way& way) const {
    WayNodes out;
    for (const osmium::NodeRef& n : way.nodes())
      if (n.location().valid()) out.ids.push_back(n.ref()), out.points.push_back({n.location().lon(), n.location().lat()});
    return out;
  }

  std::string file_;
  const ZoneRelations& relations_;
  std::map<osmium::object_id_type, WayNodes> member_ways_;
  std::set<osmium::object_id_type> assembled_;
  std::vector<std::tuple<osmium::object_id_type, ZoneRelation, WayNodes>> cut_ways_;
};

ordered_json position(std::pair<double, double> p) { return {p.first, p.second}; }

ordered_json ring_json(const LonLat& r) {
  ordered_json out = ordered_json::array();
  for (const auto& p : r) out.push_back(position(p));
  return out;
}

// OSM XML's node coordinates as written: libosmium reads a latitude of "1e308" as 0 (its
// digits overflow), so every node's lat and lon are read again here and one out of range
// is refused, naming the node. A start tag is everything up to the next '>' ('<' cannot
// stand in an attribute's value, so "<node " starts a node's tag).
void check_node_coordinates(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  auto attribute = [](const std::string& tag, const char* name) -> std::optional<std::string> {
    const std::string key = std::string(" ") + name + "=";
    std::size_t at = tag.find(key);
    if (at == std::string::npos) {
      std::string tabbed = key;
      for (const char space : {'\t', '\n', '\r'}) {
        tabbed[0] = space;
        if ((at = tag.find(tabbed)) != std::string::npos) break;
      }
      if (at == std::string::npos) return std::nullopt;
    }
    at += key.size();
    if (at >= tag.size() || (tag[at] != '"' && tag[at] != '\'')) return std::nullopt;
    const std::size_t end = tag.find(tag[at], at + 1);
    if (end == std::string::npos) return std::nullopt;
    return tag.substr(at + 1, end - at - 1);
  };
  for (std::string tag; std::getline(in, tag, '>');) {
    const std::size_t start = tag.find('<');
    if (start == std::string::npos || tag.compare(start, 6, "<node ") != 0) continue;
    for (auto [name, limit] : {std::pair{"lat", 90.0}, std::pair{"lon", 180.0}}) {
      const std::optional<std::string> text = attribute(tag, name);
      if (!text) continue;
      char* end = nullptr;
      const double v = std::strtod(text->c_str(), &end);
      if (end == text->c_str() || *end) continue;  // libosmium refuses what is not a number
      if (!(std::abs(v) <= limit))
        throw UserError(path.string() + ": node " + attribute(tag, "id").value_or("?") + " has " + name + "=\"" + *text +
                        "\", outside -" + std::to_string(static_cast<int>(limit)) + " to " + std::to_string(static_cast<int>(limit)) + "; correct or delete the node");
    }
  }
}

}  // namespace

// The extract's objects in libosmium's order (nodes, ways, relations; negative ids first),
// which its relation and area code relies on. Files of new objects are often in another:
// city.osm counts its negative ids up, as `osmium merge` wants, and JOSM writes in any order.
// The extract is held in memory whole; the input size limit bounds it.
osmium::memory::Buffer in_osmium_order(osmium::io::Reader& reader) {
  std::vector<osmium::memory::Buffer> read;
  osmium::ObjectPointerCollection objects;
  std::size_t bytes = 0;
  while (osmium::memory::Buffer buffer = reader.read()) {
    osmium::apply(buffer, objects);
    bytes += buffer.committed();
    read.push_back(std::move(buffer));
  }
  objects.sort(osmium::object_order_type_id_version{});
  osmium::memory::Buffer sorted{std::max<std::size_t>(bytes, 1024), osmium::memory::Buffer::auto_grow::yes};
  for (const osmium::OSMObject& object : objects) sorted.add_item(object);
  sorted.commit();
  return sorted;
}

// Whether the file holds an OpenStreetMap PBF, by its first blob's header (a length, then
// the type "OSMHeader"), whatever its name: test data and downloads are saved as .osm too.
namespace {
bool holds_pbf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char head[15] = {};
  in.read(head, sizeof head);
  return in.gcount() == sizeof head && head[4] == '\x0a' && head[5] == '\x09' && std::string_view(head + 6, 9) == "OSMHeader";
}
}  // namespace

ordered_json osm_sketch_document(const fs::path& path) {
  const std::string file = path.string();
  const bool pbf = holds_pbf(path);
  if (!pbf && path.extension() == ".osm") check_node_coordinates(path);
  ZoneRelations relations;
  Collector collector(file, relations);
  try {
    const osmium::io::File input(file, pbf ? "pbf" : "");
    osmium::io::Reader reader{input};
    const osmium::Box bounds = reader.header().box();
    osmium::memory::Buffer extract = in_osmium_order(reader);
    reader.close();
    osmium::area::Assembler::config_type config;
    osmium::TagsFilter areas{false};
    for (const char* key : {"landuse", "natural", "water", "waterway", "leisure", "building", "building:part"})
      areas.add_rule(true, osmium::TagMatcher{key});
    osmium::area::MultipolygonManager<osmium::area::Assembler> multipolygons{config, areas};
    osmium::apply(extract, multipolygons, relations);
    multipolygons.prepare_for_lookup();
    using Index = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
    Index index, negative_index;  // new objects carry negative ids (JOSM's and city.osm's)
    osmium::handler::NodeLocationsForWays<Index, Index> locations{index, negative_index};
    locations.ignore_errors();  // an extract cut at its edge lacks some nodes
    osmium::apply(extract, locations, collector, multipolygons.handler([&](osmium::memory::Buffer&& buffer) {
      osmium::apply(buffer, collector);
    }));
    // The extract's edge: its <bounds>, else the box around its nodes.
    collector.mend(bounds.valid() ? bounds : collector.nodes_box_);
  } catch (const UserError&) {
    throw;
  } catch (const std::exception& e) {
    throw UserError(file + ": not a readable OpenStreetMap extract (" + e.what() + "); give an .osm or .osm.pbf file");
  }
  if (collector.zones_.empty() && collector.roads_.empty() && collector.rivers_.empty())
    throw UserError(file + ": the extract has no highways, land use or water Exacity reads; see docs/gis.md");

  ordered_json features = ordered_json::array();
  // Buildings and their parts after the zones: the sketch reader keeps them apart, in this order.
  for (auto* areas : {&collector.zones_, &collector.buildings_, &collector.parts_})
    for (OsmFeature& f : *areas) {
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
  ordered_json osm{{"file", file}, {"skipped", skipped}};
  if (!collector.repaired_.empty()) osm["repaired"] = collector.repaired_;
  return {{"type", "FeatureCollection"}, {"crs", crs_member(4326)}, {"osm", std::move(osm)}, {"features", std::move(features)}};
}

}  // namespace exacity
