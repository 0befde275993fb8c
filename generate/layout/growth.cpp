#include "generate/layout/growth.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <tbb/parallel_for.h>

#include "generate/cancel.h"
#include "generate/city/random.h"
#include "geom/grid.h"
#include "geom/measure.h"

namespace exacity {
namespace {

constexpr int kMaxLevels = 64;  // a long corridor is cut a block or so per level
constexpr int kConnectorTries = 8;
constexpr int kMaxStalls = 4;        // regrowths of a cell that the roads failed to divide
constexpr int kSeedCandidates = 48;  // points tried for a cell's seed
constexpr int kDeepeningSteps = 8;   // steps moving a start away from the boundary

// A cell waiting to be grown.
struct Work {
  geom::Cell cell;
  std::uint64_t id;    // stable: the region's stream, then each split's part index
  double orientation;  // degrees
  ZoneType type;       // the parent's, until the seed's face tells
  int stalls = 0;      // times in a row its roads failed to divide it
  bool top = true;     // a whole region, with no roads of its own yet to reach
};

// How far points inside a cell lie from its boundary (its drawn edges and the roads grown
// around it before), in doubles.
class Depth {
 public:
  explicit Depth(const geom::Cell& cell) : rings_(cell.kinded_rings()) {}
  double operator()(geom::Vec2 p) const { return geom::distance(p, nearest(p)); }
  geom::Vec2 nearest(geom::Vec2 p) const {
    geom::Vec2 best = p;
    double d = INFINITY;
    for (const auto& r : rings_)
      for (std::size_t i = 0, n = r.points.size(); i < n; ++i) {
        const geom::Vec2 q = geom::nearest_on_segment(p, r.points[i], r.points[(i + 1) % n]);
        if (const double e = geom::distance(p, q); e < d) d = e, best = q;
      }
    return best;
  }

 private:
  std::vector<geom::KindedRing> rings_;
};

// Where a cell's roads start: the deepest of some points inside it (the farthest from its
// boundary), so a seed sits in the middle of a corridor or an arm rather than at the
// centroid, which a U, a ring or a spiral leaves outside or against an edge.
std::optional<geom::Vec2> seed_point(const geom::Cell& cell, const Depth& depth, Random& rng) {
  std::optional<geom::Vec2> best = cell.point_inside_near(cell.centroid());
  double best_depth = best ? depth(*best) : -1;
  const geom::Box b = cell.bounds();
  for (int i = 0; i < kSeedCandidates; ++i) {
    geom::Vec2 p = geom::snap(geom::Vec2{rng.uniform(b.min_x, b.max_x), rng.uniform(b.min_y, b.max_y)});
    double d = depth(p);
    if (d > best_depth && cell.contains(p)) best = p, best_depth = d;  // the exact test only when it would win
  }
  return best;
}

// Where a cell's roads start, and, for a start moved off an edge it lay too near, the way
// off that edge.
struct Start {
  geom::Vec2 at;
  std::optional<geom::Vec2> off_edge;  // a unit vector
};

// A start for a cell's roads at least `least` from its boundary: p, or p stepped away from
// the boundary point nearest it, a few times (a corner pushes it on from the next edge).
// Every road from a start that deep is at least that long, so none is a stub; a start just
// inside an edge (Cell::point_inside_near's answer when the point wanted lies outside) grew
// roads of centimetres out to it. nullopt where the steps leave the cell or find no such
// point: a cell narrower than twice `least` there.
std::optional<Start> deep_start(const geom::Cell& cell, const Depth& depth, geom::Vec2 p, double least) {
  Start start{p, std::nullopt};
  for (int step = 0; step < kDeepeningSteps; ++step) {
    const double d = depth(start.at);
    if (d >= least) return start;
    if (d == 0) return std::nullopt;
    const geom::Vec2 away = (start.at - depth.nearest(start.at)) * (1 / d);
    if (!start.off_edge) start.off_edge = away;
    start.at = geom::snap(start.at + away * (least - d + geom::kGridStep));
    if (!cell.contains(start.at)) return std::nullopt;
  }
  return depth(start.at) >= least ? std::optional<Start>(start) : std::nullopt;
}

// What growing one cell gave.
struct Grown {
  std::optional<geom::Vec2> seed;  // where its roads start
  ZoneType type = ZoneType::Residential;
  std::vector<geom::Path> roads;
  std::vector<Work> parts;  // to grow at the next level
  std::vector<int> joined;  // the sketch roads its roads run on to
  bool without_access = false;
};

// The grid point `distance` from p at `degrees`.
geom::Vec2 ahead(geom::Vec2 p, double degrees, double distance) {
  double t = degrees * M_PI / 180;
  return geom::snap(geom::Vec2{p.x + distance * std::cos(t), p.y + distance * std::sin(t)});
}


// The roads grown in one cell from its seed, and the sketch roads they run on to.
struct CellRoads {
  geom::Vec2 seed;
  std::vector<geom::Path> roads;
  std::vector<int> joined;
  bool open_end = false;  // a road stopped at a sketch road's surface and reached no centre line
};

// The centre lines a road stopped at a sketch road's surface runs on to: the lines of the
// road the surface is tagged with, else every sketch road's. A junction's surface is tagged
// with the first road that meets there (docs/design.md, Ids), and a mitred junction of two
// streets of unlike widths meeting almost straight on runs far down the narrower one, out of
// reach of the tagged road's line.
struct RunOnLines {
  explicit RunOnLines(const SketchLines& roads) : roads(roads) {
    for (const SketchRoad& r : roads) {
      every_line.insert(every_line.end(), r.lines.begin(), r.lines.end());
      widest = std::max(widest, r.width);
    }
  }
  const SketchLines& roads;
  std::vector<geom::Path> every_line;
  double widest = 0;
};

// Grows `branches` roads from the seed. Returns whether one reached a road (of the region,
// or of the sketch); always true when `free`, for a cell with no road to reach.
// `across_only`: only the branches within 45 degrees of `orientation` or its opposite.
// `off_edge`: for a connector's start moved off an edge, no branch but the first (back to its
// road edge) running within 45 degrees of along that edge: from where the start lay those
// were stubs, and from a block's width off the edge they would cut a sliver along it.
bool grow_branches(geom::Growth& growth, geom::Vec2 seed, const GrowthSettings& p, int level, bool free, double orientation,
                   bool across_only, std::optional<geom::Vec2> off_edge, double reach, const RunOnLines& run_on, Random& rng,
                   CellRoads& out) {
  const double segment_deviation = std::max(p.segment_deviation - 2.0 * level, 0.0);
  const int max_steps = static_cast<int>(reach / (p.segment_length * std::cos(p.origin_deviation * M_PI / 180))) + 2;
  bool reached_road = free;
  // Grows one road heading `alpha`; whether it has any length.
  auto grow = [&](double alpha) {
    growth.begin(seed);
    geom::Growth::Met met;
    if (segment_deviation == 0) {
      // Straight: one segment on the line through the seed and a far grid point, so every
      // piece of the road lies exactly on one line.
      met = growth.extend(ahead(seed, alpha, reach));
    } else {
      double theta = alpha;
      geom::Vec2 at = seed;
      int steps = 0;
      do {
        double lo = std::max(theta - segment_deviation, alpha - p.origin_deviation);
        double hi = std::min(theta + segment_deviation, alpha + p.origin_deviation);
        theta = rng.uniform(lo, hi);
        at = ahead(at, theta, p.segment_length);
        met = growth.extend(at);
        if (met.what == geom::Growth::Met::Nothing && ++steps > max_steps) met = growth.extend(ahead(at, theta, reach));
      } while (met.what == geom::Growth::Met::Nothing);
    }
    geom::Path road = growth.end();
    if (road.empty()) return false;
    const int sketch_road = met.what == geom::Growth::Met::Edge ? GrowthEdge::sketch_road_of(met.kind) : -1;
    bool joined = false;
    if (sketch_road >= 0) {
      // A road whose edge is the centre line itself (a grammar's road around a piece it
      // grows) is there already; extended, it would cross to the next line ahead.
      const SketchRoad& target = run_on.roads[sketch_road];
      const std::size_t points = road.size();
      joined = geom::ends_on(road, target.lines);
      if (!joined) road = geom::extend_to(road, target.lines, 4 * target.width);
      if (!joined && road.size() == points) road = geom::extend_to(road, run_on.every_line, 4 * run_on.widest);
      joined |= road.size() > points;
      if (joined)
        out.joined.push_back(sketch_road);
      else
        out.open_end = true;
    }
    reached_road |= met.edge_of_kind(GrowthEdge::kGrownRoad) || joined;
    out.roads.push_back(std::move(road));
    return true;
  };
  std::vector<double> grown;
  for (int i = 0; i < p.branches; ++i) {
    const double off_axis = std::fmod(360.0 * i / p.branches, 180.0);
    if (across_only && off_axis > 45 && off_axis < 135) continue;
    const double alpha = orientation + 360.0 * i / p.branches;
    const geom::Vec2 heading{std::cos(alpha * M_PI / 180), std::sin(alpha * M_PI / 180)};
    if (off_edge && i > 0 && std::abs(geom::dot(heading, *off_edge)) < M_SQRT1_2) continue;
    if (grow(alpha)) grown.push_back(alpha);
  }
  // A seed left with one road would be a dead end: that road runs on through it instead.
  if (grown.size() == 1) grow(grown[0] + 180);
  return reached_road;
}

// A cell much longer than wide, and narrow for its zone: roads along it would only cut it
// into slivers. Its long axis from the second moments of its outer ring (a choice, made
// in doubles); nullopt for a cell that is no such strip.
std::optional<double> strip_axis(const geom::Cell& cell, const GrowthSettings& p) {
  const geom::Ring ring = cell.to_plain().outer;
  if (ring.size() < 3) return std::nullopt;
  const geom::Vec2 o = ring[0];
  double a = 0, cx = 0, cy = 0, xx = 0, yy = 0, xy = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    geom::Vec2 u{ring[i].x - o.x, ring[i].y - o.y}, v{ring[(i + 1) % ring.size()].x - o.x, ring[(i + 1) % ring.size()].y - o.y};
    double c = u.x * v.y - v.x * u.y;
    a += c / 2, cx += (u.x + v.x) * c / 6, cy += (u.y + v.y) * c / 6;
    xx += (u.x * u.x + u.x * v.x + v.x * v.x) * c / 12, yy += (u.y * u.y + u.y * v.y + v.y * v.y) * c / 12;
    xy += (u.x * v.y + 2 * u.x * u.y + 2 * v.x * v.y + v.x * u.y) * c / 24;
  }
  if (a <= 0) return std::nullopt;
  cx /= a, cy /= a;
  xx = xx / a - cx * cx, yy = yy / a - cy * cy, xy = xy / a - cx * cy;
  const double mean = (xx + yy) / 2, spread = std::hypot((xx - yy) / 2, xy);
  const double length = std::sqrt(12 * (mean + spread)), width = std::sqrt(12 * std::max(mean - spread, 0.0));
  if (width > 1.5 * std::sqrt(p.block_area) || length < 2 * width) return std::nullopt;
  return std::atan2(mean + spread - xx, xy) * 180 / M_PI;  // the eigenvector of the larger moment
}


// The roads of one cell, grown from its seed. They must reach one of edges_to_reach, and
// none may stop at a sketch road's surface short of a centre line (it would end in the open);
// when they fail (a concave cell can hide those edges from the seed), they are grown
// again from inside one of those edges, the first branch heading straight back to it.
// Every start lies at least `shortest_road` inside the cell (deep_start). Empty when that
// fails too.
CellRoads grow_cell(const geom::Cell& cell, const Depth& depth, geom::Vec2 seed, const GrowthSettings& p, double shortest_road,
                    int level, bool top, double orientation, int stalls, const RunOnLines& run_on, Random& rng) {
  const geom::Box b = cell.bounds();
  const double reach = 2 * std::hypot(b.width(), b.height()) + 1;  // past the cell from anywhere in it
  auto edges = edges_to_reach(cell, top);
  const bool free = edges.empty();
  // A strip is cut across, never along.
  const std::optional<double> axis = strip_axis(cell, p);
  if (const std::optional<Start> start = deep_start(cell, depth, seed, shortest_road)) {
    geom::Growth growth(cell, p.segment_length);
    CellRoads grown{start->at, {}, {}};
    if (grow_branches(growth, start->at, p, level, free, axis ? *axis + 90 : orientation, axis.has_value(), std::nullopt, reach,
                      run_on, rng, grown) &&
        !grown.open_end)
      return grown;
  }
  auto mid = [](const std::pair<geom::Vec2, geom::Vec2>& e) {
    return geom::Vec2{(e.first.x + e.second.x) / 2, (e.first.y + e.second.y) / 2};
  };
  auto length = [](const std::pair<geom::Vec2, geom::Vec2>& e) {
    return std::hypot(e.second.x - e.first.x, e.second.y - e.first.y);
  };
  std::stable_sort(edges.begin(), edges.end(), [&](const auto& x, const auto& y) { return length(x) > length(y); });
  for (std::size_t k = 0; k < std::min<std::size_t>(edges.size(), kConnectorTries); ++k) {
    const auto& [a, c] = edges[k];
    double len = length(edges[k]);
    if (len == 0) continue;
    const geom::Vec2 m = mid(edges[k]);
    // Half a block deep: the side branches then run one block behind this road. In a
    // corridor narrower than a block (its width about 2 area / perimeter), a block's length
    // on: the road back runs down the corridor and the branches cut it a block along. A
    // retry reaches further in.
    double d = std::sqrt(p.block_area) / 2;
    if (const double width = 2 * cell.area() / geom::perimeter(cell.to_plain()); width < std::sqrt(p.block_area))
      d = std::max(d, p.block_area / width);
    d *= 1 + stalls;
    // Into the cell square to the edge (the cell is on its left); into a strip along it,
    // where that lands inside, whichever way its road edge lies.
    geom::Vec2 inward = geom::left_normal(a, c);
    if (axis) {
      geom::Vec2 along{std::cos(*axis * M_PI / 180), std::sin(*axis * M_PI / 180)};
      if (geom::dot(along, inward) < 0) along = {-along.x, -along.y};
      for (geom::Vec2 way : {along, geom::Vec2{-along.x, -along.y}})
        if (cell.contains(geom::snap(geom::Vec2{m.x + way.x * d, m.y + way.y * d}))) {
          inward = way;
          break;
        }
    }
    const std::optional<geom::Vec2> wanted = cell.point_inside_near({m.x + inward.x * d, m.y + inward.y * d});
    const std::optional<Start> start = wanted ? deep_start(cell, depth, *wanted, shortest_road) : std::nullopt;
    if (!start) continue;
    geom::Growth growth(cell, p.segment_length);
    CellRoads grown{start->at, {}, {}};
    double back = std::atan2(m.y - start->at.y, m.x - start->at.x) * 180 / M_PI;
    if (grow_branches(growth, start->at, p, level, free, back, false, start->off_edge, reach, run_on, rng, grown) &&
        !grown.open_end)
      return grown;
  }
  return {seed, {}, {}};
}

// A cell's seed, and the zone type it grows as: the type at its seed (a cell keeps its
// parent's type where the seed lies on none).
Grown seed(const Work& w, const Depth& depth, const ZoneAt& zone_at) {
  Grown g;
  Random seed_rng(mix(w.id, 3 + w.stalls));
  g.seed = seed_point(w.cell, depth, seed_rng);
  g.type = w.type;
  if (g.seed)
    if (std::optional<ZoneType> t = zone_at(*g.seed)) g.type = *t;
  return g;
}

// Grows one cell's roads and splits it by them; the parts above the block area are
// grown again at the next level. Roads that fail to divide the cell, or only shave a
// sliver off it, are dropped and the cell grown again from another seed, a few times at
// most: slivers make poor blocks. Cutting off a tenth of a block is progress, so a long
// corridor is grown on however little of it each cut takes.
void grow_one(const Work& w, const Depth& depth, Grown& g, const GrowthSettings& p, double shortest_road, int level,
              const RunOnLines& run_on) {
  if (!g.seed) return;
  if (w.cell.area() <= p.block_area) return;  // small enough to be one block
  Random rng(mix(w.id, 1 + 16 * w.stalls));
  auto again = [&] {
    g.roads.clear();
    g.joined.clear();
    if (w.stalls < kMaxStalls) {
      Work retry = w;
      ++retry.stalls;
      g.parts.push_back(std::move(retry));
    } else {
      g.without_access = !w.top;
    }
  };
  CellRoads grown = grow_cell(w.cell, depth, *g.seed, p, shortest_road, level, w.top, w.orientation, w.stalls, run_on, rng);
  g.seed = grown.seed;
  g.roads = std::move(grown.roads);
  g.joined = std::move(grown.joined);
  if (g.roads.empty()) return again();
  std::vector<geom::Cell> parts = geom::split_cell(w.cell, g.roads, GrowthEdge::kGrownRoad);
  double largest = 0;
  for (const geom::Cell& part : parts) largest = std::max(largest, part.area());
  // Cutting through a ring (a zone around a hole) leaves one part, but one the next cut divides.
  const bool opened = parts.size() == 1 && parts[0].kinded_rings().size() < w.cell.kinded_rings().size();
  const bool shaved =
      !opened && (parts.size() < 2 || w.cell.area() - largest < std::min(0.05 * w.cell.area(), 0.1 * p.block_area));
  if (shaved && w.stalls < kMaxStalls) return again();
  for (std::size_t k = 0; k < parts.size(); ++k) {
    if (parts[k].area() <= p.block_area) continue;       // small enough to be one block
    if (shaved && parts[k].area() == largest) continue;  // out of tries: left as it is
    std::uint64_t id = mix(w.id, k + 2);
    Random part_rng(id);
    double jitter = p.jitter / (level + 1);
    g.parts.push_back({std::move(parts[k]), id, w.orientation + part_rng.uniform(-jitter, jitter), g.type, 0, false});
  }
}

// The level's roads onto the plan, in cell order; returns the next level's work.
std::vector<Work> collect(std::vector<Grown>& grown, const std::vector<Work>& work, int level, const CitySettings& sketch,
                          RoadPlan& plan) {
  std::vector<Work> next;
  for (std::size_t i = 0; i < grown.size(); ++i) {
    Grown& g = grown[i];
    plan.cells_without_access += g.without_access;
    if (!g.joined.empty()) plan.piece_reaches_sketch[0] = 1;
    if (!g.roads.empty()) plan.junctions.push_back({*g.seed, static_cast<int>(plan.roads.size())});
    const RoadSettings& p = sketch.zone_settings.at(g.type).roads;
    for (geom::Path& road : g.roads)
      plan.roads.push_back({std::move(road), road_width(p, level), work[i].top ? RoadClass::Main : RoadClass::Local, level, 0});
    for (Work& w : g.parts) next.push_back(std::move(w));
  }
  return next;
}

class GrowthLayout : public RoadLayout {
 public:
  GrowthLayout(const CitySettings& sketch, const SketchLines& sketch_lines, ZoneAt zone_at)
      : sketch_(sketch), run_on_(sketch_lines), zone_at_(std::move(zone_at)) {}

  // The region's roads are one piece, grown a level at a time; each level's cells grow in
  // parallel.
  RoadPlan plan(const Region& region) const override {
    RoadPlan plan;
    plan.piece_reaches_sketch = {0};
    Random rng(region.stream);
    std::vector<Work> work{{region.cell, region.stream, rng.uniform(0, 360), ZoneType::Residential}};
    const CancelCheck cancel;
    for (int level = 0; !work.empty() && level < kMaxLevels; ++level) {
      plan.levels = level + 1;
      std::vector<Grown> grown(work.size());
      tbb::parallel_for(std::size_t(0), work.size(), [&](std::size_t i) {
        cancel.check();
        const Depth depth(work[i].cell);
        grown[i] = seed(work[i], depth, zone_at_);
        const ZoneSettings& zone = sketch_.zone_settings.at(grown[i].type);
        grow_one(work[i], depth, grown[i], zone.roads.growth, zone.blocks.min_block_width, level, run_on_);
      });
      work = collect(grown, work, level, sketch_, plan);
    }
    return plan;
  }

 private:
  const CitySettings& sketch_;
  RunOnLines run_on_;
  ZoneAt zone_at_;
};

}  // namespace

std::unique_ptr<RoadLayout> make_growth_layout(const CitySettings& sketch, const SketchLines& sketch_lines, ZoneAt zone_at) {
  return std::make_unique<GrowthLayout>(sketch, sketch_lines, std::move(zone_at));
}

}  // namespace exacity
