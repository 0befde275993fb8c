#include "generate/export/statistics.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "generate/cancel.h"
#include "generate/errors.h"
#include "generate/gis/projection.h"
#include "generate/input_file.h"
#include "generate/parcels/lots.h"
#include "geom/measure.h"
#include "geom/segment_index.h"

namespace exacity {
namespace {

using geom::Vec2;
using nlohmann::ordered_json;

constexpr double kSharpAngle = 30;   // degrees
constexpr double kNarrow = 5;        // m
constexpr double kOversized = 4;     // times the zone's block_area
constexpr double kOnEdge = 1e-6;     // m: an end this close to the drawn city's edge lies on it

ordered_json summary(std::vector<double> v) {
  if (v.empty()) return {{"count", 0}};
  std::sort(v.begin(), v.end());
  auto at = [&](double q) { return v[static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1]; };
  auto round = [](double x) { return std::round(x * 10) / 10; };
  return {{"count", v.size()}, {"median", round(at(0.5))}, {"p95", round(at(0.95))}, {"max", round(v.back())}};
}

double share(std::size_t part, std::size_t whole) {
  return whole ? std::round(1e4 * static_cast<double>(part) / static_cast<double>(whole)) / 1e4 : 0;
}

// The smallest interior angle of the outer ring, in degrees (vertices in line skipped).
double sharpest_angle(const geom::Ring& ring) {
  const std::size_t n = ring.size();
  const double orientation = geom::signed_area(ring) < 0 ? -1 : 1;
  double sharpest = 180;
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 a = ring[(i + n - 1) % n], o = ring[i], b = ring[(i + 1) % n];
    double ux = o.x - a.x, uy = o.y - a.y, vx = b.x - o.x, vy = b.y - o.y;
    double turn = std::atan2(ux * vy - uy * vx, ux * vx + uy * vy) * orientation;
    if (std::abs(turn) < 1e-9) continue;
    sharpest = std::min(sharpest, 180 - turn * 180 / M_PI);
  }
  return sharpest;
}

// The least width of the ring: the smallest extent across its convex hull, over the hull's
// edge directions (rotating calipers).
double least_width(const geom::Ring& ring) {
  std::vector<Vec2> p = ring;
  std::sort(p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  auto cross = [](Vec2 o, Vec2 a, Vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
  std::vector<Vec2> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  double best = INFINITY;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    Vec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    double len = std::hypot(b.x - a.x, b.y - a.y), widest = 0;
    if (len == 0) continue;
    for (Vec2 q : hull) widest = std::max(widest, std::abs(cross(a, b, q)) / len);
    best = std::min(best, widest);
  }
  return std::isfinite(best) ? best : 0;
}

struct SegmentHash {
  std::size_t operator()(const std::pair<Vec2, Vec2>& s) const { return geom::Vec2Hash()(s.first) * 17 ^ geom::Vec2Hash()(s.second); }
};
std::pair<Vec2, Vec2> undirected(Vec2 a, Vec2 b) {
  return (a.x < b.x || (a.x == b.x && a.y < b.y)) ? std::pair{a, b} : std::pair{b, a};
}

// Footprints' areas and how many have a sharp corner or are narrow.
struct FootprintTally {
  std::vector<double> areas;
  std::size_t sharp = 0, narrow = 0;
};

struct FootprintMeasure {
  double area;
  bool sharp, narrow;
};

FootprintMeasure measure_footprint(const geom::Polygon& p) {
  return {geom::area(p), sharpest_angle(p.outer) < kSharpAngle, least_width(p.outer) < kNarrow};
}

void add(FootprintTally& t, const FootprintMeasure& m) {
  t.areas.push_back(m.area);
  t.sharp += m.sharp;
  t.narrow += m.narrow;
}

ordered_json footprint_figures(const FootprintTally& t) {
  return {{"area_m2", summary(t.areas)},
          {"share_sharp_angle", share(t.sharp, t.areas.size())},
          {"share_under_5m_across", share(t.narrow, t.areas.size())}};
}

// Junctions by degree, dead ends (ends that meet nothing and are not on the city's edge),
// length and densities per km2 of `area_m2`.
ordered_json street_figures(const std::vector<const geom::Polyline*>& lines, double area_m2,
                            const std::function<bool(Vec2)>& on_edge) {
  std::unordered_map<Vec2, int, geom::Vec2Hash> degree;
  double length = 0;
  for (const geom::Polyline* l : lines)
    for (std::size_t i = 0; i + 1 < l->size(); ++i) {
      if ((*l)[i] == (*l)[i + 1]) continue;
      length += std::hypot((*l)[i + 1].x - (*l)[i].x, (*l)[i + 1].y - (*l)[i].y);
      ++degree[(*l)[i]], ++degree[(*l)[i + 1]];
    }
  std::map<int, int> by_degree;
  int dead_ends = 0, edge_ends = 0, junctions = 0;
  for (const auto& [p, d] : degree) {
    if (d != 2) ++by_degree[d];
    if (d >= 3) ++junctions;
    if (d == 1) (on_edge(p) ? edge_ends : dead_ends)++;
  }
  ordered_json degrees = ordered_json::object();
  for (auto [d, n] : by_degree) degrees[std::to_string(d)] = n;
  const double km2 = area_m2 / 1e6;
  auto per_km2 = [&](double v) { return km2 > 0 ? std::round(v / km2 * 10) / 10 : 0.0; };
  return {{"centre_lines", lines.size()},
          {"length_km", std::round(length / 100) / 10},
          {"junctions_by_degree", degrees},
          {"dead_ends", dead_ends},
          {"ends_on_city_edge", edge_ends},
          {"area_km2", std::round(km2 * 1000) / 1000},
          {"street_km_per_km2", per_km2(length / 1000)},
          {"junctions_per_km2", per_km2(junctions)}};
}

using RoadEdges = std::unordered_set<std::pair<Vec2, Vec2>, SegmentHash>;

template <class T>
std::vector<const T*> pointers(const std::vector<T>& items) {
  std::vector<const T*> out;
  for (const auto& item : items) out.push_back(&item);
  return out;
}

// "all" and every zone a block, lot or building says it lies in.
std::set<std::string> zone_names(const CityLayers& layers) {
  std::set<std::string> zones{"all"};
  for (const Layer* l : {&layers.blocks, &layers.lots, &layers.buildings})
    for (const auto& f : l->features) zones.insert(f.properties.value("zone", "all"));
  return zones;
}

// Every edge of the road areas' rings, either way round: a lot fronts a road where one of
// its edges is one of these.
RoadEdges road_area_edges(const Layer& road_areas) {
  RoadEdges road_edges;
  auto add_edges = [&](const geom::Ring& r) {
    for (std::size_t i = 0; i < r.size(); ++i) road_edges.insert(undirected(r[i], r[(i + 1) % r.size()]));
  };
  for (const auto& f : road_areas.features) {
    add_edges(f.polygon.outer);
    for (const auto& h : f.polygon.holes) add_edges(h);
  }
  return road_edges;
}

// A lot's depth over its width: its extents across and along its longest edge on a road
// area; 0 for a lot with none.
double lot_depth_over_width(const geom::Polygon& p, const RoadEdges& road_edges) {
  const auto& r = p.outer;
  double longest = 0;
  std::pair<Vec2, Vec2> frontage;
  for (std::size_t i = 0; i < r.size(); ++i) {
    Vec2 a = r[i], b = r[(i + 1) % r.size()];
    double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len > longest && road_edges.count(undirected(a, b))) longest = len, frontage = {a, b};
  }
  return longest > 0 ? geom::depth_over_width(r, frontage.first, frontage.second) : 0.0;
}

// A zone's built blocks (green space is left out), and how much of their area lies in
// blocks over kOversized times their zone's block_area (none without the sketch to say).
struct BlockTally {
  std::vector<double> areas;
  double total = 0, oversized = 0;
};

struct BlockMeasure {
  double area;
  bool oversized;
};

BlockMeasure measure_block(const VectorFeature& f, const CitySettings* settings) {
  const double a = geom::area(f.polygon);
  auto type = parse_zone_type(f.properties.value("zone", ""));
  return {a, settings && type && a > kOversized * settings->zone_settings.at(*type).roads.growth.block_area};
}

void add(BlockTally& t, const BlockMeasure& m) {
  t.areas.push_back(m.area);
  t.total += m.area;
  if (m.oversized) t.oversized += m.area;
}

ordered_json block_figures(const BlockTally& t) {
  return {{"area_m2", summary(t.areas)},
          {"share_area_over_4x_block_area", t.total > 0 ? std::round(1e4 * t.oversized / t.total) / 1e4 : 0}};
}

struct LotTally {
  std::vector<double> areas;
  std::size_t fronting = 0, odd_shape = 0, sharp = 0, unbuilt = 0;
};

struct LotMeasure {
  double area;
  bool unbuilt, fronting, odd_shape, sharp;
};

LotMeasure measure_lot(const VectorFeature& f, const RoadEdges& road_edges, const std::unordered_set<int>& built) {
  const double ratio = lot_depth_over_width(f.polygon, road_edges);
  return {geom::area(f.polygon), !f.properties.contains("id") || !built.count(f.properties["id"].get<int>()), ratio > 0,
          ratio > 0 && (ratio < kLotShape.min || ratio > kLotShape.max), sharpest_angle(f.polygon.outer) < kSharpAngle};
}

void add(LotTally& t, const LotMeasure& m) {
  t.areas.push_back(m.area);
  t.unbuilt += m.unbuilt;
  t.fronting += m.fronting;
  t.odd_shape += m.odd_shape;
  t.sharp += m.sharp;
}

ordered_json lot_figures(const LotTally& t) {
  const std::size_t count = t.areas.size();
  return {{"area_m2", summary(t.areas)},
          {"share_touching_road", share(t.fronting, count)},
          {"share_depth_over_width_outside_0.5_5", share(t.odd_shape, count)},
          {"share_sharp_angle", share(t.sharp, count)},
          {"share_without_building", share(t.unbuilt, count)}};
}

// Buildings only: a layer's other kinds of feature have no footprint to measure.
bool is_building(const VectorFeature& f) { return f.properties.value("kind", "building") == "building"; }

// The ids of the lots a building stands on: an extruded one or a placed building model
// (street furniture and trees build nothing).
std::unordered_set<int> built_lots(const Layer& buildings) {
  std::unordered_set<int> built;
  for (const auto& f : buildings.features)
    if (is_building(f) && f.properties.contains("lot") && f.properties["lot"].is_number_integer())
      built.insert(f.properties["lot"].get<int>());
  return built;
}

struct ZoneTally {
  BlockTally blocks;
  LotTally lots;
  FootprintTally footprints;
};

// Every zone's blocks, lots and footprints, and "all"'s: each feature is measured once and
// counted in "all" and in the zone it says it lies in.
class ZoneTallies {
 public:
  ZoneTallies(const CityLayers& layers, const RoadEdges& road_edges, const CitySettings* settings) {
    const CancelCheck cancel;
    for (const auto& f : layers.blocks.features)
      if (!f.properties.value("green", false)) count(f, &ZoneTally::blocks, measure_block(f, settings));
    const std::unordered_set<int> built = built_lots(layers.buildings);
    for (const auto& f : layers.lots.features) {
      cancel.check();
      count(f, &ZoneTally::lots, measure_lot(f, road_edges, built));
    }
    for (const auto& f : layers.buildings.features)
      if (is_building(f)) count(f, &ZoneTally::footprints, measure_footprint(f.polygon));
  }

  // One zone's (or "all"'s) figures; none for a zone with no block, lot or footprint.
  std::optional<ordered_json> figures(const std::string& zone) const {
    static const ZoneTally kNone;
    auto it = by_zone_.find(zone);
    const ZoneTally& t = zone == "all" ? all_ : it != by_zone_.end() ? it->second : kNone;
    if (t.blocks.areas.empty() && t.lots.areas.empty() && t.footprints.areas.empty()) return std::nullopt;
    return ordered_json{{"blocks", block_figures(t.blocks)},
                        {"lots", lot_figures(t.lots)},
                        {"footprints", footprint_figures(t.footprints)}};
  }

 private:
  template <class Tally, class Measure>
  void count(const VectorFeature& f, Tally ZoneTally::*tally, const Measure& m) {
    add(all_.*tally, m);
    add(by_zone_[f.properties.value("zone", "")].*tally, m);
  }

  ZoneTally all_;
  std::map<std::string, ZoneTally> by_zone_;
};

// The city's ground: what zones, water and road areas cover.
double ground_area(const CityLayers& layers) {
  double ground = 0;
  for (const Layer* l : {&layers.zones, &layers.water, &layers.road_areas})
    for (const auto& f : l->features) ground += geom::area(f.polygon);
  return ground;
}

// The city's edge: the drawn zones' rings and the water's, and whatever lies outside every
// drawn zone.
class CityEdge {
 public:
  CityEdge(const CityLayers& layers, const DrawnFeatures* drawn) {
    if (drawn)
      for (const auto& z : drawn->zones)
        for (const auto& p : z.polygons) rings_.add_polygon(p), drawn_.push_back(&p);
    for (const auto& f : layers.water.features) rings_.add_polygon(f.polygon);
  }

  bool lies_on(Vec2 p) const {
    if (rings_.near(p, kOnEdge)) return true;
    for (const geom::Polygon* d : drawn_)
      if (geom::odd_crossings(d->outer, p)) return false;
    return true;  // outside every drawn zone: a sketch road's end past the city
  }

 private:
  geom::SegmentIndex rings_{16.0};
  std::vector<const geom::Polygon*> drawn_;
};

std::vector<const geom::Polyline*> centre_lines(const Layer& roads) {
  std::vector<const geom::Polyline*> lines;
  for (const auto& f : roads.features) lines.push_back(&f.line);
  return lines;
}

// Positions past a million kilometres are no place on Earth in any frame: their feature is skipped.
constexpr double kFarthest = 1e9;

// The footprints and streets of a file of real data.
struct RealFeatures {
  std::vector<geom::Polygon> polygons;
  std::vector<geom::Polyline> lines;
  std::size_t skipped = 0;  // features that are neither, or unusable
};

ordered_json read_feature_collection(const std::filesystem::path& file) {
  ordered_json doc = ordered_json::parse(
      read_input(file, kMaxDataFileBytes, "real data", "give a GeoJSON file of footprints or streets"), nullptr, false);
  if (doc.is_discarded() || !doc.is_object() || !doc.contains("features") || !doc["features"].is_array())
    throw UserError(file.string() + ": not a GeoJSON FeatureCollection; give footprints (Polygons) or streets (LineStrings)");
  return doc;
}

// Malformed positions are passed over; a position past kFarthest empties the whole list.
std::vector<Vec2> real_positions(const ordered_json& c) {
  std::vector<Vec2> out;
  if (!c.is_array()) return out;
  for (const auto& p : c) {
    if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number()) continue;
    Vec2 v{p[0].get<double>(), p[1].get<double>()};
    if (!(std::abs(v.x) <= kFarthest && std::abs(v.y) <= kFarthest)) return std::vector<Vec2>{};
    out.push_back(v);
  }
  return out;
}

void add_polygon(const ordered_json& rings, RealFeatures& real) {
  if (!rings.is_array() || rings.empty()) return ++real.skipped, void();
  geom::Polygon p{real_positions(rings[0]), {}};
  if (p.outer.size() > 1 && p.outer.front() == p.outer.back()) p.outer.pop_back();
  if (p.outer.size() < 3) return ++real.skipped, void();
  for (std::size_t k = 1; k < rings.size(); ++k) p.holes.push_back(real_positions(rings[k]));
  // Real files wind their rings either way (ogr2ogr writes OSM's outer rings clockwise):
  // the figures take outer rings counter-clockwise and holes clockwise, as the city's are.
  if (geom::signed_area(p.outer) < 0) std::reverse(p.outer.begin(), p.outer.end());
  for (geom::Ring& h : p.holes)
    if (geom::signed_area(h) > 0) std::reverse(h.begin(), h.end());
  real.polygons.push_back(std::move(p));
}

void add_line(const ordered_json& c, RealFeatures& real) {
  std::vector<Vec2> l = real_positions(c);
  if (l.size() < 2) return ++real.skipped, void();
  real.lines.push_back(std::move(l));
}

RealFeatures read_features(const ordered_json& features) {
  RealFeatures real;
  for (const auto& f : features) {
    if (!f.is_object() || !f.contains("geometry") || !f["geometry"].is_object()) {
      ++real.skipped;
      continue;
    }
    const auto& g = f["geometry"];
    const std::string type = g.value("type", "");
    const auto& c = g.contains("coordinates") ? g["coordinates"] : ordered_json();
    if (type == "Polygon") add_polygon(c, real);
    else if (type == "MultiPolygon" && c.is_array()) for (const auto& p : c) add_polygon(p, real);
    else if (type == "LineString") add_line(c, real);
    else if (type == "MultiLineString" && c.is_array()) for (const auto& l : c) add_line(l, real);
    else ++real.skipped;
  }
  return real;
}

geom::Box bounds(const RealFeatures& real) {
  geom::Box box = geom::Box::none();
  for (const auto& p : real.polygons) for (Vec2 v : p.outer) box.add(v);
  for (const auto& l : real.lines) for (Vec2 v : l) box.add(v);
  return box;
}

// The extract's box stands for the city's edge: streets cut there end on it.
ordered_json real_street_figures(const std::vector<geom::Polyline>& lines, const geom::Box& box) {
  const double margin = 20;
  auto on_edge = [&](Vec2 p) {
    return p.x - box.min_x < margin || box.max_x - p.x < margin || p.y - box.min_y < margin || box.max_y - p.y < margin;
  };
  return street_figures(pointers(lines), box.width() * box.height(), on_edge);
}

}  // namespace

ordered_json city_statistics(const CityLayers& layers, const CitySettings* settings, const DrawnFeatures* drawn) {
  const std::set<std::string> zones = zone_names(layers);
  const ZoneTallies tallies(layers, road_area_edges(layers.road_areas), settings);
  ordered_json per_zone = ordered_json::object();
  for (const std::string& zone : zones)
    if (std::optional<ordered_json> z = tallies.figures(zone)) per_zone[zone] = *z;
  const double ground = ground_area(layers);
  const CityEdge edge(layers, drawn);
  auto on_edge = [&](Vec2 p) { return edge.lies_on(p); };
  return {{"zones", per_zone}, {"streets", street_figures(centre_lines(layers.roads), ground, on_edge)}};
}

ordered_json real_statistics(const std::filesystem::path& file) {
  ordered_json doc = read_feature_collection(file);
  // Measured in ground metres as a sketch is built (generate/gis/projection.h): its crs
  // (Web Mercator, feet) or lon/lat without one projected to its UTM zone.
  const bool projected = project_to_metres(doc, file);
  RealFeatures real = read_features(doc["features"]);
  const geom::Box box = bounds(real);
  if (box.holds_nothing()) throw UserError(file.string() + ": holds no usable Polygon or LineString; give footprints or streets");
  ordered_json out{{"file", file.filename().string()}, {"projected", projected}, {"features_skipped", real.skipped}};
  if (!real.polygons.empty()) {
    FootprintTally t;
    for (const geom::Polygon& p : real.polygons) add(t, measure_footprint(p));
    out["zones"] = {{"all", {{"footprints", footprint_figures(t)}}}};
  }
  if (!real.lines.empty()) out["streets"] = real_street_figures(real.lines, box);
  return out;
}

std::string format_statistics(const ordered_json& s) {
  std::ostringstream out;
  auto areas = [&](const char* what, const ordered_json& a) {
    if (a.value("count", 0) == 0) return;
    out << "    " << what << ": " << a["count"] << ", area m2 median " << a["median"] << ", p95 " << a["p95"] << ", largest "
        << a["max"] << "\n";
  };
  if (s.value("features_skipped", 0) > 0)
    out << "features left out: " << s["features_skipped"]
        << " (rings of fewer than 3 corners, lines of fewer than 2 points, other geometry, positions past 1e9 m)\n";
  if (s.contains("zones"))
    for (const auto& [zone, z] : s["zones"].items()) {
      out << zone << "\n";
      if (z.contains("blocks") && z["blocks"]["area_m2"].value("count", 0) > 0) {
        areas("blocks", z["blocks"]["area_m2"]);
        out << "      share of block area in blocks over 4x block_area: " << z["blocks"]["share_area_over_4x_block_area"] << "\n";
      }
      if (z.contains("lots") && z["lots"]["area_m2"].value("count", 0) > 0) {
        areas("lots", z["lots"]["area_m2"]);
        out << "      share of lots touching a road area: " << z["lots"]["share_touching_road"]
            << ", with depth/width outside 0.5-5: " << z["lots"]["share_depth_over_width_outside_0.5_5"]
            << ", with an angle under 30 degrees: " << z["lots"]["share_sharp_angle"]
            << ", without a building: " << z["lots"]["share_without_building"] << "\n";
      }
      const auto& f = z["footprints"];
      areas("footprints", f["area_m2"]);
      out << "      share with an angle under 30 degrees: " << f["share_sharp_angle"] << ", under 5 m across: "
          << f["share_under_5m_across"] << "\n";
    }
  if (s.contains("streets")) {
    const auto& t = s["streets"];
    out << "streets\n    " << t["centre_lines"] << " centre lines, " << t["length_km"] << " km over " << t["area_km2"]
        << " km2: " << t["street_km_per_km2"] << " km/km2, " << t["junctions_per_km2"] << " junctions/km2\n";
    out << "    junctions by degree " << t["junctions_by_degree"].dump() << ", dead ends " << t["dead_ends"]
        << ", ends on the city's edge " << t["ends_on_city_edge"] << "\n";
  }
  return out.str();
}

}  // namespace exacity
