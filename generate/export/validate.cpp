#include "generate/export/validate.h"
#include "generate/export/validate_window.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <span>
#include <string_view>
#include <stdexcept>
#include <set>
#include <tuple>
#include <unordered_map>

#include "generate/cancel.h"
#include "generate/cancellable_invoke.h"
#include "generate/city/drawn_zones.h"
#include "generate/errors.h"
#include "generate/export/geojson.h"
#include "generate/export/validate_nesting.h"
#include "generate/export/validate_clutter.h"
#include "generate/export/vector_layers.h"
#include "generate/sketch/sketch.h"
#include "geom/measure.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"
#include "geom/segment_index.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxProblems = 20;

// Written coordinates are the exact vertices rounded to doubles, so where a constructed
// vertex lies on a drawn edge, the written edge and the drawn edge bound a sliver about
// 1e-13 m wide (1e-9 m at UTM-sized coordinates), and a road's end written on a drawn
// edge lies that far from it. Comparisons with the drawn sketch accept this much; every
// other check is exact without tolerance.
constexpr double kRounding = 1e-6;

enum class Kind { Zone, Park, Water, Road, Bridge, Block, Lot, Building };

struct PolygonRef {
  Kind kind;
  std::string name;  // "zones.geojson features[3]"
  std::string zone;  // for zones, blocks and lots
  bool green = false;
  int id = -1;       // the feature's id
  int block = -1;    // for lots: the block it names
  int lot = -1;      // for lots: their id; for buildings: the lot they stand on
  const nlohmann::ordered_json* properties = nullptr;  // for buildings: their slabs, if nested
};

std::string near(geom::Vec2 p) { return " near (" + format_number(p.x) + ", " + format_number(p.y) + ")"; }

class Checker {
 public:
  explicit Checker(Validation& v) : v_(v) {}
  void problem(const std::string& p) {
    if (v_.problems.size() < kMaxProblems) v_.problems.push_back(p);
  }
  Validation& v_;
};

// Simple rings, outer counter-clockwise, holes clockwise; records each polygon.
void check_polygons(Checker& c, const Layer& layer, std::vector<PolygonRef>& refs,
                    std::vector<const geom::Polygon*>& polygons) {
  c.v_.features[layer.name] = static_cast<int>(layer.features.size());
  const CancelCheck cancel;
  for (std::size_t i = 0; i < layer.features.size(); ++i) {
    cancel.check();
    const VectorFeature& f = layer.features[i];
    std::string name = layer.name + ".geojson features[" + std::to_string(i) + "]";
    if (!f.properties.contains("id")) c.problem(name + ": no \"id\"");
    if (geom::ring_orientation(f.polygon.outer) != 1)
      c.problem(name + ": outer ring is not simple and counter-clockwise" + near(f.polygon.outer[0]));
    for (const auto& h : f.polygon.holes)
      if (geom::ring_orientation(h) != -1) c.problem(name + ": a hole is not simple and clockwise" + near(h[0]));
    std::string zone = f.properties.value("zone", "");
    Kind kind = layer.name == "zones"   ? (zone == "park" ? Kind::Park : Kind::Zone)
                : layer.name == "water" ? Kind::Water
                : layer.name == "blocks" ? Kind::Block
                : layer.name == "lots"   ? Kind::Lot
                : layer.name == "buildings" ? Kind::Building
                : f.properties.value("bridge", false) ? Kind::Bridge
                                                      : Kind::Road;
    const int id = f.properties.value("id", -1);
    const auto lot = f.properties.find("lot");  // null for a mapped building on no lot
    refs.push_back({kind, name, zone, f.properties.value("green", false), id, f.properties.value("block", -1),
                    kind == Kind::Lot ? id : lot != f.properties.end() && lot->is_number_integer() ? lot->get<int>() : -1,
                    &f.properties});
    polygons.push_back(&f.polygon);
  }
}

// Zones and parks, water and road areas cover the drawn zones once; so do blocks, parks,
// water and road areas.
constexpr std::initializer_list<Kind> kZoning{Kind::Zone, Kind::Park, Kind::Water, Kind::Road};
constexpr std::initializer_list<Kind> kBlocking{Kind::Block, Kind::Park, Kind::Water, Kind::Road};

// The polygons one face of the tiling map lies in, by kind: indices into refs, grouped by
// kind in a buffer reused from face to face rather than a map of vectors made per face.
class FaceCover {
 public:
  static constexpr int kKinds = static_cast<int>(Kind::Building) + 1;

  FaceCover(const std::vector<PolygonRef>& refs, const std::vector<int>& inside, std::vector<int>& by_kind)
      : refs_(refs), by_kind_(by_kind) {
    start_.fill(0);
    for (int p : inside) ++start_[static_cast<int>(refs[p].kind) + 1];
    for (int k = 1; k <= kKinds; ++k) start_[k] += start_[k - 1];
    by_kind_.resize(inside.size());
    std::array<int, kKinds + 1> next = start_;
    for (int p : inside) by_kind_[next[static_cast<int>(refs[p].kind)]++] = p;
  }

  std::size_t count(std::initializer_list<Kind> kinds) const {
    std::size_t n = 0;
    for (Kind k : kinds) n += all(k).size();
    return n;
  }

  std::string names(std::initializer_list<Kind> kinds) const {
    std::string s;
    for (Kind k : kinds)
      for (int p : all(k)) s += (s.empty() ? "" : " and ") + refs_[p].name;
    return s;
  }

  // The first polygon of that kind; there must be one.
  const PolygonRef& first(Kind k) const {
    const std::span<const int> of_kind = all(k);
    if (of_kind.empty()) throw std::out_of_range("FaceCover::first: no polygon of this kind");
    return refs_[of_kind[0]];
  }
  // The indices of every polygon of that kind.
  std::span<const int> all(Kind k) const {
    const int i = static_cast<int>(k);
    return {by_kind_.data() + start_[i], static_cast<std::size_t>(start_[i + 1] - start_[i])};
  }

 private:
  const std::vector<PolygonRef>& refs_;
  std::vector<int>& by_kind_;
  std::array<int, kKinds + 1> start_;  // kind k's indices are by_kind_[start_[k], start_[k + 1])
};

// Labels each face of the tiling map with the index of what is wrong there, 0 where
// nothing is; each problem is stated once however many faces have it.
// Two maps are labelled: the zoning map (zones, parks, water, road areas and the drawn
// zones), whose faces are checked against the sketch, and the map of every polygon (or of
// those a window meets), whose faces get every other check.
class FaceLabels {
 public:
  // With `drawn`, the zoning map's; else the polygons' map, whose faces outside the window
  // (counters from window_first on; -1: no window) are not checked.
  FaceLabels(const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs, const DrawnZones* drawn, int polygons,
             int window_first = -1)
      : sketch_(sketch), refs_(refs), drawn_(drawn), polygons_(polygons), window_first_(window_first) {}

  int of(const geom::Windings& w) {
    cancel_.check();
    if (window_first_ >= 0 && std::none_of(w.begin(), w.end(), [&](const auto& c) { return c.first >= window_first_; }))
      return 0;
    inside_.clear();
    if (int label = ring_windings(w, inside_)) return label;
    const FaceCover here(refs_, inside_, by_kind_);
    if (drawn_) return against_sketch(here, w);
    if (int label = overlaps(here)) return label;
    return nesting(here);
  }

  std::vector<std::string> messages{""};
  // Problems found against the drawn sketch, where a rounding sliver is no problem.
  std::vector<bool> sketch_checks{false};

 private:
  int wrong(const std::string& m, bool sketch_check = false) {
    auto [it, added] = message_index_.emplace(m, static_cast<int>(messages.size()));
    if (added) messages.push_back(m), sketch_checks.push_back(sketch_check);
    return it->second;
  }

  // Each polygon's outer ring winds once around the face or not at all, and its holes
  // wind once around it only inside the outer ring. `inside` gets the polygons the face
  // lies in.
  int ring_windings(const geom::Windings& w, std::vector<int>& inside) {
    for (std::size_t i = 0; i < w.size() && w[i].first < 2 * polygons_;) {
      int p = w[i].first / 2, outer = 0, holes = 0;
      for (; i < w.size() && w[i].first < 2 * polygons_ && w[i].first / 2 == p; ++i)
        (w[i].first % 2 == 0 ? outer : holes) = w[i].second;
      // The zoning map's rings are checked in the polygons' map: a ring wound wrong is not in the face.
      if (outer != 0 && outer != 1) {
        if (drawn_) continue;
        return wrong(refs_[p].name + ": outer ring winds " + std::to_string(outer) + " times");
      }
      if (holes != 0 && (holes != -1 || outer != 1)) {
        if (drawn_) continue;
        return wrong(refs_[p].name + ": holes overlap or leave the outer ring");
      }
      if (outer == 1 && holes == 0) inside.push_back(p);
    }
    return 0;
  }

  int overlaps(const FaceCover& here) {
    if (here.count(kZoning) > 1) return wrong(here.names(kZoning) + " overlap");
    if (here.count(kBlocking) > 1) return wrong(here.names(kBlocking) + " overlap");
    if (here.count({Kind::Bridge}) > 1) return wrong("two bridges overlap");
    if (here.count({Kind::Bridge}) == 1 && here.count({Kind::Water}) == 0) return wrong("a bridge lies outside the water");
    if (here.count({Kind::Zone}) != here.count({Kind::Block}))
      return wrong((here.count({Kind::Zone}) ? here.names({Kind::Zone}) + " holds no block"
                                             : here.names({Kind::Block}) + " lies outside the zones"));
    return 0;
  }

  // A lot lies in the block it names, a building on the lot it names, a block in a zone
  // of its type unless it is green space.
  int nesting(const FaceCover& here) {
    if (here.count({Kind::Lot}) > 1) return wrong(here.names({Kind::Lot}) + " overlap");
    if (here.count({Kind::Lot}) == 1) {
      const PolygonRef& lot = here.first(Kind::Lot);
      if (here.count({Kind::Block}) == 0 || here.first(Kind::Block).id != lot.block)
        return wrong(lot.name + " leaves its block " + std::to_string(lot.block));
    }
    // Buildings overlap only where nesting proves one wholly below the other
    // (docs/design.md, Placement: nesting), each pair decided once.
    if (here.count({Kind::Building}) > 0) {
      const std::span<const int> buildings = here.all(Kind::Building);
      for (std::size_t i = 0; i < buildings.size(); ++i)
        for (std::size_t j = i + 1; j < buildings.size(); ++j) {
          const PolygonRef &a = refs_[buildings[i]], &b = refs_[buildings[j]];
          auto [it, added] = nested_.emplace(std::pair{buildings[i], buildings[j]}, 0);
          if (added)
            if (auto why = nested_overlap_problem(*a.properties, a.name, *b.properties, b.name)) it->second = wrong(*why);
          if (it->second) return it->second;
        }
      // A mapped building stands as mapped, on lots or not, but never on a road.
      for (int p : buildings)
        if (refs_[p].properties->value("mapped", false)) {
          if (here.count({Kind::Road, Kind::Bridge}) > 0) return wrong(refs_[p].name + " stands on a road");
        } else if (here.count({Kind::Lot}) == 0 || here.first(Kind::Lot).lot != refs_[p].lot) {
          return wrong(refs_[p].name + " leaves its lot " + std::to_string(refs_[p].lot));
        }
    }
    if (here.count({Kind::Block}) == 1) {
      const PolygonRef &b = here.first(Kind::Block), &z = here.first(Kind::Zone);
      if (!b.green && b.zone != z.zone) return wrong(b.name + " says \"" + b.zone + "\" inside " + z.name + " (\"" + z.zone + "\")");
    }
    return 0;
  }

  // The drawn zones are covered, by zones of the type drawn, and nothing else is zoned.
  int against_sketch(const FaceCover& here, const geom::Windings& w) {
    int top = drawn_->top_zone(w);
    std::size_t surfaces = here.count(kZoning);
    if (top >= 0 && surfaces == 0)
      return wrong("the drawn zone features[" + std::to_string(sketch_.zones[top].index) +
                       "] is not covered by a zone, water or road area", true);
    if (top < 0 && here.count({Kind::Zone, Kind::Park}) > 0) return wrong(here.names({Kind::Zone, Kind::Park}) + " lies outside every drawn zone", true);
    if (top >= 0 && here.count({Kind::Zone, Kind::Park}) == 1) {
      const PolygonRef& z = here.count({Kind::Zone}) == 0 ? here.first(Kind::Park) : here.first(Kind::Zone);
      if (z.zone != name(sketch_.zones[top].type))
        return wrong(z.name + " says zone \"" + z.zone + "\" where the sketch draws \"" +
                         std::string(name(sketch_.zones[top].type)) + "\"", true);
    }
    return 0;
  }

  const DrawnFeatures& sketch_;
  const std::vector<PolygonRef>& refs_;
  const DrawnZones* drawn_;
  const int polygons_, window_first_;
  const CancelCheck cancel_;
  std::map<std::string, int> message_index_{{"", 0}};
  std::map<std::pair<int, int>, int> nested_;  // overlapping buildings -> their problem's label, 0 for none
  std::vector<int> inside_, by_kind_;  // of the face being labelled (FaceCover's buffers)
};

// A window of the polygons' map (below) and its outline.
struct Window;
void add_window(geom::PlanarMap& map, const Window& w, int counter);

// Polygon p's outer ring winds around counter 2p and its holes around 2p + 1.
void add_polygon_rings(geom::PlanarMap& map, const std::vector<const geom::Polygon*>& polygons) {
  const int P = static_cast<int>(polygons.size());
  for (int p = 0; p < P; ++p) {
    map.add_ring(polygons[p]->outer, 2 * p, 0);
    for (std::size_t h = 0; h < polygons[p]->holes.size(); ++h)
      map.add_ring(polygons[p]->holes[h], 2 * p + 1, static_cast<int>(h) + 1);
  }
}

// Each face problem once, near a face that has it. Faces found wrong only against the
// sketch and no wider than kRounding are rounding slivers, not problems.
void report_face_problems(Checker& c, const geom::PlanarMap& map, const FaceLabels& labels) {
  if (labels.messages.size() == 1) return;  // no face has a problem: no widths to measure (a pass over every face)
  const std::vector<double> widths = map.widest_faces(static_cast<int>(labels.messages.size()));
  for (std::size_t m = 1; m < labels.messages.size(); ++m) {
    if (labels.sketch_checks[m]) {
      double width = widths[m];
      if (width <= kRounding) {
        c.v_.widest_sliver = std::max(c.v_.widest_sliver, width);
        continue;
      }
    }
    geom::Vec2 at;
    c.problem(labels.messages[m] + (map.point_near_label(static_cast<int>(m), at) ? near(at) : ""));
  }
}

// Two rings of one polygon may touch at a vertex but not run along each other. One pass
// over the edges also finds which polygons share an edge with a road area or bridge.
std::vector<bool> check_shared_edges(Checker& c, const geom::PlanarMap& map, const std::vector<PolygonRef>& refs, int P) {
  std::vector<bool> fronts(P, false);
  const CancelCheck cancel;
  map.for_each_edge([&](const std::vector<geom::CurveTag>& tags, geom::Vec2 a, geom::Vec2) {
    cancel.check();
    bool road = false;
    for (const auto& t : tags)
      if (t.counter < 2 * P && (refs[t.counter / 2].kind == Kind::Road || refs[t.counter / 2].kind == Kind::Bridge)) road = true;
    for (std::size_t i = 0; i < tags.size(); ++i) {
      if (tags[i].counter >= 2 * P) continue;
      if (road) fronts[tags[i].counter / 2] = true;
      for (std::size_t j = i + 1; j < tags.size(); ++j)
        if (tags[j].counter < 2 * P && tags[i].counter / 2 == tags[j].counter / 2)
          c.problem(refs[tags[i].counter / 2].name + ": two of its rings share an edge" + near(a));
    }
  });
  return fronts;
}

// The polygons of the given kinds (all for none), as the refs and rings of a map of their own.
struct MapPolygons {
  std::vector<PolygonRef> refs;
  std::vector<const geom::Polygon*> polygons;
  void add(const PolygonRef& ref, const geom::Polygon* polygon) { refs.push_back(ref), polygons.push_back(polygon); }
};

// The zoning polygons and the drawn zones in one exact map, each face labelled with what
// is wrong there against the sketch; rounding slivers are measured here.
void check_zoning(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                  const std::vector<const geom::Polygon*>& polygons) {
  MapPolygons zoning;
  for (std::size_t p = 0; p < refs.size(); ++p)
    if (refs[p].kind == Kind::Zone || refs[p].kind == Kind::Park || refs[p].kind == Kind::Water ||
        refs[p].kind == Kind::Road || refs[p].kind == Kind::Bridge)
      zoning.add(refs[p], polygons[p]);
  geom::PlanarMap map;
  const int P = static_cast<int>(zoning.polygons.size());
  add_polygon_rings(map, zoning.polygons);
  DrawnZones drawn(sketch.zones, map, 2 * P);
  map.insert_batch();
  FaceLabels labels(sketch, zoning.refs, &drawn, P);
  map.label_faces([&](const geom::Windings& w) { return labels.of(w); });
  report_face_problems(c, map, labels);
}

// The polygons in one exact map, each face inside the window (every face without one)
// labelled with what is wrong there; then the map's edges. Every lot shares an edge with
// a road area. `in_window` says which polygons the map holds (all without a window), and
// `fronting` which further road areas it needs for the lots' frontage.
void check_polygon_map(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                       const std::vector<const geom::Polygon*>& polygons, const Window* window,
                       const std::vector<char>& in_window, const std::vector<char>& fronting) {
  MapPolygons local;
  for (std::size_t p = 0; p < refs.size(); ++p)
    if (!window || in_window[p] || fronting[p]) local.add(refs[p], polygons[p]);
  geom::PlanarMap map;
  const int P = static_cast<int>(local.polygons.size());
  add_polygon_rings(map, local.polygons);
  if (window) add_window(map, *window, 2 * P);
  map.insert_batch();
  FaceLabels labels(sketch, local.refs, nullptr, P, window ? 2 * P : -1);
  map.label_faces([&](const geom::Windings& w) { return labels.of(w); });
  report_face_problems(c, map, labels);
  const std::vector<bool> fronts = check_shared_edges(c, map, local.refs, P);
  for (std::size_t p = 0, q = 0; p < refs.size(); ++p) {
    if (window && !in_window[p] && !fronting[p]) continue;
    const bool checked = !window || in_window[p];  // a road area added for frontage has no lot's verdict
    if (checked && refs[p].kind == Kind::Lot && !fronts[q]) c.problem(refs[p].name + " touches no road area");
    ++q;
  }
}

void check_tiling(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                  const std::vector<const geom::Polygon*>& polygons, const Window* window = nullptr,
                  const std::vector<char>& in_window = {}, const std::vector<char>& fronting = {}) {
  check_polygon_map(c, sketch, refs, polygons, window, in_window, fronting);
  check_zoning(c, sketch, refs, polygons);
}

// The centre lines are a noded network: two of them meet only at a vertex of both. Every
// end of a grown road is a vertex of another centre line (a junction) or lies on the edge
// of the built city (a drawn zone's ring or water). Every piece of the network holding a
// region's roads holds a road the sketch drew (in a sketch without roads, all are one).
// A road's centre line meets another only at its vertices: never between them, nor along
// a segment both have.
void check_road_meetings(Checker& c, const std::vector<VectorFeature>& features) {
  geom::PlanarMap map;
  for (std::size_t i = 0; i < features.size(); ++i) map.add_polyline(features[i].line, static_cast<int>(i));
  map.insert_batch();
  const CancelCheck cancel;
  std::map<geom::SegmentKey, int> line_along;  // each piece's first line
  for (const auto& [tag, pieces] : map.polyline_pieces()) {
    cancel.check();
    for (const geom::PolylinePiece& piece : pieces) {
      const auto [it, first] = line_along.emplace(geom::segment_key(piece.from, piece.to), tag);
      if (!first && it->second != tag) {
        c.problem("roads.geojson: road " + std::to_string(features[tag].properties.value("id", -1)) +
                  " runs along road " + std::to_string(features[it->second].properties.value("id", -1)) +
                  near(piece.from));
        break;
      }
    }
    if (pieces.size() != features[tag].line.size() - 1)
      for (std::size_t k = 1; k < pieces.size(); ++k)
        if (pieces[k].segment == pieces[k - 1].segment) {
          c.problem("roads.geojson: road " + std::to_string(features[tag].properties.value("id", -1)) +
                    " meets another centre line between its vertices" + near(pieces[k].from));
          break;
        }
  }
}

void check_road_connectivity(Checker& c, const std::vector<VectorFeature>& features) {
  // Union-find over vertices.
  std::unordered_map<geom::Vec2, int, geom::Vec2Hash> node;
  std::vector<int> parent;
  std::vector<geom::Vec2> at;
  auto id = [&](geom::Vec2 p) {
    auto [it, added] = node.emplace(p, static_cast<int>(parent.size()));
    if (added) parent.push_back(it->second), at.push_back(p);
    return it->second;
  };
  std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
  std::map<int, std::vector<int>> region_nodes;
  std::vector<int> sketch_nodes;
  for (const auto& f : features)
    for (std::size_t i = 0; i < f.line.size(); ++i) {
      int a = id(f.line[i]);
      if (f.properties["region"].is_null()) sketch_nodes.push_back(a);
      else region_nodes[f.properties["region"].get<int>()].push_back(a);
      if (i > 0) parent[find(a)] = find(id(f.line[i - 1]));
    }
  // Each piece of the network a region's roads lie in holds a road the sketch drew (the
  // sketch's own roads need not meet each other); in a sketch without roads, all the
  // regions' roads are one piece.
  std::set<int> drawn;
  for (int n : sketch_nodes) drawn.insert(find(n));
  const int first = region_nodes.empty() ? -1 : find(region_nodes.begin()->second.front());
  for (const auto& [region, nodes] : region_nodes) {
    std::set<int> pieces;
    for (int n : nodes) pieces.insert(find(n));
    bool cut_off = false;
    for (int p : pieces) cut_off |= drawn.empty() ? p != first : !drawn.count(p);
    if (!cut_off) continue;
    if (pieces.size() > 1)
      c.problem("roads.geojson: the roads of region " + std::to_string(region) + " are not connected");
    else
      c.problem("roads.geojson: the roads of region " + std::to_string(region) + " reach no other road" +
                near(at[nodes.front()]));
  }
}

// A generated road ends at another road or on a drawn edge (a zone's or the water's).
void check_road_ends(Checker& c, const DrawnFeatures& sketch, const std::vector<VectorFeature>& features, const Layer& water) {
  std::unordered_map<geom::Vec2, std::vector<int>, geom::Vec2Hash> roads_at;  // vertex -> features through it
  for (std::size_t i = 0; i < features.size(); ++i)
    for (auto p : features[i].line) roads_at[p].push_back(static_cast<int>(i));
  geom::SegmentIndex edges(16.0);
  for (const auto& z : sketch.zones)
    for (const auto& p : z.polygons) edges.add_polygon(p);
  for (const auto& f : water.features) edges.add_polygon(f.polygon);
  const CancelCheck cancel;
  for (std::size_t i = 0; i < features.size(); ++i) {
    cancel.check();
    const VectorFeature& f = features[i];
    if (f.properties["level"].is_null()) continue;  // drawn in the sketch
    for (geom::Vec2 end : {f.line.front(), f.line.back()}) {
      bool junction = false;
      for (int o : roads_at[end]) junction |= o != static_cast<int>(i);
      if (!junction && !edges.near(end, kRounding))
        c.problem("roads.geojson: road " + std::to_string(f.properties.value("id", -1)) + " ends in the open" + near(end));
    }
  }
}

void check_roads(Checker& c, const DrawnFeatures& sketch, const Layer& roads, const Layer& water) {
  check_road_meetings(c, roads.features);
  check_road_connectivity(c, roads.features);
  check_road_ends(c, sketch, roads.features, water);
}

// Every reference names the id of a feature of the layer it refers to.
void check_references(Checker& c, const Layer& from, const char* key, const Layer& to) {
  std::set<int> ids;
  for (const auto& f : to.features) ids.insert(f.properties.value("id", -1));
  for (std::size_t i = 0; i < from.features.size(); ++i) {
    const auto& value = from.features[i].properties.value(key, nlohmann::ordered_json());
    if (value.is_null() && from.features[i].properties.value("mapped", false)) continue;  // a mapped building on no lot
    for (const auto& v : value.is_array() ? value : nlohmann::ordered_json::array({value}))
      if (!v.is_number_integer() || !ids.count(v.get<int>())) {
        c.problem(from.name + ".geojson features[" + std::to_string(i) + "]: \"" + key + "\" " + v.dump() +
                  " names no feature of " + to.name + ".geojson");
        break;
      }
  }
}

}  // namespace

struct ValidatedPolygons {
  std::vector<std::string> keys;  // what it is, ids left out (polygon_key)
  std::vector<int> ids, names;    // its id; the id a lot's block or a building's lot has, else -1
  std::vector<geom::Box> boxes;
};

namespace {

// A polygon as the window compares it: its kind, its properties but ids, its rings exactly.
// Coordinates go in as their bytes: exact, and cheaper than text for every polygon of a city.
std::string polygon_key(const PolygonRef& ref, const geom::Polygon& polygon) {
  std::string key = std::to_string(static_cast<int>(ref.kind));
  for (const auto& [name, value] : ref.properties->items())
    if (name != "id" && name != "block" && name != "lot" && name != "road" && name != "roads") key += nlohmann::json(name).dump() + ':' + value.dump() + ',';
  auto ring = [&](const geom::Ring& r) {
    key += '|' + std::to_string(r.size()) + '|';
    key.append(reinterpret_cast<const char*>(r.data()), r.size() * sizeof(geom::Vec2));
  };
  ring(polygon.outer);
  for (const geom::Ring& h : polygon.holes) ring(h);
  return key;
}

ValidatedPolygons polygons_of(const std::vector<PolygonRef>& refs, const std::vector<const geom::Polygon*>& polygons) {
  ValidatedPolygons out;
  for (std::size_t p = 0; p < refs.size(); ++p) {
    out.keys.push_back(polygon_key(refs[p], *polygons[p]));
    out.ids.push_back(refs[p].id);
    out.names.push_back(refs[p].kind == Kind::Lot ? refs[p].block : refs[p].kind == Kind::Building ? refs[p].lot : -1);
    geom::Box box = geom::Box::none();
    for (geom::Vec2 q : polygons[p]->outer) box.add(q);
    out.boxes.push_back(box);
  }
  return out;
}

// The boxes of the polygons that changed since `last`, as they were and as they are. A
// polygon is kept where one of the same key was there before (one each way) and what it
// names, mapped through the kept blocks' and lots' ids, is what that one named.
std::vector<geom::Box> changed_boxes(const ValidatedPolygons& last, const ValidatedPolygons& now,
                                     const std::vector<PolygonRef>& refs) {
  auto index = [](const std::vector<std::string>& keys) {
    std::unordered_map<std::string_view, int> at;
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (auto [it, added] = at.emplace(keys[i], static_cast<int>(i)); !added) it->second = -1;  // not one of a kind
    return at;
  };
  const auto old_at = index(last.keys), new_at = index(now.keys);
  std::vector<int> match(now.keys.size(), -1);
  std::unordered_map<int, int> block_ids, lot_ids;  // old id -> new id, of matched blocks and lots
  for (std::size_t p = 0; p < now.keys.size(); ++p) {
    const auto o = old_at.find(now.keys[p]);
    if (o == old_at.end() || o->second < 0 || new_at.at(now.keys[p]) < 0) continue;
    match[p] = o->second;
    if (refs[p].kind == Kind::Block) block_ids[last.ids[o->second]] = now.ids[p];
    if (refs[p].kind == Kind::Lot) lot_ids[last.ids[o->second]] = now.ids[p];
  }
  auto mapped = [](const std::unordered_map<int, int>& ids, int id) {
    const auto it = ids.find(id);
    return it == ids.end() ? -2 : it->second;
  };
  std::vector<char> old_kept(last.keys.size(), 0);
  std::vector<geom::Box> boxes;
  for (std::size_t p = 0; p < now.keys.size(); ++p) {
    const int o = match[p];
    bool kept = o >= 0;
    if (kept && refs[p].kind == Kind::Lot) kept = mapped(block_ids, last.names[o]) == now.names[p];
    if (kept && refs[p].kind == Kind::Building)
      kept = last.names[o] < 0 ? now.names[p] < 0 : mapped(lot_ids, last.names[o]) == now.names[p];
    if (kept) old_kept[o] = 1;
    else boxes.push_back(now.boxes[p]);
  }
  for (std::size_t o = 0; o < last.keys.size(); ++o)
    if (!old_kept[o]) boxes.push_back(last.boxes[o]);
  // A polygon kept in place but naming anew has the same box twice.
  std::sort(boxes.begin(), boxes.end(), [](const geom::Box& a, const geom::Box& b) {
    return std::tie(a.min_x, a.min_y, a.max_x, a.max_y) < std::tie(b.min_x, b.min_y, b.max_x, b.max_y);
  });
  boxes.erase(std::unique(boxes.begin(), boxes.end(),
                          [](const geom::Box& a, const geom::Box& b) {
                            return a.min_x == b.min_x && a.min_y == b.min_y && a.max_x == b.max_x && a.max_y == b.max_y;
                          }),
              boxes.end());
  return boxes;
}

// The window: the cells of a grid that the changed boxes meet. Its outline is made of the
// cells' sides with an unmarked cell across, so no two of its edges overlap (overlapping
// window rings tripped the sweep). The grid is offset by a fraction of a metre so its lines
// do not run along the sketch's round coordinates.
struct Window {
  static constexpr double kCell = 40;
  double x0 = 0, y0 = 0;
  std::set<std::pair<int, int>> cells;
  int column(double x) const { return static_cast<int>(std::floor((x - x0) / kCell)); }
  int row(double y) const { return static_cast<int>(std::floor((y - y0) / kCell)); }
  geom::Vec2 corner(int i, int j) const { return {x0 + i * kCell, y0 + j * kCell}; }
  // Whether a cell the box meets is marked (a cell either side of a box's edge on a grid line counts).
  bool meets(const geom::Box& b) const {
    for (int i = column(b.min_x) - 1; i <= column(b.max_x) + 1; ++i)
      if (auto it = cells.lower_bound({i, row(b.min_y) - 1}); it != cells.end() && it->first == i && it->second <= row(b.max_y) + 1)
        return true;
    return false;
  }
};

Window window_of(const std::vector<geom::Box>& changed, const ValidatedPolygons& now) {
  Window w;
  geom::Box all = geom::Box::none();
  for (const geom::Box& b : now.boxes) all.add(b);
  if (!all.holds_nothing()) w.x0 = std::floor(all.min_x) - 0.318, w.y0 = std::floor(all.min_y) - 0.318;
  for (const geom::Box& b : changed)
    for (int i = w.column(b.min_x); i <= w.column(b.max_x); ++i)
      for (int j = w.row(b.min_y); j <= w.row(b.max_y); ++j) w.cells.insert({i, j});
  return w;
}

// The window's outline around `counter`, counter-clockwise.
void add_window(geom::PlanarMap& map, const Window& w, int counter) {
  for (const auto& [i, j] : w.cells) {
    const geom::Vec2 a = w.corner(i, j), b = w.corner(i + 1, j), c = w.corner(i + 1, j + 1), d = w.corner(i, j + 1);
    if (!w.cells.count({i, j - 1})) map.add_edge(a, b, counter);
    if (!w.cells.count({i + 1, j})) map.add_edge(b, c, counter);
    if (!w.cells.count({i, j + 1})) map.add_edge(c, d, counter);
    if (!w.cells.count({i - 1, j})) map.add_edge(d, a, counter);
  }
}

// The polygons' map of a window holds every polygon whose box meets it (the only ones
// that can cover a point in it), and the road areas beside its lots, which the lots'
// frontage needs.
void window_polygons(const Window& window, const ValidatedPolygons& now, const std::vector<PolygonRef>& refs,
                     std::vector<char>& in_window, std::vector<char>& fronting) {
  const std::size_t P = refs.size();
  in_window.assign(P, 0), fronting.assign(P, 0);
  std::vector<geom::Box> lots;
  for (std::size_t p = 0; p < P; ++p) {
    in_window[p] = window.meets(now.boxes[p]);
    if (in_window[p] && refs[p].kind == Kind::Lot) lots.push_back(now.boxes[p]);
  }
  for (std::size_t p = 0; p < P; ++p)
    if (!in_window[p] && (refs[p].kind == Kind::Road || refs[p].kind == Kind::Bridge))
      fronting[p] = std::any_of(lots.begin(), lots.end(), [&](const geom::Box& b) { return b.meets(now.boxes[p]); });
}

Validation validate(const fs::path& dir, std::shared_ptr<ValidatedPolygons>* last) {
  // Kept again below only if this city passes.
  const std::shared_ptr<ValidatedPolygons> previous = last ? std::exchange(*last, nullptr) : nullptr;
  Validation v;
  Checker c(v);
  Sketch sketch;
  try {
    sketch = load_sketch(dir / "sketch.geojson", false);
  } catch (const UserError& e) {
    c.problem(std::string("sketch copy: ") + e.what());
    return v;
  }
  std::vector<std::string> read_problems;
  const CityLayers layers = read_layers(dir / "vector", read_problems);
  const Layer &zones = layers.zones, &water = layers.water, &road_areas = layers.road_areas, &blocks = layers.blocks,
              &lots = layers.lots, &buildings = layers.buildings, &roads = layers.roads;
  for (auto& p : read_problems) c.problem(p);

  std::vector<PolygonRef> refs;
  std::vector<const geom::Polygon*> polygons;
  for (const Layer* l : {&zones, &water, &road_areas, &blocks, &lots, &buildings}) check_polygons(c, *l, refs, polygons);
  for (const auto& f : buildings.features)
    if (!(f.properties.value("height", 0.0) > 0))
      c.problem("buildings.geojson: building " + std::to_string(f.properties.value("id", -1)) + " has no height");
  for (const auto& f : lots.features) {
    auto zt = parse_zone_type(f.properties.value("zone", ""));
    if (zt && geom::area(f.polygon) < sketch.zone_settings.at(*zt).lots.min_lot_area)
      c.problem("lots.geojson: lot " + std::to_string(f.properties.value("id", -1)) + " is under its zone's min_lot_area");
  }
  v.features["roads"] = static_cast<int>(roads.features.size());
  for (std::size_t i = 0; i < roads.features.size(); ++i) {
    const VectorFeature& f = roads.features[i];
    for (const char* key : {"id", "class", "width", "level", "region", "bridge"})
      if (!f.properties.contains(key)) c.problem("roads.geojson features[" + std::to_string(i) + "]: no \"" + key + "\"");
    if (f.line.size() < 2) c.problem("roads.geojson features[" + std::to_string(i) + "]: fewer than 2 positions");
  }
  for (const Layer* l : {&zones, &water, &road_areas, &blocks, &lots, &buildings, &roads}) {
    std::set<int> ids;
    for (std::size_t i = 0; i < l->features.size(); ++i)
      if (!ids.insert(l->features[i].properties.value("id", -1)).second)
        c.problem(l->name + ".geojson features[" + std::to_string(i) + "]: its id is not unique");
  }
  const bool well_formed = v.ok();  // the checks below need simple rings and whole lines
  check_references(c, lots, "block", blocks);
  check_references(c, buildings, "lot", lots);
  check_references(c, road_areas, "road", roads);
  check_references(c, blocks, "roads", roads);
  if (!well_formed) return v;
  // The tiling's map, the roads' checks and the clutter's share nothing: they run at once,
  // each with its own problems, taken in this order as if they had run one after another.
  Validation tiling, road_checks, clutter;
  std::shared_ptr<ValidatedPolygons> now;
  invoke_cancellable(
      [&] {
        Checker t(tiling);
        if (!last) return check_tiling(t, sketch, refs, polygons);
        now = std::make_shared<ValidatedPolygons>(polygons_of(refs, polygons));
        if (!previous) return check_tiling(t, sketch, refs, polygons);
        // Within the window of what changed (docs/design.md, Regions and regenerating); a
        // problem there is looked for again in the whole city, whose check states it.
        const Window window = window_of(changed_boxes(*previous, *now, refs), *now);
        std::vector<char> in_window, fronting;
        window_polygons(window, *now, refs, in_window, fronting);
        check_tiling(t, sketch, refs, polygons, &window, in_window, fronting);
        if (tiling.ok()) return;
        tiling = {};
        check_tiling(t, sketch, refs, polygons);
      },
      [&] {
        Checker r(road_checks);
        check_roads(r, sketch, roads, water);
        validate_clutter(dir, layers, clutter);
      });
  for (const Validation* part : {&tiling, &road_checks, &clutter}) {
    for (const std::string& p : part->problems) c.problem(p);
    v.features.insert(part->features.begin(), part->features.end());
    v.widest_sliver = std::max(v.widest_sliver, part->widest_sliver);
  }
  if (last && v.ok()) *last = now;
  return v;
}

}  // namespace

Validation validate_output(const fs::path& dir) { return validate(dir, nullptr); }

Validation validate_output(const fs::path& dir, std::shared_ptr<ValidatedPolygons>& last) {
  return validate(dir, &last);
}

}  // namespace exacity
