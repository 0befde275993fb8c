// Seed 002's layout: the region's triangles and near-square quads grow by a split grammar;
// each road leaf becomes one road down its middle, and each land leaf a use.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "generate/city/random.h"
#include "generate/layout/road_layout.h"
#include "generate/layout/settle.h"
#include "geom/grid.h"
#include "geom/measure.h"

namespace exacity {
namespace {

geom::Vec2 mid(geom::Vec2 a, geom::Vec2 b) { return {(a.x + b.x) / 2, (a.y + b.y) / 2}; }

// Whether segment a-b lies along p-q (both ends within a hair of it).
bool lies_along(geom::Vec2 a, geom::Vec2 b, geom::Vec2 p, geom::Vec2 q) {
  const double tolerance = 1e-7 * (geom::distance(p, q) + std::abs(p.x) + std::abs(p.y)) + 1e-9;
  return geom::distance_to_segment(a, p, q) <= tolerance && geom::distance_to_segment(b, p, q) <= tolerance;
}

// A road leaf's corners from the start of its long side: a road runs along its longer
// axis, whichever edge the grammar wrote first (seed 002 writes the long one first; a road
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

class GrammarLayout : public RoadLayout {
 public:
  GrammarLayout(const RoadSettings& roads, double min_block_area, ZoneType type, const SketchLines& sketch)
      : roads_(roads), min_block_area_(min_block_area), type_(type), sketch_(sketch) {}

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
    for (GrammarLeaf& leaf : grow_layout(*roads_.grammar.file, roots, roads_.grammar.depth, min_block_area_, random.next())) {
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
    return settle(std::move(plan), region.cell, sketch_);
  }

 private:
  RoadSettings roads_;
  double min_block_area_;  // the grammar's land leaves stop above it
  ZoneType type_;
  const SketchLines& sketch_;
};

}  // namespace

std::unique_ptr<RoadLayout> make_grammar_layout(const ZoneSettings& settings, ZoneType type, const SketchLines& sketch) {
  return std::make_unique<GrammarLayout>(settings.roads, settings.blocks.min_block_area, type, sketch);
}

}  // namespace exacity
