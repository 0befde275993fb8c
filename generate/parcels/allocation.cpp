// Lots measured from the street (docs/design.md, Lots): along every run of road edges of a
// block, lots side by side, corner lots at its corners, the block's middle left open.
#include "generate/parcels/allocation.h"

#include <algorithm>
#include <cmath>

#include "geom/grid.h"
#include "geom/measure.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::Vec2;

using geom::lerp;

using geom::cross;
using geom::dot;
using geom::left_normal;
using geom::unit;

// How deep lots may reach from p along the unit vector `dir`: half the way the ray runs
// inside the block before it meets a boundary edge (past a millimetre, so the edge it
// starts on does not count) when that edge is a road's, whose lots take the other half;
// the whole way when no lots come from there (water, a park, another zone). A choice of
// lot depth, made in doubles; the map decides the lots' topology exactly.
double lot_room(const std::vector<geom::KindedRing>& rings, Vec2 p, Vec2 dir, double limit) {
  double best = limit;
  bool road = true;
  for (const auto& r : rings)
    for (std::size_t i = 0, n = r.points.size(); i < n; ++i) {
      Vec2 a = r.points[i], e = r.points[(i + 1) % n] - a;
      double den = cross(dir, e);
      if (den == 0) continue;
      double t = cross(a - p, e) / den, u = cross(a - p, dir) / den;
      if (t > 1e-3 && u >= 0 && u <= 1 && t < best) best = t, road = BlockEdge::is_road(r.kinds[i]);
    }
  return road ? best / 2 : best;
}

// Where a run of street edges is broken: the kind changes between road and not, or the
// boundary turns by more than this.
constexpr double kRunTurn = 35 * M_PI / 180;
constexpr Range kOwnedCorner{60 * M_PI / 180, 150 * M_PI / 180};  // turns at which a corner lot takes the corner
constexpr double kTinyEdge = 0.1;  // m: a block edge shorter than this makes no corner
constexpr double kFrontOverhang = 0.5;  // m: lots reach this far past the block's edge, so they meet it exactly

// One lot boundary across the street side: from `at` on the block's edge, `depth` along `dir`.
struct Cut {
  Vec2 at, dir;
  double depth = 0;
};

// How a run of lots ends: the cut there, how much of the run is left to the lot across
// the corner (at its start), and how far past its end its last lot reaches to take the
// corner (at its end).
struct RunEnd {
  Vec2 dir;
  double skip = 0, extend = 0;
};

// Where the lots along `length` of street start and end, as shares of it from 0 to 1: each
// lot's frontage drawn from `steps` in turn (no wider than `widest`, and a metre at least,
// as the setting's least, so that a sliver of a block makes no more lots than that)
// until they pass its end, the last one kept when at least half of it fits (else its part
// shared out), and all scaled alike to fill it.
std::vector<double> drawn_cuts(double length, const std::vector<double>& steps, double widest, Random& rng) {
  std::vector<double> ends;
  double sum = 0;
  while (sum < length) ends.push_back(sum += std::max(std::min(draw_from_steps(steps, rng), widest), 1.0));
  if (ends.size() > 1 && length - ends[ends.size() - 2] < (ends.back() - ends[ends.size() - 2]) / 2) ends.pop_back();
  std::vector<double> cuts{0};
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) cuts.push_back(ends[k] / ends.back());
  cuts.push_back(1);
  return cuts;
}

// The lots along one run of street edges: `points` from one end of the run to the other
// (the block on the left), `normals` inward at each point, cut at equal steps near `width`
// (or where `drawn_cuts` says, from p.lot_frontages).
void run_lots(const std::vector<Vec2>& points, const std::vector<Vec2>& normals, const RunEnd& first, const RunEnd& last,
              const std::vector<geom::KindedRing>& rings, const AllocationSettings& p, double width, Random& rng,
              std::vector<geom::Ring>& lots) {
  const double depth = p.lot_depth, min_edge = p.min_lot_edge;
  std::vector<double> at_length{0};
  for (std::size_t i = 1; i < points.size(); ++i) at_length.push_back(at_length.back() + geom::distance(points[i - 1], points[i]));
  const double total = at_length.back(), begin = first.skip;
  if (total - begin < min_edge) return;
  // Where the block is too thin for the full depth, lots are narrower too, so that none is
  // much wider than deep (kLotShape).
  std::size_t mid = 0;
  while (mid + 2 < points.size() && at_length[mid + 1] < (begin + total) / 2) ++mid;
  const double room = lot_room(rings, lerp(points[mid], points[mid + 1], 0.5), left_normal(points[mid], points[mid + 1]), 4 * depth);
  const double widest = std::max(2 * std::min(depth, room), min_edge);
  std::vector<double> cut_at;  // where along the run each lot starts, and the last one ends
  if (!p.lot_frontages.empty()) {
    for (double f : drawn_cuts(total - begin, p.lot_frontages, widest, rng)) cut_at.push_back(begin + (total - begin) * f);
  } else {
    width = std::min(width, widest);
    const int count = std::max(1, static_cast<int>(std::lround((total - begin) / width)));
    for (int k = 0; k <= count; ++k) cut_at.push_back(begin + (total - begin) * k / count);
  }
  const int count = static_cast<int>(cut_at.size()) - 1;
  // The cuts: square to the street, but at the run's ends, where they are as given.
  std::vector<Cut> cuts;
  std::vector<std::size_t> after;  // per cut: the index of the first point past it
  std::size_t seg = 0;
  for (int k = 0; k <= count; ++k) {
    const double s = cut_at[k];
    while (seg + 2 < points.size() && at_length[seg + 1] <= s) ++seg;
    const double span = at_length[seg + 1] - at_length[seg];
    Vec2 at = lerp(points[seg], points[seg + 1], span > 0 ? (s - at_length[seg]) / span : 0);
    Vec2 dir = at_length[seg] == s ? normals[seg] : left_normal(points[seg], points[seg + 1]);
    Vec2 depth_from = at;  // where the block's thickness is measured
    if (k == 0 && begin == 0) at = points.front(), dir = first.dir;
    if (k == count) {
      depth_from = points.back();
      at = points.back() + unit(points.back() - points[points.size() - 2]) * last.extend;
      dir = last.dir;
    }
    double reach = depth / std::max(dot(dir, k == count ? normals.back() : normals[seg]), 0.5);
    cuts.push_back({at, dir, std::min(reach, lot_room(rings, depth_from, dir, 4 * depth))});
    after.push_back(k == count ? points.size() : seg + 1);
  }
  // Neighbouring cuts that would cross (inside a bend) stop short of where they meet.
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    Cut &a = cuts[k], &b = cuts[k + 1];
    double den = cross(a.dir, b.dir);
    if (den == 0) continue;
    double ta = cross(b.at - a.at, b.dir) / den, tb = cross(b.at - a.at, a.dir) / den;
    if (ta > 0 && tb > 0 && ta < a.depth && tb < b.depth) a.depth = std::min(a.depth, 0.9 * ta), b.depth = std::min(b.depth, 0.9 * tb);
  }
  for (int k = 0; k < count; ++k) {
    const Cut &a = cuts[k], &b = cuts[k + 1];
    if (std::min(a.depth, b.depth) < min_edge) continue;
    geom::Ring ring{a.at - a.dir * kFrontOverhang};
    for (std::size_t i = after[k]; i < after[k + 1] && i < points.size(); ++i)
      if (!(points[i] == a.at) && !(points[i] == b.at)) ring.push_back(points[i] - normals[i] * kFrontOverhang);
    ring.push_back(b.at - b.dir * kFrontOverhang);
    ring.push_back(b.at + b.dir * b.depth);
    ring.push_back(a.at + a.dir * a.depth);
    lots.push_back(std::move(ring));
  }
}

// The ring on the grid, counter-clockwise; empty when it is not a simple polygon.
geom::Ring on_grid(const geom::Ring& ring) {
  geom::Ring r;
  for (Vec2 p : ring) r.push_back(geom::snap(p));
  int o = geom::ring_orientation(r);
  if (o == 0) return {};
  if (o < 0) std::reverse(r.begin(), r.end());
  return r;
}

// The industrial chance: a lot is kept with a chance that falls after a kept lot and
// rises after a dropped one, so some street frontage stays open yard (unless the lots'
// frontages are a real place's, or its coverage fills the blocks, whose yards they hold).
class Allocation : public LotLayout {
 public:
  explicit Allocation(const AllocationSettings& settings) : settings_(settings) {}
  std::vector<PlannedLot> plan(const Block& block, int index, Random& rng) const override {
    std::vector<PlannedLot> out;
    double keep = 0.8;
    for (const geom::Ring& ring : street_lots(block.cell, settings_, rng)) {
      if (block.zone == ZoneType::Industrial && settings_.lot_frontages.empty() && !settings_.fills_blocks) {
        bool kept = rng.uniform() < keep;
        keep = std::clamp(keep + (kept ? -0.25 : 0.25), 0.25, 1.0);
        if (!kept) continue;
      }
      geom::Ring r = on_grid(ring);
      if (!r.empty()) out.push_back({index, block.zone, r, {}});
    }
    return out;
  }

 private:
  AllocationSettings settings_;
};

}  // namespace

std::unique_ptr<LotLayout> AllocationChoice::make(ZoneType, const ModelLibrary*, const Channels&) const {
  return std::make_unique<Allocation>(settings_);
}

std::vector<geom::Ring> street_lots(const geom::Cell& block, const AllocationSettings& p, Random& rng) {
  std::vector<geom::Ring> lots;
  const std::vector<geom::KindedRing> rings = block.kinded_rings();
  for (const geom::KindedRing& r : rings) {
    const std::size_t n = r.points.size();
    auto road = [&](std::size_t edge) { return BlockEdge::is_road(r.kinds[edge % n]); };
    auto normal = [&](std::size_t edge) { return left_normal(r.points[edge % n], r.points[(edge + 1) % n]); };
    // At vertex i, between edge i - 1 and edge i; or, for a real place's lots, where either
    // is shorter than kTinyEdge, the nearest longer ones: rounding leaves blocks with such
    // edges at random turns along straight streets (Helsinki's centre has 249), which break
    // a run into lots cut at false corners.
    auto edge = [&](std::size_t e) { return r.points[(e + 1) % n] - r.points[e % n]; };
    const double tiny = p.lot_frontages.empty() ? 0 : kTinyEdge;  // sketches without them as before
    auto turn = [&](std::size_t i) {
      std::size_t before = i + n - 1, after = i;
      for (std::size_t k = 0; k < n && std::hypot(edge(before).x, edge(before).y) < tiny; ++k) before += n - 1;
      for (std::size_t k = 0; k < n && std::hypot(edge(after).x, edge(after).y) < tiny; ++k) ++after;
      const Vec2 u = edge(before), v = edge(after);
      return std::atan2(cross(u, v), dot(u, v));
    };
    auto breaks = [&](std::size_t i) { return road(i + n - 1) != road(i) || std::abs(turn(i)) > kRunTurn; };
    std::size_t start = n;
    for (std::size_t i = 0; i < n; ++i)
      if (breaks(i)) {
        start = i;
        break;
      }
    const bool closed = start == n;  // one smooth run all round
    if (closed) {
      if (!road(0)) continue;
      start = 0;
    }
    // At a corner the cut runs along the bisector of the two edges' inward normals; a
    // square-ish convex corner between two streets goes whole to the lot arriving there,
    // and the run leaving it starts where that lot's back line meets it. Where the run meets
    // an edge with no road, whose side no lots come from, the cut runs along that edge (when
    // it turns into the block by 30° to 150°, and the cut ends on it), so the lot takes the
    // land up to it.
    auto corner_dir = [&](std::size_t vertex, Vec2 own) {
      if (!closed && road(vertex + n - 1) != road(vertex)) {
        const Vec2 v = r.points[vertex % n], far = road(vertex) ? r.points[(vertex + n - 1) % n] : r.points[(vertex + 1) % n];
        const Vec2 along = unit(far - v);
        if (dot(along, own) >= 0.5 &&
            std::min(p.lot_depth / dot(along, own), lot_room(rings, v, along, 4 * p.lot_depth)) <= geom::distance(v, far))
          return along;
      }
      Vec2 d = unit(normal(vertex + n - 1) + normal(vertex));
      return closed || dot(d, own) > 0.5 ? d : own;
    };
    // How deep the lot arriving at a vertex reaches there: lot_depth, at most the room
    // across (lot_room, as run_lots cuts its last lot). An owned corner's lot ends that far back, so
    // the run leaving the corner starts where that depth, not lot_depth, meets it.
    auto corner_depth = [&](std::size_t vertex) {
      return std::min(p.lot_depth, lot_room(rings, r.points[vertex % n], normal(vertex + n - 1), 4 * p.lot_depth));
    };
    auto owned = [&](std::size_t vertex) {
      const double t = turn(vertex);
      return !closed && road(vertex + n - 1) && road(vertex) && t >= kOwnedCorner.min && t <= kOwnedCorner.max;
    };
    // Runs from `start` on: [i, j) edges.
    for (std::size_t i = start; i < start + n;) {
      std::size_t j = i + 1;
      while (j < start + n && !breaks(j)) ++j;
      if (road(i)) {
        std::vector<Vec2> pts, normals;
        for (std::size_t k = i; k <= j; ++k) {
          pts.push_back(r.points[k % n]);
          normals.push_back(k == i ? normal(i) : k == j ? normal(j - 1) : unit(normal(k - 1) + normal(k)));
        }
        RunEnd first{corner_dir(i, normals.front())}, last{corner_dir(j, normals.back())};
        if (owned(i)) first = {normals.front(), corner_depth(i) / std::sin(turn(i)), 0};
        if (owned(j)) last = {normals.back(), 0, kFrontOverhang + std::max(0.0, corner_depth(j) / std::tan(turn(j)))};
        const double width = p.lot_frontages.empty() ? rng.uniform(p.lot_width.min, p.lot_width.max) : 0;
        run_lots(pts, normals, first, last, rings, p, width, rng, lots);
      }
      i = j;
    }
  }
  return lots;
}

std::shared_ptr<const LotLayoutChoice> read_allocation(const LotLayoutReading& reading) {
  const SettingsReader& s = reading.settings;
  AllocationSettings a;
  if (reading.zone == ZoneType::Commercial) a.lot_width = {20, 45}, a.lot_depth = 35;
  if (reading.zone == ZoneType::Industrial) a.lot_width = {40, 90}, a.lot_depth = 60;
  s.number("min_lot_edge", a.min_lot_edge, 0, 1e4);
  s.number("lot_depth", a.lot_depth, 2, 1e4);
  s.range("lot_width", a.lot_width, 2, 1e4, "lot frontage in metres");
  s.distribution("lot_frontages", a.lot_frontages, 1, 1e4, "lot frontages in m", "[12, 18, 25, 60]");
  double coverage = 0;  // a building setting (read_building_settings), read here for what it means to the lots
  s.number("lot_coverage", coverage, 0, 1);
  a.fills_blocks = coverage > 0;
  return std::make_shared<AllocationChoice>(a);
}

}  // namespace exacity
