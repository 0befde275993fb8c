#include "generate/lots.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "generate/random.h"
#include "geom/grid.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace {

using geom::Vec2;

Vec2 lerp(Vec2 a, Vec2 b, double t) { return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t}; }
double length(Vec2 a, Vec2 b) { return std::hypot(b.x - a.x, b.y - a.y); }

// The projection of p on the segment ab, when it falls on the segment.
std::optional<Vec2> project(Vec2 p, Vec2 a, Vec2 b) {
  double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  if (len2 == 0) return std::nullopt;
  double t = ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2;
  if (t < 0 || t > 1) return std::nullopt;
  return Vec2{a.x + t * dx, a.y + t * dy};
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

bool edges_at_least(const geom::Ring& r, double min_edge) {
  for (std::size_t i = 0; i < r.size(); ++i)
    if (length(r[i], r[(i + 1) % r.size()]) < min_edge) return false;
  return true;
}

constexpr int kCut = -2;  // edge kind of a split's cut (not a road)

// Seed 003: halve perpendicular to the longest edge near its middle until below lot_area;
// a split that would leave a part with no road edge (seed 004: frontage) is not made.
std::vector<geom::Cell> split_lots(const geom::Cell& block, const ZoneParams& p, Random& rng) {
  std::vector<geom::Cell> done, todo{block};
  while (!todo.empty()) {
    geom::Cell cell = std::move(todo.back());
    todo.pop_back();
    if (cell.area() <= p.lot_area) {
      done.push_back(std::move(cell));
      continue;
    }
    geom::Polygon shape = cell.to_plain();
    std::vector<std::pair<double, std::size_t>> edges;
    for (std::size_t i = 0; i < shape.outer.size(); ++i)
      edges.push_back({length(shape.outer[i], shape.outer[(i + 1) % shape.outer.size()]), i});
    std::sort(edges.rbegin(), edges.rend());
    const geom::Box b = cell.bounds();
    const double reach = 2 * std::hypot(b.width(), b.height()) + 1;
    bool split = false;
    for (std::size_t k = 0; k < std::min<std::size_t>(edges.size(), 2) && !split; ++k) {
      Vec2 a = shape.outer[edges[k].second], c = shape.outer[(edges[k].second + 1) % shape.outer.size()];
      Vec2 m = lerp(a, c, 0.5 + rng.uniform(-0.1, 0.1));
      Vec2 n{-(c.y - a.y) / edges[k].first, (c.x - a.x) / edges[k].first};
      auto cut = geom::Path::from({geom::snap({m.x - n.x * reach, m.y - n.y * reach}),
                                   geom::snap({m.x + n.x * reach, m.y + n.y * reach})});
      auto parts = geom::split_cell(cell, {cut}, kCut);
      bool fronted = parts.size() >= 2;
      for (const geom::Cell& part : parts) {
        auto kinds = part.edge_kinds();
        fronted &= !kinds.empty() && kinds.back() >= 0;
      }
      if (!fronted) continue;
      for (auto& part : parts) todo.push_back(std::move(part));
      split = true;
    }
    if (!split) done.push_back(std::move(cell));
  }
  return done;
}

}  // namespace

Vec2 weighted_centre(const std::vector<Vec2>& v) {
  const std::size_t n = v.size();
  double total = 0, x = 0, y = 0;
  for (std::size_t i = 0; i < n; ++i) {
    Vec2 a = v[(i + n - 1) % n], p = v[i], b = v[(i + 1) % n];
    double ux = a.x - p.x, uy = a.y - p.y, wx = b.x - p.x, wy = b.y - p.y;
    double lengths = std::hypot(ux, uy) * std::hypot(wx, wy);
    if (lengths == 0) continue;
    double w = 1 + (ux * wx + uy * wy) / lengths;
    // Relative to the first corner, so large coordinates keep their precision.
    total += w, x += w * (p.x - v[0].x), y += w * (p.y - v[0].y);
  }
  if (total <= 0) return v[0];
  return geom::snap({v[0].x + x / total, v[0].y + y / total});
}

std::vector<geom::Ring> corner_lots(Vec2 v0, Vec2 v1, Vec2 v2, Vec2 c) {
  auto toward = [&](Vec2 p, double t) { return lerp(p, c, t); };
  Vec2 p0 = toward(v0, 0.1), p1 = toward(v1, 0.1), p2 = toward(v2, 0.1);
  Vec2 p3 = toward(v2, 0.8), p4 = toward(v1, 0.8);
  auto p4_01 = project(p4, p0, p1), p4_12 = project(p4, p1, p2), p3_12 = project(p3, p1, p2);
  if (p4_01 && p4_12 && p3_12) return {{*p4_01, p1, *p4_12, p4}, {*p4_12, *p3_12, p3, p4}};
  if (!p4_01 && p4_12 && p3_12) {
    // The corner cannot be projected: two inside lots, the second from p5.
    Vec2 p5 = toward(v0, 0.8);
    std::vector<geom::Ring> lots;
    if (auto p5_01 = project(p5, p0, p1)) lots.push_back({*p4_12, *p5_01, p5, p4});
    lots.push_back({*p4_12, *p3_12, p3, p4});
    return lots;
  }
  if (p4_01 && !p4_12) {
    // The inside cannot be projected: p3 goes onto p0p1; an inside lot and a corner lot.
    if (auto p3_01 = project(p3, p0, p1)) return {{*p4_01, *p3_01, p3, p4}, {*p3_01, p1, p2, p3}};
  }
  return {};
}

std::vector<geom::Ring> residential_lots(const std::vector<Vec2>& v, Vec2 c) {
  std::vector<geom::Ring> lots;
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i)
    for (geom::Ring& r : corner_lots(v[(i + n - 1) % n], v[i], v[(i + 1) % n], c)) lots.push_back(std::move(r));
  return lots;
}

std::vector<Lot> plan_lots(const std::vector<Block>& blocks, const Sketch& sketch) {
  std::vector<std::vector<Lot>> per_block(blocks.size());
  const std::uint64_t stage = mix(sketch.seed, static_cast<std::uint64_t>(Stage::Lots));
  tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t bi) {
    const Block& block = blocks[bi];
    if (block.green) return;
    const ZoneParams& p = sketch.zone_params.at(block.zone);
    Random rng(mix(stage, bi));
    std::vector<Lot>& out = per_block[bi];
    const int b = static_cast<int>(bi);
    auto add_ring = [&](const geom::Ring& ring, bool check_edges) {
      geom::Ring r = on_grid(ring);
      if (!r.empty() && (!check_edges || edges_at_least(r, p.min_lot_edge))) out.push_back({b, block.zone, false, r, {}});
    };
    if (p.lots == "split") {
      for (geom::Cell& c : split_lots(block.cell, p, rng)) out.push_back({b, block.zone, true, {}, std::move(c)});
      return;
    }
    std::vector<Vec2> corners = block.cell.corners();
    if (corners.size() < 3) return;
    Vec2 centre = weighted_centre(corners);
    switch (block.zone) {
      case ZoneType::Residential:
        for (const geom::Ring& r : residential_lots(corners, centre)) add_ring(r, true);
        break;
      case ZoneType::Commercial: {
        geom::Ring inset;
        for (Vec2 v : corners) inset.push_back(lerp(centre, v, 0.8));
        add_ring(inset, false);
        break;
      }
      default: {  // industrial
        if (corners.size() != 4) {
          out.push_back({b, block.zone, false, {}, block.cell});
          break;
        }
        // Four quarters between the midlines, each kept with a chance that falls after a
        // kept quarter and rises after a dropped one.
        Vec2 q = lerp(lerp(corners[0], corners[2], 0.5), lerp(corners[1], corners[3], 0.5), 0.5);
        double keep = 0.8;
        for (int k = 0; k < 4; ++k) {
          Vec2 prev = corners[(k + 3) % 4], v = corners[k], next = corners[(k + 1) % 4];
          bool kept = rng.uniform() < keep;
          keep = std::clamp(keep + (kept ? -0.25 : 0.25), 0.25, 1.0);
          if (kept) add_ring({v, lerp(v, next, 0.5), q, lerp(prev, v, 0.5)}, true);
        }
      }
    }
  });
  std::vector<Lot> lots;
  for (auto& list : per_block)
    for (auto& lot : list) lots.push_back(std::move(lot));
  return lots;
}

void insert_lots(ZoneMap& zm, const std::vector<Block>& blocks, const std::vector<Lot>& lots, const Sketch& sketch) {
  zm.block_base = zm.generated_base + static_cast<int>(zm.roads.size()) - zm.sketch_roads;
  zm.lot_base = zm.block_base + static_cast<int>(blocks.size());
  zm.lot_block.clear();
  for (std::size_t b = 0; b < blocks.size(); ++b) zm.map.add_cell(blocks[b].cell, zm.block_base + static_cast<int>(b));
  for (std::size_t l = 0; l < lots.size(); ++l) {
    int counter = zm.lot_base + static_cast<int>(l);
    if (lots[l].ring.empty()) zm.map.add_cell(lots[l].cell, counter);
    else zm.map.add_ring(lots[l].ring, counter);
    zm.lot_block.push_back(lots[l].block);
  }
  zm.map.insert_batch();
  zm.label(sketch);
}

}  // namespace exacity
