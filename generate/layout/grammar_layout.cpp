// The split grammar layout: the region's triangles and near-square quads grow by a split grammar;
// each road leaf becomes one road down its middle, and each land leaf a use.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "generate/city/random.h"
#include "generate/layout/growth.h"
#include "generate/layout/road_layout.h"
#include "generate/layout/settle.h"
#include "geom/box_index.h"
#include "geom/grid.h"
#include "geom/measure.h"

namespace exacity {
namespace {

// The split grammar (docs/design.md, Road layouts).
struct GrammarSettings {
  std::shared_ptr<const Grammar> file;  // read with the sketch
  int depth = 8;                        // rules applied at most, from a root down
  bool grow_large_pieces = true;        // land over 4 x block_area is grown by recursive growth
};

geom::Vec2 mid(geom::Vec2 a, geom::Vec2 b) { return {(a.x + b.x) / 2, (a.y + b.y) / 2}; }

// Whether segment a-b lies along p-q (both ends within a hair of it).
bool lies_along(geom::Vec2 a, geom::Vec2 b, geom::Vec2 p, geom::Vec2 q) {
  const double tolerance = 1e-7 * (geom::distance(p, q) + std::abs(p.x) + std::abs(p.y)) + 1e-9;
  return geom::distance_to_segment(a, p, q) <= tolerance && geom::distance_to_segment(b, p, q) <= tolerance;
}

// A road leaf's corners from the start of its long side: a road runs along its longer
// axis, whichever edge the grammar wrote first (grammars are meant to write the long one first; a road
// read across would be a stub of its own width, which nothing joins).
std::vector<geom::Vec2> long_side_first(std::vector<geom::Vec2> c) {
  if (c.size() == 4) {
    const double along = geom::distance(mid(c[3], c[0]), mid(c[1], c[2]));
    const double across = geom::distance(mid(c[0], c[1]), mid(c[2], c[3]));
    if (across > along) std::rotate(c.begin(), c.begin() + 1, c.end());
  } else {
    std::size_t longest = 0;
    for (std::size_t i = 1; i < c.size(); ++i)
      if (geom::distance(c[i], c[(i + 1) % c.size()]) > geom::distance(c[longest], c[(longest + 1) % c.size()])) longest = i;
    std::rotate(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(longest), c.end());
  }
  return c;
}

// The leaves' uses, to find the one that holds a point without a pass over all of them
// (a deep grammar has tens of thousands, and every piece and growth seed asks).
class UsesIndex {
 public:
  explicit UsesIndex(const std::vector<PlannedUse>& uses) : uses_(uses), boxes_(mean_size(uses)) {
    for (std::size_t k = 0; k < uses.size(); ++k) {
      geom::Box box = geom::Box::none();
      for (geom::Vec2 v : uses[k].ring) box.add(v);
      boxes_.add(static_cast<int>(k), box);
    }
  }
  // The use of the first leaf that holds p, if any (asking the index a metre around p: it
  // filters in doubles, and the winding number decides as it did over all leaves).
  std::optional<Terminal> at(geom::Vec2 p) const {
    for (int k : boxes_.meeting({p.x - 1, p.y - 1, p.x + 1, p.y + 1}))
      if (geom::winding_number(uses_[k].ring, p) != 0) return uses_[k].use;
    return std::nullopt;
  }

 private:
  static double mean_size(const std::vector<PlannedUse>& uses) {
    double sum = 0;
    for (const PlannedUse& u : uses) {
      geom::Box box = geom::Box::none();
      for (geom::Vec2 v : u.ring) box.add(v);
      if (!box.holds_nothing()) sum += std::max(box.width(), box.height());
    }
    return uses.empty() ? 0 : sum / static_cast<double>(uses.size());
  }
  const std::vector<PlannedUse>& uses_;
  geom::BoxIndex boxes_;
};

// Whether a use other than land (a park) lies in the piece: growth's roads would cross it.
bool holds_other_use(const geom::Cell& piece, const std::vector<PlannedUse>& uses) {
  const geom::Polygon plain = piece.to_plain();
  for (const PlannedUse& u : uses) {
    if (u.use.kind == Terminal::Land || u.ring.empty()) continue;
    geom::Vec2 c{0, 0};
    for (geom::Vec2 v : u.ring) c = c + v;
    c = c * (1.0 / u.ring.size());
    if (geom::winding_number(plain.outer, c) != 0) return true;
  }
  return false;
}

// The grown roads into the plan, in the piece of the grammar's roads they run on to (a
// piece of their own when they reach none).
void add_grown(RoadPlan& plan, RoadPlan grown, const std::vector<std::vector<geom::Path>>& piece_lines) {
  int piece = -1;
  for (std::size_t k = 0; k < piece_lines.size() && piece < 0; ++k)
    for (const LaidRoad& r : grown.roads)
      if (geom::ends_on(r.path, piece_lines[k])) {
        piece = static_cast<int>(k);
        break;
      }
  if (piece < 0) piece = static_cast<int>(plan.piece_reaches_sketch.size()), plan.piece_reaches_sketch.push_back(grown.piece_reaches_sketch[0]);
  const int first = static_cast<int>(plan.roads.size());
  for (LaidRoad& r : grown.roads) r.piece = piece, plan.roads.push_back(std::move(r));
  for (const Junction& j : grown.junctions) plan.junctions.push_back({j.at, first + j.first_road});
  plan.levels = std::max(plan.levels, grown.levels);
  plan.cells_without_access += grown.cells_without_access;
}

// Land between the grammar's roads over 4 times the zone's block_area (as the statistics
// measure blocks), where a plain split grammar would fill one piece all the way in: the region is cut
// along the roads' centre lines and each such piece grown by recursive road growth as a region
// of its own, its roads running on to the grammar's (an Exacity extension;
// "grow_large_pieces": false keeps the pieces whole). A piece holding a park is kept whole:
// growth's roads would cross it.
void grow_large_pieces(RoadPlan& plan, const Region& region, const CitySettings& city, ZoneType zone, const SketchLines& sketch_roads) {
  SketchLines lines = sketch_roads;  // the grammar's roads are one more sketch road to growth
  lines.push_back({});
  std::vector<std::vector<geom::Path>> piece_lines(plan.piece_reaches_sketch.size());
  for (const LaidRoad& r : plan.roads) {
    lines.back().lines.push_back(r.path);
    lines.back().width = std::max(lines.back().width, r.width);
    piece_lines[r.piece].push_back(r.path);
  }
  const int grammar_road = GrowthEdge::sketch_road(static_cast<int>(lines.size()) - 1);
  const std::vector<geom::Cell> pieces =
      lines.back().lines.empty() ? std::vector<geom::Cell>{region.cell} : geom::split_cell(region.cell, lines.back().lines, grammar_road);
  const UsesIndex uses(plan.uses);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const std::optional<geom::Vec2> inside = pieces[k].point_inside_near(pieces[k].centroid());
    const std::optional<Terminal> use = inside ? uses.at(*inside) : std::nullopt;
    if (!use || use->kind != Terminal::Land) continue;
    if (pieces[k].area() <= 4 * city.zone_settings.at(zone).roads.growth.block_area) continue;
    if (holds_other_use(pieces[k], plan.uses)) continue;
    // Each cell grows as the land use at its seed, as a growth region follows its zones.
    const auto growth = make_growth_layout(city, lines, [&uses, piece_type = use->type](geom::Vec2 p) {
      const std::optional<Terminal> u = uses.at(p);
      return std::optional<ZoneType>(u && u->kind == Terminal::Land ? u->type : piece_type);
    });
    add_grown(plan, growth->plan({pieces[k], mix(region.stream, 0x9e0000 + k)}), piece_lines);
  }
}

class GrammarLayout : public RoadLayout {
 public:
  GrammarLayout(const GrammarSettings& grammar, const LayoutSite& site)
      : city_(site.city), roads_(site.roads()), grammar_(grammar),
        min_block_area_(site.city.zone_settings.at(site.type).blocks.min_block_area), type_(site.type),
        sketch_roads_(site.sketch_roads) {}

  RoadPlan plan(const Region& region) const override {
    Random random(region.stream);
    const std::vector<std::pair<geom::Vec2, geom::Vec2>> along_sketch_roads = edges_to_reach(region.cell, true);
    std::vector<std::vector<geom::Vec2>> roots;
    for (const geom::Polygon& p : region.cell.rounded())
      for (auto& r : layout_roots(p)) roots.push_back(std::move(r));
    // Root edges two roots share: a road along one is built once, centred on it (seed
    // 002's tree puts one on each side).
    using geom::segment_key;
    std::map<geom::SegmentKey, int> edge_roots;
    for (const auto& r : roots)
      for (std::size_t i = 0; i < r.size(); ++i) ++edge_roots[segment_key(r[i], r[(i + 1) % r.size()])];
    std::set<geom::SegmentKey> built;

    LinePlan plan;
    // Road pieces meet only roughly (each is mapped from its own parent): join within a width.
    plan.join = *std::max_element(roads_.road_widths.begin(), roads_.road_widths.end());
    for (GrammarLeaf& leaf : grow_layout(*grammar_.file, roots, grammar_.depth, min_block_area_, random.next())) {
      Terminal t;
      if (!parse_terminal(leaf.name, t)) t.type = type_;  // a symbol left at the depth bound
      if (t.kind != Terminal::Road) {
        plan.uses.push_back({std::move(leaf.corners), t});
        continue;
      }
      const std::vector<geom::Vec2> c = long_side_first(leaf.corners);
      const geom::Vec2 a = c[0], b = c[1];
      if (geom::distance(a, b) == 0) continue;
      bool along_sketch = false;
      for (auto [p, q] : along_sketch_roads) along_sketch |= lies_along(a, b, p, q);
      if (along_sketch) continue;  // the sketch's road runs there
      // The grammar places a road; its width is the zone's, by level, as a grown road's.
      PlannedRoad road;
      road.road_class = leaf.depth <= 1 ? RoadClass::Main : RoadClass::Local;
      road.width = road_width(roads_, leaf.depth - 1);
      bool on_shared_edge = false;
      const auto& root = roots[leaf.root];
      for (std::size_t i = 0; i < root.size() && !on_shared_edge; ++i) {
        const geom::Vec2 p = root[i], q = root[(i + 1) % root.size()];
        if (edge_roots[segment_key(p, q)] < 2 || !lies_along(a, b, p, q)) continue;
        on_shared_edge = true;
        if (!built.insert(segment_key(p, q)).second) break;
        road.line = {geom::snap(geom::nearest_on_segment(a, p, q)), geom::snap(geom::nearest_on_segment(b, p, q))};
      }
      if (on_shared_edge && road.line.empty()) continue;  // built from the other side
      if (!on_shared_edge) {
        road.line = c.size() == 4 ? geom::Polyline{geom::snap(mid(c[3], a)), geom::snap(mid(b, c[2]))}
                                  : geom::Polyline{geom::snap(mid(c[2], a)), geom::snap(mid(b, c[2]))};
      }
      if (road.line[0] == road.line[1]) continue;
      plan.roads.push_back(std::move(road));
    }
    RoadPlan settled = settle(std::move(plan), region.cell, sketch_roads_);
    if (grammar_.grow_large_pieces) grow_large_pieces(settled, region, city_, type_, sketch_roads_);
    return settled;
  }

 private:
  const CitySettings& city_;
  RoadSettings roads_;
  GrammarSettings grammar_;
  double min_block_area_;  // the grammar's land leaves stop above it
  ZoneType type_;
  const SketchLines& sketch_roads_;
};

class GrammarChoice : public RoadLayoutChoice {
 public:
  explicit GrammarChoice(GrammarSettings settings) : RoadLayoutChoice("grammar"), settings_(std::move(settings)) {}
  std::unique_ptr<RoadLayout> make(const LayoutSite& site) const override {
    return std::make_unique<GrammarLayout>(settings_, site);
  }

 private:
  GrammarSettings settings_;
};

}  // namespace

std::shared_ptr<const RoadLayoutChoice> read_grammar_layout(const RoadLayoutReading& reading) {
  const SettingsReader& s = reading.settings;
  GrammarSettings g;
  s.whole_number("grammar_depth", g.depth, 1, 32, "rules");
  if (s.has("grammar")) {
    if (!s.at("grammar").is_string())
      s.fail("grammar", "expected the path of a grammar file (a string), relative to the sketch");
    const std::filesystem::path file = std::filesystem::path(s.file()).parent_path() / s.at("grammar").get<std::string>();
    g.file = std::make_shared<Grammar>(reading.read_grammars ? load_grammar(file) : Grammar{file, {}});
  }
  if (reading.chosen && !g.file) s.fail("layout", "\"grammar\" needs \"grammar\": the path of a grammar file");
  s.boolean("grow_large_pieces", g.grow_large_pieces);
  return std::make_shared<GrammarChoice>(std::move(g));
}

}  // namespace exacity
