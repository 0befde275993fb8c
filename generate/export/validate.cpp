#include "generate/export/validate.h"
#include "generate/export/validate_window.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <exception>
#include <map>
#include <numeric>
#include <span>
#include <string_view>
#include <stdexcept>
#include <set>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "generate/cancel.h"
#include "generate/cancellable_invoke.h"
#include "generate/city/drawn_zones.h"
#include "generate/errors.h"
#include "generate/export/geojson.h"
#include "generate/export/read_lines.h"
#include "generate/export/ring_sides.h"
#include "generate/export/validate_nesting.h"
#include "generate/export/validate_tiles.h"
#include "generate/export/validate_clutter.h"
#include "generate/export/vector_layers.h"
#include "generate/sketch/sketch.h"
#include "geom/box_index.h"
#include "geom/measure.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"
#include "geom/segment_index.h"
#include "geom/shared_ends.h"

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
  // For zones: the block of the same rings was proven and left out of the map, so the zone
  // counts as holding its block (prove_blocks).
  bool block_left_out = false;
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

// Counters of a tile's map (check_tile): polygon p's outer ring winds around 2p and its
// holes around 2p + 1; the tile's outline around 2P and the window's around 2P + 1 (P
// polygons); the edges that stand in for a run of a ring's edges outside the tile
// (ring_near_tile) around their ring's counter plus 2P + kStandIns, so that they count in
// its windings but are no edge of it.
constexpr int kStandIns = 2;

// Labels each face of the tiling map with the index of what is wrong there, 0 where
// nothing is; each problem is stated once however many faces have it.
// Two maps are labelled: the zoning map (zones, parks, water, road areas and the drawn
// zones), whose faces are checked against the sketch, and the map of every polygon (or of
// those a window meets), whose faces get every other check.
class FaceLabels {
 public:
  // With `drawn`, the zoning map's; else a tile of the polygons' map, whose faces are
  // checked only inside every ring of `inside_of` (the tile's outline, and the window's).
  // With both `drawn` and `polygon_checks`, the zoning map's faces get every check: the
  // polygons' first, then the sketch's.
  // With `far_counter` (the zoning map's), the far zoning polygons' outline winds around
  // it (far_zoning): a face it winds once around and nothing else lies in one far polygon,
  // which was proven to pass there; any other face it winds around is no proof.
  FaceLabels(const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs, const DrawnZones* drawn, int polygons,
             std::vector<int> inside_of = {}, bool polygon_checks = false, int far_counter = -1)
      : sketch_(sketch), refs_(refs), drawn_(drawn), polygons_(polygons), inside_of_(std::move(inside_of)),
        polygon_checks_(polygon_checks || !drawn), far_counter_(far_counter) {}

  int of(const geom::Windings& windings) {
    cancel_.check();
    for (int counter : inside_of_)
      if (geom::winding_of(windings, counter) == 0) return 0;
    if (far_counter_ >= 0) {
      if (const int far = geom::winding_of(windings, far_counter_); far != 0) {
        if (far == 1 && (windings.empty() || windings.front().first >= 2 * polygons_)) return 0;
        return wrong("far zoning polygons overlap");  // not a sketch check: the whole map decides
      }
    }
    const geom::Windings& w = with_stand_ins(windings);
    inside_.clear();
    if (int label = ring_windings(w, inside_)) return label;
    const FaceCover here(refs_, inside_, by_kind_);
    if (polygon_checks_) {
      if (int label = overlaps(here)) return label;
      if (int label = nesting(here)) return label;
    }
    return drawn_ ? against_sketch(here, w) : 0;
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

  // The windings with each stand-in's counter (kStandIns on from its ring's) counted as its ring's.
  const geom::Windings& with_stand_ins(const geom::Windings& w) {
    if (w.empty() || w.back().first < stand_ins_) return w;
    merged_.clear();
    for (const auto& [counter, winding] : w)
      if (counter < 2 * polygons_) merged_.push_back({counter, winding});
      else if (counter >= stand_ins_) merged_.push_back({counter - stand_ins_, winding});
    std::sort(merged_.begin(), merged_.end());
    std::size_t n = 0;
    for (std::size_t i = 0; i < merged_.size(); ++i)
      if (n > 0 && merged_[n - 1].first == merged_[i].first) merged_[n - 1].second += merged_[i].second;
      else merged_[n++] = merged_[i];
    merged_.resize(n);
    std::erase_if(merged_, [](const auto& c) { return c.second == 0; });
    return merged_;
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
        if (!polygon_checks_) continue;
        return wrong(refs_[p].name + ": outer ring winds " + std::to_string(outer) + " times");
      }
      if (holes != 0 && (holes != -1 || outer != 1)) {
        if (!polygon_checks_) continue;
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
    std::size_t zones = 0;  // those whose block is in the map
    for (int z : here.all(Kind::Zone)) zones += !refs_[z].block_left_out;
    if (zones != here.count({Kind::Block}))
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
  const int polygons_;
  const std::vector<int> inside_of_;
  const bool polygon_checks_;
  const int far_counter_;
  const int stand_ins_ = drawn_ ? INT_MAX : 2 * polygons_ + kStandIns;  // the zoning map's counters from 2P on are the drawn zones
  geom::Windings merged_;  // with_stand_ins' buffer
  const CancelCheck cancel_;
  std::map<std::string, int> message_index_{{"", 0}};
  std::map<std::pair<int, int>, int> nested_;  // overlapping buildings -> their problem's label, 0 for none
  std::vector<int> inside_, by_kind_;  // of the face being labelled (FaceCover's buffers)
};

// A grid of square cells, offset by a fraction of a metre so its lines do not run along the
// sketch's round coordinates: the window's cells (below), and the tiles of the polygons' map
// (each tile a square of cells, so a tile holds whole cells of the window).
struct Grid {
  static constexpr double kCell = 40;
  double x0 = 0, y0 = 0;
  int column(double x) const { return static_cast<int>(std::floor((x - x0) / kCell)); }
  int row(double y) const { return static_cast<int>(std::floor((y - y0) / kCell)); }
  geom::Vec2 corner(int i, int j) const { return {x0 + i * kCell, y0 + j * kCell}; }
};

// The grid of a city whose polygons' outer rings have these boxes.
Grid grid_of(const std::vector<geom::Box>& boxes) {
  geom::Box all = geom::Box::none();
  for (const geom::Box& b : boxes) all.add(b);
  Grid g;
  if (!all.holds_nothing()) g.x0 = std::floor(all.min_x) - 0.318, g.y0 = std::floor(all.min_y) - 0.318;
  return g;
}

// The window: the cells that the changed boxes meet. Its outline is made of the cells'
// sides with an unmarked cell across, so no two of its edges overlap (overlapping window
// rings tripped the sweep).
struct Window {
  Grid grid;
  std::set<std::pair<int, int>> cells;
  // Whether a cell the box meets is marked (a cell either side of a box's edge on a grid line counts).
  bool meets(const geom::Box& b) const {
    for (int i = grid.column(b.min_x) - 1; i <= grid.column(b.max_x) + 1; ++i)
      if (auto it = cells.lower_bound({i, grid.row(b.min_y) - 1});
          it != cells.end() && it->first == i && it->second <= grid.row(b.max_y) + 1)
        return true;
    return false;
  }
};

// The outline of the window's cells in columns [i0, i1) and rows [j0, j1) around
// `counter`, counter-clockwise.
void add_window(geom::PlanarMap& map, const Window& w, int counter, int i0, int j0, int i1, int j1) {
  auto marked = [&](int i, int j) { return i >= i0 && i < i1 && j >= j0 && j < j1 && w.cells.count({i, j}); };
  for (auto it = w.cells.lower_bound({i0, INT_MIN}); it != w.cells.end() && it->first < i1; ++it) {
    const auto [i, j] = *it;
    if (!marked(i, j)) continue;
    const geom::Vec2 a = w.grid.corner(i, j), b = w.grid.corner(i + 1, j), c = w.grid.corner(i + 1, j + 1),
                     d = w.grid.corner(i, j + 1);
    if (!marked(i, j - 1)) map.add_edge(a, b, counter);
    if (!marked(i + 1, j)) map.add_edge(b, c, counter);
    if (!marked(i, j + 1)) map.add_edge(c, d, counter);
    if (!marked(i - 1, j)) map.add_edge(d, a, counter);
  }
}

// Each face problem once, near a face that has it, given to `problem(message, near)`.
// Faces found wrong only against the sketch and no wider than kRounding are rounding
// slivers, not problems: the widest is kept in `widest_sliver`.
template <typename F>
void report_face_problems(const geom::PlanarMap& map, const FaceLabels& labels, double& widest_sliver, F&& problem) {
  if (labels.messages.size() == 1) return;  // no face has a problem: no widths to measure (a pass over every face)
  const std::vector<double> widths = map.widest_faces(static_cast<int>(labels.messages.size()));
  for (std::size_t m = 1; m < labels.messages.size(); ++m) {
    if (labels.sketch_checks[m]) {
      double width = widths[m];
      if (width <= kRounding) {
        widest_sliver = std::max(widest_sliver, width);
        continue;
      }
    }
    geom::Vec2 at;
    problem(labels.messages[m], map.point_near_label(static_cast<int>(m), at) ? near(at) : "");
  }
}

// The polygons of the given kinds (all for none), as the refs and rings of a map of their own.
struct MapPolygons {
  std::vector<PolygonRef> refs;
  std::vector<const geom::Polygon*> polygons;
  void add(const PolygonRef& ref, const geom::Polygon* polygon) { refs.push_back(ref), polygons.push_back(polygon); }
};

// Polygon p's outer ring winds around counter 2p and its holes around 2p + 1.
void add_polygon_rings(geom::PlanarMap& map, const std::vector<const geom::Polygon*>& polygons) {
  const int P = static_cast<int>(polygons.size());
  for (int p = 0; p < P; ++p) {
    map.add_ring(polygons[p]->outer, 2 * p, 0);
    for (std::size_t h = 0; h < polygons[p]->holes.size(); ++h)
      map.add_ring(polygons[p]->holes[h], 2 * p + 1, static_cast<int>(h) + 1);
  }
}

// What one tile of the polygons' map found.
struct TileFindings {
  std::vector<std::pair<std::string, std::string>> face_problems;  // each message once, and where
  std::vector<std::pair<int, geom::Vec2>> shared_rings;  // a polygon two of whose rings share an edge, and where
  std::vector<int> fronting;  // polygons with an edge on a road area's or bridge's edge
};

// Two rings of one polygon may touch at a vertex but not run along each other. One pass
// over the edges also finds which polygons share an edge with a road area or bridge. Every
// edge a tile's map has is checked, outside the tile too: each is where rings of its tags
// really run along each other (stand-ins left out), and each such place of the city lies in
// some tile, whose map holds both rings there.
void check_shared_edges(const geom::PlanarMap& map, const std::vector<PolygonRef>& refs, TileFindings& found) {
  const int P = static_cast<int>(refs.size());
  const CancelCheck cancel;
  std::vector<const geom::CurveTag*> own;
  map.for_each_edge([&](const std::vector<geom::CurveTag>& tags, geom::Vec2 a, geom::Vec2) {
    cancel.check();
    own.clear();
    bool road = false;
    for (const auto& t : tags)
      if (t.counter < 2 * P) {  // a ring's own edge (not the tile's, the window's or a stand-in)
        own.push_back(&t);
        road |= refs[t.counter / 2].kind == Kind::Road || refs[t.counter / 2].kind == Kind::Bridge;
      }
    for (std::size_t i = 0; i < own.size(); ++i) {
      const int p = own[i]->counter / 2;
      if (road) found.fronting.push_back(p);
      for (std::size_t j = i + 1; j < own.size(); ++j)
        if (own[j]->counter / 2 == p) found.shared_rings.push_back({p, a});
    }
  });
}

bool is_zoning(Kind k) { return k == Kind::Zone || k == Kind::Park || k == Kind::Water || k == Kind::Road || k == Kind::Bridge; }

struct SegmentHash {
  std::size_t operator()(const geom::SegmentKey& k) const {
    return geom::Vec2Hash()({k.first.first, k.first.second}) * 31 ^ geom::Vec2Hash()({k.second.first, k.second.second});
  }
};

// The zoning polygons the zoning map need not hold one by one (docs/design.md, Validation
// by tiles: the zoning map's proof). A zone, park, water or road area is far when it has
// no holes, its box meets no drawn edge (so the drawn zones are the same all over it) and
// no box of a polygon the map holds that is not one of these (a bridge; with the polygons'
// checks, a block, lot or building the proofs left), and, a zone or park, the drawn zone
// on top there is of its type (a zone, with the polygons' checks, counts as holding its
// block: block_left_out). Such a polygon passes every check of the map's faces in it unless
// another zoning polygon overlaps it. The map holds, in place of the far polygons, their
// outline: their edges less each pair that two of them have, one each way. The far
// polygons' windings sum to the outline's exactly (the pairs cancel), and both sides of a
// pair lie in far polygons, so the map's faces outside every far polygon are the whole
// map's, labelled as there; a face the outline winds once around and nothing else does
// lies in one far polygon, and passes; any other face it winds around is an overlap.
struct FarZoning {
  std::vector<char> far;  // by polygon
  std::vector<std::pair<geom::Vec2, geom::Vec2>> outline;  // directed edges, ordered by their ends
  bool any() const { return !outline.empty(); }
};

FarZoning far_zoning(const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                     const std::vector<const geom::Polygon*>& polygons, const std::vector<char>* rest) {
  const std::size_t P = refs.size();
  FarZoning out;
  out.far.assign(P, 0);
  auto box_of = [](const geom::Ring& ring) {
    geom::Box b = geom::Box::none();
    for (geom::Vec2 q : ring) b.add(q);
    return b;
  };
  std::vector<std::pair<geom::Vec2, geom::Vec2>> drawn_edges;
  geom::BoxIndex drawn_index(64.0);
  for (const ZoneFeature& z : sketch.zones)
    for (const geom::Polygon& polygon : z.polygons)
      for (int r = 0; r <= static_cast<int>(polygon.holes.size()); ++r) {
        const geom::Ring& ring = r == 0 ? polygon.outer : polygon.holes[r - 1];
        for (std::size_t i = 0; i < ring.size(); ++i) {
          const geom::Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
          drawn_index.add(static_cast<int>(drawn_edges.size()), box_of({a, b}));
          drawn_edges.push_back({a, b});
        }
      }
  geom::BoxIndex mapped_index(32.0);  // what the map holds that is not a far candidate (ids from 0: its queries pass over them all)
  int mapped = 0;
  for (std::size_t p = 0; p < P; ++p)
    if (refs[p].kind == Kind::Bridge || (rest && (*rest)[p] && !is_zoning(refs[p].kind)))
      mapped_index.add(mapped++, box_of(polygons[p]->outer));
  // The last drawn zone whose polygon's outer ring winds around p and no hole of it does
  // (DrawnZones::top_zone); p lies on no drawn edge.
  auto top_zone = [&](geom::Vec2 p) {
    for (int z = static_cast<int>(sketch.zones.size()) - 1; z >= 0; --z)
      for (const geom::Polygon& polygon : sketch.zones[z].polygons) {
        if (exact_winding_number(polygon.outer, p) == 0) continue;
        bool in_hole = false;
        for (const geom::Ring& h : polygon.holes) in_hole |= exact_winding_number(h, p) != 0;
        if (!in_hole) return z;
      }
    return -1;
  };
  const bool polygon_checks = rest != nullptr;
  for_each_cancellable(P, [&](std::size_t p) {
    const PolygonRef& ref = refs[p];
    const geom::Polygon& polygon = *polygons[p];
    if (ref.kind == Kind::Bridge || !is_zoning(ref.kind) || !polygon.holes.empty() || polygon.outer.size() < 3) return;
    if (polygon_checks && ref.kind == Kind::Zone && !ref.block_left_out) return;
    const geom::Box box = box_of(polygon.outer);
    for (int e : drawn_index.meeting(box))
      if (segment_meets_box(drawn_edges[e].first, drawn_edges[e].second, box)) return;
    if (!mapped_index.meeting(box).empty()) return;
    if (ref.kind == Kind::Zone || ref.kind == Kind::Park) {
      const int top = top_zone(polygon.outer[0]);
      if (top < 0 || ref.zone != name(sketch.zones[top].type)) return;
    }
    out.far[p] = 1;
  });
  // The far edges sorted by segment (a hash of half a million edges missed the cache at
  // every edge), each group's count one way less the other (the way from the lower end, as
  // segment_key orders them, counts +1) left as that many edges in the outline.
  struct FarEdge {
    geom::SegmentKey key;
    int way;
  };
  std::vector<FarEdge> edges;
  for (std::size_t p = 0; p < P; ++p) {
    if (!out.far[p]) continue;
    const geom::Ring& ring = polygons[p]->outer;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const geom::Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
      const geom::SegmentKey key = geom::segment_key(a, b);
      edges.push_back({key, key.first == std::pair{a.x, a.y} ? 1 : -1});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const FarEdge& a, const FarEdge& b) { return a.key < b.key; });
  for (std::size_t i = 0, j = 0; i < edges.size(); i = j) {
    int net = 0;
    for (j = i; j < edges.size() && edges[j].key == edges[i].key; ++j) net += edges[j].way;
    const geom::Vec2 lower{edges[i].key.first.first, edges[i].key.first.second},
        upper{edges[i].key.second.first, edges[i].key.second.second};
    for (; net > 0; --net) out.outline.push_back({lower, upper});
    for (; net < 0; ++net) out.outline.push_back({upper, lower});
  }
  return out;
}

// What a zoning map found: nothing but rounding slivers, problems of the polygons (the
// caller checks every map again), or, with far polygons, anything (the whole map decides).
enum class ZoningFound { Nothing, PolygonProblems, NoProof };

// The zoning polygons (but the far ones, whose outline stands in for them) and the drawn
// zones in one exact map, each face labelled with what is wrong there against the sketch;
// rounding slivers are measured here. With `rest`, the polygons the polygons' map would
// hold (those of `rest`: the zoning polygons and the few blocks, lots and buildings not
// proven without it) are all in this map, and its faces and edges get that map's checks
// too, before the sketch's.
ZoningFound zoning_map(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                       const std::vector<const geom::Polygon*>& polygons, const std::vector<char>* rest,
                       const FarZoning* far) {
  const geom::SharedEndsByOrientation shared_ends;  // every end is a written double
  const bool polygon_checks = rest != nullptr;
  MapPolygons zoning;
  for (std::size_t p = 0; p < refs.size(); ++p)
    if ((is_zoning(refs[p].kind) || (rest && (*rest)[p])) && !(far && far->far[p])) zoning.add(refs[p], polygons[p]);
  geom::PlanarMap map;
  const int P = static_cast<int>(zoning.polygons.size());
  add_polygon_rings(map, zoning.polygons);
  DrawnZones drawn(sketch.zones, map, 2 * P);
  const int far_counter = far ? drawn.end_counter() : -1;
  if (far)
    for (const auto& [a, b] : far->outline) map.add_edge(a, b, far_counter);
  map.insert_batch();
  FaceLabels labels(sketch, zoning.refs, &drawn, P, {}, polygon_checks, far_counter);
  map.label_faces([&](const geom::Windings& w) { return labels.of(w); });
  bool polygon_problems = false;
  if (polygon_checks) {
    for (std::size_t m = 1; m < labels.messages.size(); ++m) polygon_problems |= !labels.sketch_checks[m];
    TileFindings found;
    check_shared_edges(map, zoning.refs, found);
    polygon_problems |= !found.shared_rings.empty();
    std::vector<char> fronts(P, 0);
    for (int p : found.fronting) fronts[p] = 1;
    for (int p = 0; p < P; ++p) polygon_problems |= zoning.refs[p].kind == Kind::Lot && !fronts[p];
  } else if (far) {
    for (std::size_t m = 1; m < labels.messages.size(); ++m) polygon_problems |= !labels.sketch_checks[m];
  }
  if (polygon_problems) return far ? ZoningFound::NoProof : ZoningFound::PolygonProblems;
  if (far) {
    // Only rounding slivers: the whole map would find these, and no more.
    double widest = 0;
    bool problems = false;
    report_face_problems(map, labels, widest, [&](const std::string&, const std::string&) { problems = true; });
    if (problems) return ZoningFound::NoProof;
    c.v_.widest_sliver = std::max(c.v_.widest_sliver, widest);
    return ZoningFound::Nothing;
  }
  report_face_problems(map, labels, c.v_.widest_sliver,
                       [&](const std::string& m, const std::string& at) { c.problem(m + at); });
  return ZoningFound::Nothing;
}

// The zoning map, with the far zoning polygons' proof first (`far_proof`); returns whether
// the polygons' checks (with `rest`) found anything, when the caller checks every map again.
bool check_zoning(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                  const std::vector<const geom::Polygon*>& polygons, const std::vector<char>* rest = nullptr,
                  bool far_proof = true) {
  if (far_proof) {
    const FarZoning far = far_zoning(sketch, refs, polygons, rest);
    if (far.any() && zoning_map(c, sketch, refs, polygons, rest, &far) == ZoningFound::Nothing) return false;
  }
  return zoning_map(c, sketch, refs, polygons, rest, nullptr) == ZoningFound::PolygonProblems;
}

// A polygon's rings: ring 0 its outer ring, ring h + 1 its hole h.
const geom::Ring& ring_of(const geom::Polygon& polygon, int ring) { return ring == 0 ? polygon.outer : polygon.holes[ring - 1]; }

// The tiles of the polygons' map: squares of `cells` grid cells, and the rings of `held`
// polygons whose boxes meet each (rings[t]: (polygon, ring) in polygon order).
struct Tiles {
  Grid grid;
  int cells = 1;
  std::vector<std::pair<int, int>> at;  // each tile's column and row
  std::vector<std::vector<std::pair<int, int>>> rings;
  geom::Box box(std::size_t t) const {
    const geom::Vec2 lo = grid.corner(at[t].first * cells, at[t].second * cells);
    const geom::Vec2 hi = grid.corner((at[t].first + 1) * cells, (at[t].second + 1) * cells);
    return {lo.x, lo.y, hi.x, hi.y};
  }
};

// Tiles of about this many ring vertices each: small maps sweep faster and hold less, and
// each ring a tile cuts is partly swept twice.
constexpr double kVerticesPerTile = 20000;

Tiles tiles_of(const Grid& grid, const std::vector<const geom::Polygon*>& polygons, const std::vector<char>& held,
               double tile_side) {
  Tiles tiles;
  tiles.grid = grid;
  struct HeldRing {
    int polygon, ring;
    geom::Box box;
  };
  std::vector<HeldRing> rings;
  geom::Box all = geom::Box::none();
  double vertices = 0;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    if (!held[p]) continue;
    for (int r = 0; r <= static_cast<int>(polygons[p]->holes.size()); ++r) {
      geom::Box b = geom::Box::none();
      for (geom::Vec2 q : ring_of(*polygons[p], r)) b.add(q);
      if (b.holds_nothing()) continue;
      rings.push_back({static_cast<int>(p), r, b});
      all.add(b);
      vertices += static_cast<double>(ring_of(*polygons[p], r).size());
    }
  }
  if (rings.empty()) return tiles;
  if (tile_side <= 0)
    tile_side = std::sqrt(std::max(all.width() * all.height(), 1.0) * kVerticesPerTile / std::max(vertices, 1.0));
  tiles.cells = std::clamp(static_cast<int>(std::lround(tile_side / Grid::kCell)), 1, 1 << 20);
  const double side = tiles.cells * Grid::kCell;
  auto tile_column = [&](double x) { return static_cast<int>(std::floor((x - grid.x0) / side)); };
  auto tile_row = [&](double y) { return static_cast<int>(std::floor((y - grid.y0) / side)); };
  std::map<std::pair<int, int>, std::size_t> index;  // tile (column, row) -> t, in that order
  const int c0 = tile_column(all.min_x) - 1, r0 = tile_row(all.min_y) - 1;
  for (int i = c0; i <= tile_column(all.max_x) + 1; ++i)
    for (int j = r0; j <= tile_row(all.max_y) + 1; ++j) index.emplace(std::pair{i, j}, 0);
  std::vector<std::vector<std::pair<int, int>>> by_cell(index.size());
  {
    std::size_t t = 0;
    for (auto& [cell, at] : index) at = t++;
  }
  for (const HeldRing& r : rings)
    for (int i = tile_column(r.box.min_x) - 1; i <= tile_column(r.box.max_x) + 1; ++i)
      for (int j = tile_row(r.box.min_y) - 1; j <= tile_row(r.box.max_y) + 1; ++j) {
        const geom::Vec2 lo = grid.corner(i * tiles.cells, j * tiles.cells);
        const geom::Vec2 hi = grid.corner((i + 1) * tiles.cells, (j + 1) * tiles.cells);
        if (r.box.meets({lo.x, lo.y, hi.x, hi.y})) by_cell[index.at({i, j})].push_back({r.polygon, r.ring});
      }
  for (auto& [cell, t] : index)
    if (!by_cell[t].empty()) tiles.at.push_back(cell), tiles.rings.push_back(std::move(by_cell[t]));
  return tiles;
}

// One tile's map: each held ring as its edges near the tile (ring_near_tile), the tile's
// outline and the window's cells in it; its faces inside both labelled with what is wrong
// there, then its edges.
TileFindings check_tile(const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                        const std::vector<const geom::Polygon*>& polygons, const Tiles& tiles, std::size_t t,
                        const Window* window) {
  const geom::SharedEndsByOrientation shared_ends;  // every end is a written double
  const int P = static_cast<int>(refs.size());
  const geom::Box box = tiles.box(t);
  geom::PlanarMap map;
  std::vector<TileEdge> edges;
  for (const auto& [p, r] : tiles.rings[t]) {
    edges.clear();
    ring_near_tile(ring_of(*polygons[p], r), box, edges);
    const int counter = r == 0 ? 2 * p : 2 * p + 1;
    for (const TileEdge& e : edges) map.add_edge(e.a, e.b, e.stand_in ? 2 * P + kStandIns + counter : counter);
  }
  map.add_ring({{box.min_x, box.min_y}, {box.max_x, box.min_y}, {box.max_x, box.max_y}, {box.min_x, box.max_y}}, 2 * P);
  std::vector<int> inside_of{2 * P};
  if (window) {
    const int i0 = tiles.at[t].first * tiles.cells, j0 = tiles.at[t].second * tiles.cells;
    add_window(map, *window, 2 * P + 1, i0, j0, i0 + tiles.cells, j0 + tiles.cells);
    inside_of.push_back(2 * P + 1);
  }
  map.insert_batch();
  FaceLabels labels(sketch, refs, nullptr, P, inside_of);
  map.label_faces([&](const geom::Windings& w) { return labels.of(w); });
  TileFindings found;
  double no_slivers = 0;  // none: the polygons' map is not checked against the sketch
  report_face_problems(map, labels, no_slivers,
                       [&](const std::string& m, const std::string& at) { found.face_problems.push_back({m, at}); });
  check_shared_edges(map, refs, found);
  return found;
}

// Lots and buildings the polygons' map need not hold: each proven, exactly and without a
// map, to pass every check that map makes of it (docs/design.md, Validation by tiles:
// proofs). A lot: no holes, in the closed region of the block it names, its interior apart
// from every other lot of that block, an edge running along a road area's; lots of other
// blocks lie apart, as the map checks that the blocks do and that every lot it holds lies
// in its block. A building, not mapped: no holes, in the closed region of the lot it
// names, and where its interior meets another building's (one on the same lot or a mapped
// one: those on other lots lie apart with their lots), nested as the map would ask.
std::vector<char> proven_without_map(const std::vector<PolygonRef>& refs, const std::vector<const geom::Polygon*>& polygons,
                                     const std::vector<geom::Box>& boxes) {
  const std::size_t P = refs.size();
  std::vector<char> proven(P, 0);
  std::unordered_map<int, int> block_at, lot_at;  // id -> polygon
  for (std::size_t p = 0; p < P; ++p) {
    if (refs[p].kind == Kind::Block) block_at.emplace(refs[p].id, static_cast<int>(p));
    if (refs[p].kind == Kind::Lot) lot_at.emplace(refs[p].id, static_cast<int>(p));
  }
  auto edge_box = [](geom::Vec2 a, geom::Vec2 b) {
    geom::Box box = geom::Box::none();
    box.add(a), box.add(b);
    return box;
  };
  // Frontage: a lot's edge that is a road area's or bridge's edge, both ends the same
  // (every lot of the 10 km city has one), else one running along such an edge, looked up
  // in an index of those edges made only for the lots that need it.
  std::unordered_set<geom::SegmentKey, SegmentHash> road_edges;  // every ring's of road areas and bridges
  auto for_each_road_edge = [&](auto&& f) {
    for (std::size_t p = 0; p < P; ++p) {
      if (refs[p].kind != Kind::Road && refs[p].kind != Kind::Bridge) continue;
      for (int r = 0; r <= static_cast<int>(polygons[p]->holes.size()); ++r) {
        const geom::Ring& ring = ring_of(*polygons[p], r);
        for (std::size_t i = 0; i < ring.size(); ++i) f(ring[i], ring[(i + 1) % ring.size()]);
      }
    }
  };
  for_each_road_edge([&](geom::Vec2 a, geom::Vec2 b) { road_edges.insert(geom::segment_key(a, b)); });
  auto has_road_edge = [&](const geom::Ring& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i)
      if (road_edges.count(geom::segment_key(ring[i], ring[(i + 1) % ring.size()]))) return true;
    return false;
  };
  std::vector<char> along_only(P, 0);  // lots proven but for an edge along a road area's
  // Each lot and building on its own, at once.
  for_each_cancellable(P, [&](std::size_t p) {
    const PolygonRef& ref = refs[p];
    const geom::Polygon& polygon = *polygons[p];
    if (!polygon.holes.empty()) return;
    if (ref.kind == Kind::Lot) {
      const auto block = block_at.find(ref.block);
      if (block == block_at.end() || !ring_in_polygon(polygon.outer, *polygons[block->second])) return;
      proven[p] = has_road_edge(polygon.outer);
      along_only[p] = !proven[p];
    } else if (ref.kind == Kind::Building && !ref.properties->value("mapped", false)) {
      const auto lot = lot_at.find(ref.lot);
      proven[p] = lot != lot_at.end() && ring_in_polygon(polygon.outer, *polygons[lot->second]);
    }
  });
  if (std::find(along_only.begin(), along_only.end(), 1) != along_only.end()) {
    std::vector<std::pair<geom::Vec2, geom::Vec2>> edges;
    geom::BoxIndex index(16.0);
    for_each_road_edge([&](geom::Vec2 a, geom::Vec2 b) {
      index.add(static_cast<int>(edges.size()), edge_box(a, b));
      edges.push_back({a, b});
    });
    for_each_cancellable(P, [&](std::size_t p) {
      if (!along_only[p]) return;
      const geom::Ring& ring = polygons[p]->outer;
      for (std::size_t i = 0; i < ring.size() && !proven[p]; ++i) {
        const geom::Vec2 a = ring[i], b = ring[(i + 1) % ring.size()];
        for (int e : index.meeting(edge_box(a, b)))
          if (segments_run_along(a, b, edges[e].first, edges[e].second)) proven[p] = 1;
      }
    });
  }
  // Then the pairs whose boxes meet, each once: lots of one block, buildings on one lot or
  // mapped (as the map takes them, the first in polygon order first).
  std::unordered_map<int, std::vector<int>> by_block, by_lot;  // lots by their block, unmapped buildings by their lot
  std::vector<int> mapped;
  for (std::size_t p = 0; p < P; ++p) {
    if (refs[p].kind == Kind::Lot) by_block[refs[p].block].push_back(static_cast<int>(p));
    if (refs[p].kind != Kind::Building) continue;
    if (refs[p].properties->value("mapped", false)) mapped.push_back(static_cast<int>(p));
    else by_lot[refs[p].lot].push_back(static_cast<int>(p));
  }
  std::vector<char> paired(P, 1);  // every pair of p's checked is apart, or nested as the map asks
  const CancelCheck cancel;
  auto pair = [&](int p, int o) {
    if (!proven[p] && !proven[o]) return;
    if (!boxes[p].meets(boxes[o])) return;
    if (!polygons[p]->holes.empty() || !polygons[o]->holes.empty()) return void(paired[p] = paired[o] = 0);
    if (interiors_apart(polygons[p]->outer, polygons[o]->outer)) return;
    const PolygonRef &a = refs[std::min(p, o)], &b = refs[std::max(p, o)];
    if (a.kind == Kind::Lot || nested_overlap_problem(*a.properties, a.name, *b.properties, b.name)) paired[p] = paired[o] = 0;
  };
  for (const auto* groups : {&by_block, &by_lot})
    for (const auto& [id, group] : *groups) {
      cancel.check();
      for (std::size_t i = 0; i < group.size(); ++i)
        for (std::size_t j = i + 1; j < group.size(); ++j) pair(group[i], group[j]);
    }
  if (!mapped.empty()) {
    geom::BoxIndex building_index(32.0);
    for (std::size_t p = 0; p < P; ++p)
      if (refs[p].kind == Kind::Building) building_index.add(static_cast<int>(p), boxes[p]);
    for (int m : mapped)
      for (int o : building_index.meeting(boxes[m]))
        if (o != m) pair(m, o);  // two mapped ones: neither is proven
  }
  for (std::size_t p = 0; p < P; ++p) proven[p] &= paired[p];
  return proven;
}

// Whether two rings are the same: the same vertices in the same order, from any start.
bool same_ring(const geom::Ring& a, const geom::Ring& b) {
  if (a.size() != b.size()) return false;
  if (a.empty()) return true;
  const auto start = std::find(b.begin(), b.end(), a[0]);
  if (start == b.end()) return false;
  const std::size_t k = static_cast<std::size_t>(start - b.begin());
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[(k + i) % b.size()])) return false;
  return true;
}

// Blocks the polygons' map need not hold, as zone z holds block b (zone_of_block[b] = z):
// the block's rings are one zone's, that zone is the one zone and the block the one block
// with them, the block's zone is that zone's (or the block is green), and every lot that
// names the block is proven without the map. The zone stays in the map and checks for its
// block: overlaps with other zones, parks, water and road areas, the windings of its rings
// and shared edges; other blocks in the map lie in zones it counts (block_left_out), so a
// block over it is found; lots in the map name blocks in it.
void prove_blocks(const std::vector<PolygonRef>& refs, const std::vector<const geom::Polygon*>& polygons,
                  std::vector<char>& proven, std::vector<int>& zone_of_block) {
  const std::size_t P = refs.size();
  zone_of_block.assign(P, -1);
  // Rings by their lowest vertex: the same ring has it whatever its start.
  auto lowest = [](const geom::Ring& r) {
    return *std::min_element(r.begin(), r.end(), [](geom::Vec2 a, geom::Vec2 b) { return std::tie(a.x, a.y) < std::tie(b.x, b.y); });
  };
  auto same_polygon = [&](std::size_t a, std::size_t b) {
    const geom::Polygon &x = *polygons[a], &y = *polygons[b];
    if (!same_ring(x.outer, y.outer) || x.holes.size() != y.holes.size()) return false;
    for (std::size_t h = 0; h < x.holes.size(); ++h)
      if (!same_ring(x.holes[h], y.holes[h])) return false;
    return true;
  };
  std::unordered_map<geom::Vec2, std::vector<int>, geom::Vec2Hash> at;  // zones and blocks by their outer ring's lowest vertex
  std::unordered_set<int> unproven_lots_of;  // blocks named by a lot not proven
  for (std::size_t p = 0; p < P; ++p) {
    if ((refs[p].kind == Kind::Zone || refs[p].kind == Kind::Block) && !polygons[p]->outer.empty())
      at[lowest(polygons[p]->outer)].push_back(static_cast<int>(p));
    if (refs[p].kind == Kind::Lot && !proven[p]) unproven_lots_of.insert(refs[p].block);
  }
  for (const auto& [vertex, here] : at) {
    for (int b : here) {
      if (refs[b].kind != Kind::Block || unproven_lots_of.count(refs[b].id)) continue;
      int zone = -1, same = 0;  // the zone of the same rings, and how many zones and blocks have them
      for (int o : here)
        if (same_polygon(b, o)) ++same, zone = refs[o].kind == Kind::Zone ? o : zone;
      if (same != 2 || zone < 0 || (!refs[b].green && refs[b].zone != refs[zone].zone)) continue;
      proven[b] = 1, zone_of_block[b] = zone;
    }
  }
}

// The polygons' map, tile by tile at once (docs/design.md, Validation by tiles): each face
// inside the window (every face without one) labelled with what is wrong there; then the
// map's edges. Every lot shares an edge with a road area. `held` says which polygons the
// map holds, `checked` which have their lots' frontage checked. Problems are taken tile by
// tile, each once.
void check_polygons_held(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                         const std::vector<const geom::Polygon*>& polygons, const Grid& grid, double tile_side,
                         const Window* window, const std::vector<char>& held, const std::vector<char>& checked) {
  const std::size_t P = refs.size();
  const Tiles tiles = tiles_of(grid, polygons, held, tile_side);
  std::vector<TileFindings> found(tiles.rings.size());
  for_each_cancellable(found.size(), [&](std::size_t t) { found[t] = check_tile(sketch, refs, polygons, tiles, t, window); });
  std::set<std::string> said;
  for (const TileFindings& f : found)
    for (const auto& [message, at] : f.face_problems)
      if (said.insert(message).second) c.problem(message + at);
  std::map<int, geom::Vec2> shared;  // each polygon once, where its first tile found it
  std::vector<char> fronts(P, 0);
  for (const TileFindings& f : found) {
    for (const auto& [p, at] : f.shared_rings) shared.emplace(p, at);
    for (int p : f.fronting) fronts[p] = 1;
  }
  for (const auto& [p, at] : shared) c.problem(refs[p].name + ": two of its rings share an edge" + near(at));
  for (std::size_t p = 0; p < P; ++p)
    if (checked[p] && refs[p].kind == Kind::Lot && !fronts[p]) c.problem(refs[p].name + " touches no road area");
}

// The polygons' map of the whole city, or of a window: `in_window` says which polygons it
// holds (all without a window), and `fronting` which further road areas it needs for the
// lots' frontage.
void check_polygon_map(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                       const std::vector<const geom::Polygon*>& polygons, const Grid& grid, double tile_side,
                       const Window* window, const std::vector<char>& in_window, const std::vector<char>& fronting) {
  const std::size_t P = refs.size();
  std::vector<char> held(P, 1);
  if (window)
    for (std::size_t p = 0; p < P; ++p) held[p] = in_window[p] || fronting[p];
  const std::vector<char> checked = window ? in_window : held;  // a road area added for frontage has no lot's verdict
  check_polygons_held(c, sketch, refs, polygons, grid, tile_side, window, held, checked);
}

// Adds a part's problems and widest sliver to c's.
void take_problems(Checker& c, const Validation& part) {
  for (const std::string& p : part.problems) c.problem(p);
  c.v_.widest_sliver = std::max(c.v_.widest_sliver, part.widest_sliver);
}

// The polygons' map and the zoning map share nothing: they run at once, the polygons'
// problems taken first.
void check_both_maps(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                     const std::vector<const geom::Polygon*>& polygons, const Grid& grid, double tile_side,
                     const Window* window = nullptr, const std::vector<char>& in_window = {},
                     const std::vector<char>& fronting = {}, bool far_proof = true) {
  Validation polygon_map, zoning;
  invoke_cancellable(
      [&] {
        Checker p(polygon_map);
        check_polygon_map(p, sketch, refs, polygons, grid, tile_side, window, in_window, fronting);
      },
      [&] {
        Checker z(zoning);
        check_zoning(z, sketch, refs, polygons, nullptr, far_proof);
      });
  for (const Validation* part : {&polygon_map, &zoning}) take_problems(c, *part);
}

// Of a whole city, the maps first without the blocks, lots and buildings proven to pass
// (proven_without_map, prove_blocks): the polygons' map of the rest beside the zoning map,
// or, when the rest is the zoning polygons, the zoning map alone with both maps' checks.
// When the maps without them find nothing, neither would the whole ones; when they find
// something, the whole maps are checked, so the problems are those of the whole maps.
void check_tiling(Checker& c, const DrawnFeatures& sketch, const std::vector<PolygonRef>& refs,
                  const std::vector<const geom::Polygon*>& polygons, const std::vector<geom::Box>& boxes, const Grid& grid,
                  double tile_side, MapProofs proofs, const Window* window = nullptr, const std::vector<char>& in_window = {},
                  const std::vector<char>& fronting = {}) {
  if (window || proofs == MapProofs::None)
    return check_both_maps(c, sketch, refs, polygons, grid, tile_side, window, in_window, fronting, proofs != MapProofs::None);
  const std::size_t P = refs.size();
  std::vector<char> proven = proven_without_map(refs, polygons, boxes);
  std::vector<int> zone_of_block;
  prove_blocks(refs, polygons, proven, zone_of_block);
  if (std::find(proven.begin(), proven.end(), 1) == proven.end()) return check_both_maps(c, sketch, refs, polygons, grid, tile_side);
  std::vector<PolygonRef> marked = refs;  // the zones whose blocks are left out say so
  std::vector<char> rest(P);
  double rest_vertices = 0;  // of the blocks, lots and buildings left
  for (std::size_t p = 0; p < P; ++p) {
    if (zone_of_block[p] >= 0) marked[zone_of_block[p]].block_left_out = true;
    rest[p] = !proven[p];
    if (rest[p] && !is_zoning(refs[p].kind)) {
      rest_vertices += static_cast<double>(polygons[p]->outer.size());
      for (const geom::Ring& h : polygons[p]->holes) rest_vertices += static_cast<double>(h.size());
    }
  }
  // No more of them than a tile holds: the zoning map, a map of the whole city, holds them too.
  const bool zoning_only = rest_vertices <= kVerticesPerTile;
  if (zoning_only) {
    Validation both;
    Checker b(both);
    if (!check_zoning(b, sketch, marked, polygons, &rest)) return take_problems(c, both);
  } else {
    Validation without, zoning;
    invoke_cancellable(
        [&] {
          Checker w(without);
          check_polygons_held(w, sketch, marked, polygons, grid, tile_side, nullptr, rest, rest);
        },
        [&] {
          Checker z(zoning);
          check_zoning(z, sketch, refs, polygons);
        });
    Validation whole;  // the polygons' map of everything, when the rest's found anything
    if (!without.ok()) {
      Checker w(whole);
      check_polygon_map(w, sketch, refs, polygons, grid, tile_side, nullptr, {}, {});
    }
    for (const Validation* part : {&whole, &zoning}) take_problems(c, *part);
    return;
  }
  check_both_maps(c, sketch, refs, polygons, grid, tile_side);
}

// Whether the centre lines pass check_road_meetings without its map: any two of their
// segments meet nowhere but at an end of both, or are the same segment of one line (each
// pair whose boxes meet asked exactly, segment_meeting). Then no segment is cut and no
// piece is two lines'; anything else (a repeated vertex too) is left to the map.
bool roads_meet_at_vertices(const std::vector<VectorFeature>& features) {
  struct Segment {
    geom::Vec2 a, b;
    int line;
  };
  std::vector<Segment> segments;
  geom::BoxIndex index(64.0);
  for (std::size_t i = 0; i < features.size(); ++i)
    for (std::size_t k = 1; k < features[i].line.size(); ++k) {
      const geom::Vec2 a = features[i].line[k - 1], b = features[i].line[k];
      if (a == b) return false;
      geom::Box box = geom::Box::none();
      box.add(a), box.add(b);
      index.add(static_cast<int>(segments.size()), box);
      segments.push_back({a, b, static_cast<int>(i)});
    }
  std::vector<char> wrong(segments.size(), 0);
  for_each_cancellable(segments.size(), [&](std::size_t s) {
    const Segment& x = segments[s];
    geom::Box box = geom::Box::none();
    box.add(x.a), box.add(x.b);
    for (int o : index.meeting(box)) {
      if (o <= static_cast<int>(s)) continue;
      const Segment& y = segments[o];
      const SegmentMeeting meeting = segment_meeting(x.a, x.b, y.a, y.b);
      if (meeting == SegmentMeeting::Otherwise || (meeting == SegmentMeeting::Same && x.line != y.line)) return void(wrong[s] = 1);
    }
  });
  return std::find(wrong.begin(), wrong.end(), 1) == wrong.end();
}

// The centre lines are a noded network: two of them meet only at a vertex of both. Every
// end of a grown road is a vertex of another centre line (a junction) or lies on the edge
// of the built city (a drawn zone's ring or water). Every piece of the network holding a
// region's roads holds a road the sketch drew (in a sketch without roads, all are one).
// A road's centre line meets another only at its vertices: never between them, nor along
// a segment both have.
// With `proof`, the map only when roads_meet_at_vertices finds anything.
void check_road_meetings(Checker& c, const std::vector<VectorFeature>& features, bool proof) {
  if (proof && roads_meet_at_vertices(features)) return;
  const geom::SharedEndsByOrientation shared_ends;  // every end is a written double
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

void check_roads(Checker& c, const DrawnFeatures& sketch, const Layer& roads, const Layer& water, MapProofs proofs) {
  check_road_meetings(c, roads.features, proofs != MapProofs::None);
  check_road_connectivity(c, roads.features);
  check_road_ends(c, sketch, roads.features, water);
}

// Every reference names the id of a feature of the layer it refers to.
void check_references(Checker& c, const Layer& from, const char* key, const Layer& to) {
  std::unordered_set<int> ids;
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
  // Each layer file's features by the text of their lines, as read (read_geojson): the next
  // reading parses only the lines that changed.
  std::map<std::string, ReadLines> lines;
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

ValidatedPolygons polygons_of(const std::vector<PolygonRef>& refs, const std::vector<const geom::Polygon*>& polygons,
                              const std::vector<geom::Box>& boxes) {
  ValidatedPolygons out;
  for (std::size_t p = 0; p < refs.size(); ++p) {
    out.keys.push_back(polygon_key(refs[p], *polygons[p]));
    out.ids.push_back(refs[p].id);
    out.names.push_back(refs[p].kind == Kind::Lot ? refs[p].block : refs[p].kind == Kind::Building ? refs[p].lot : -1);
  }
  out.boxes = boxes;
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

Window window_of(const std::vector<geom::Box>& changed, const Grid& grid) {
  Window w{grid, {}};
  for (const geom::Box& b : changed)
    for (int i = grid.column(b.min_x); i <= grid.column(b.max_x); ++i)
      for (int j = grid.row(b.min_y); j <= grid.row(b.max_y); ++j) w.cells.insert({i, j});
  return w;
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

Validation validate(const fs::path& dir, std::shared_ptr<ValidatedPolygons>* last, double tile_side,
                    MapProofs proofs = MapProofs::First) {
  // Kept again below only if this city passes.
  const std::shared_ptr<ValidatedPolygons> previous = last ? std::exchange(*last, nullptr) : nullptr;
  std::map<std::string, ReadLines> lines;  // with `last`: the lines read before, then this city's
  if (previous) lines = std::move(previous->lines);
  // A validation cancelled (the server's next generation replaces this city) keeps the last
  // one that passed, to check the next city against; its lines, whatever this read added
  // (a line's reading depends on its text alone).
  struct KeepOnCancel {
    std::shared_ptr<ValidatedPolygons>* last;
    const std::shared_ptr<ValidatedPolygons>& previous;
    std::map<std::string, ReadLines>& lines;
    const int unwinding = std::uncaught_exceptions();
    ~KeepOnCancel() {
      if (previous && std::uncaught_exceptions() > unwinding) previous->lines = std::move(lines), *last = previous;
    }
  } keep{last, previous, lines};
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
  lines["clutter"];  // made before the reads at once
  const CityLayers layers =
      last ? read_layers(dir / "vector", read_problems, lines) : read_layers(dir / "vector", read_problems);
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
    std::unordered_set<int> ids;
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
        std::vector<geom::Box> boxes;  // of the outer rings: for the grid, the proofs and the window, made once
        for (const geom::Polygon* polygon : polygons) {
          geom::Box b = geom::Box::none();
          for (geom::Vec2 q : polygon->outer) b.add(q);
          boxes.push_back(b);
        }
        const Grid grid = grid_of(boxes);
        if (!last) return check_tiling(t, sketch, refs, polygons, boxes, grid, tile_side, proofs);
        now = std::make_shared<ValidatedPolygons>(polygons_of(refs, polygons, boxes));
        if (!previous) return check_tiling(t, sketch, refs, polygons, boxes, grid, tile_side, proofs);
        // Within the window of what changed (docs/design.md, Regions and regenerating); a
        // problem there is looked for again in the whole city, whose check states it.
        const Window window = window_of(changed_boxes(*previous, *now, refs), grid);
        std::vector<char> in_window, fronting;
        window_polygons(window, *now, refs, in_window, fronting);
        check_tiling(t, sketch, refs, polygons, boxes, grid, tile_side, proofs, &window, in_window, fronting);
        if (tiling.ok()) return;
        tiling = {};
        check_tiling(t, sketch, refs, polygons, boxes, grid, tile_side, proofs);
      },
      [&] {
        Checker r(road_checks);
        check_roads(r, sketch, roads, water, proofs);
        validate_clutter(dir, layers, clutter, last ? &lines.at("clutter") : nullptr);
      });
  for (const Validation* part : {&tiling, &road_checks, &clutter}) {
    for (const std::string& p : part->problems) c.problem(p);
    v.features.insert(part->features.begin(), part->features.end());
    v.widest_sliver = std::max(v.widest_sliver, part->widest_sliver);
  }
  if (last && v.ok()) now->lines = std::move(lines), *last = now;
  return v;
}

}  // namespace

Validation validate_output(const fs::path& dir) { return validate(dir, nullptr, 0); }

Validation validate_output(const fs::path& dir, double tile_side) { return validate(dir, nullptr, tile_side); }

Validation validate_output(const fs::path& dir, double tile_side, MapProofs proofs) {
  return validate(dir, nullptr, tile_side, proofs);
}

Validation validate_output(const fs::path& dir, std::shared_ptr<ValidatedPolygons>& last, double tile_side) {
  return validate(dir, &last, tile_side);
}

}  // namespace exacity
