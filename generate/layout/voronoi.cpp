#include "generate/layout/voronoi.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "geom/grid.h"

namespace exacity {
namespace {

struct Edge {
  geom::Vec2 a, b;
};

double cross(geom::Vec2 o, geom::Vec2 a, geom::Vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Whether open segments p-q and r-s cross.
bool cross_each_other(geom::Vec2 p, geom::Vec2 q, geom::Vec2 r, geom::Vec2 s) {
  const double d1 = cross(p, q, r), d2 = cross(p, q, s), d3 = cross(r, s, p), d4 = cross(r, s, q);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// Degrees between two directions, ignoring which way each points: 0 to 90.
double angle_between(geom::Vec2 u, geom::Vec2 v) {
  const double a = std::abs(std::atan2(u.x * v.y - u.y * v.x, u.x * v.x + u.y * v.y)) * 180 / M_PI;
  return std::min(a, 180 - a);
}

geom::Vec2 direction(geom::Vec2 a, geom::Vec2 b) { return {b.x - a.x, b.y - a.y}; }

}  // namespace

std::vector<VoronoiCell> voronoi_cells(const std::vector<geom::Vec2>& sites, const geom::Box& box, double spacing) {
  // Sites in buckets of `spacing`: a cell's neighbours lie within a few buckets of it.
  std::map<std::pair<long, long>, std::vector<int>> buckets;
  auto bucket = [&](geom::Vec2 p) {
    return std::make_pair(static_cast<long>(std::floor((p.x - box.min_x) / spacing)),
                          static_cast<long>(std::floor((p.y - box.min_y) / spacing)));
  };
  for (std::size_t i = 0; i < sites.size(); ++i) buckets[bucket(sites[i])].push_back(static_cast<int>(i));
  std::vector<VoronoiCell> cells(sites.size());
  constexpr long kReach = 4;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const geom::Vec2 s = sites[i];
    VoronoiCell cell{{{box.min_x, box.min_y}, {box.max_x, box.min_y}, {box.max_x, box.max_y}, {box.min_x, box.max_y}},
                     {-1, -1, -1, -1}};
    const auto [bx, by] = bucket(s);
    std::vector<int> near;
    for (long y = by - kReach; y <= by + kReach; ++y)
      for (long x = bx - kReach; x <= bx + kReach; ++x)
        if (auto it = buckets.find({x, y}); it != buckets.end())
          for (int j : it->second)
            if (j != static_cast<int>(i)) near.push_back(j);
    // Nearest first, so most far sites cut nothing.
    std::sort(near.begin(), near.end(), [&](int a, int b) {
      return std::hypot(sites[a].x - s.x, sites[a].y - s.y) < std::hypot(sites[b].x - s.x, sites[b].y - s.y);
    });
    for (int j : near) {
      const geom::Vec2 t = sites[j];
      // Keep the side of the bisector nearer s: (p - m) . (t - s) <= 0.
      const geom::Vec2 m{(s.x + t.x) / 2, (s.y + t.y) / 2}, n{t.x - s.x, t.y - s.y};
      auto side = [&](geom::Vec2 p) { return (p.x - m.x) * n.x + (p.y - m.y) * n.y; };
      VoronoiCell clipped;
      const std::size_t k = cell.ring.size();
      for (std::size_t e = 0; e < k; ++e) {
        const geom::Vec2 p = cell.ring[e], q = cell.ring[(e + 1) % k];
        const double sp = side(p), sq = side(q);
        if (sp <= 0) clipped.ring.push_back(p), clipped.across.push_back(cell.across[e]);
        if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0)) {
          const double f = sp / (sp - sq);
          clipped.ring.push_back({p.x + f * (q.x - p.x), p.y + f * (q.y - p.y)});
          // Entering the kept side: the edge on from here is p-q's; leaving: the bisector's.
          clipped.across.push_back(sp < 0 ? j : cell.across[e]);
        }
      }
      if (clipped.ring.size() < 3) {
        cell = {};
        break;
      }
      cell = std::move(clipped);
    }
    cells[i] = std::move(cell);
  }
  return cells;
}

std::vector<geom::Vec2> junctions_along(geom::Vec2 a, geom::Vec2 b, double spacing) {
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int steps = static_cast<int>(std::floor(length / spacing + 0.5));
  std::vector<geom::Vec2> out;
  if (length < 1.5 * spacing || steps < 2) return out;
  for (int k = 1; k < steps; ++k) {
    const double f = static_cast<double>(k) / steps;
    out.push_back(geom::snap(geom::Vec2{a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)}));
  }
  return out;
}

std::vector<std::pair<geom::Vec2, geom::Vec2>> inner_roads(const std::vector<CellRoad>& roads) {
  constexpr double kPerpendicular = 30, kParallel = 15;  // degrees of slack
  constexpr double kAlongRoad = 10;                       // degrees: a connection this near a road's line runs along it
  std::vector<std::pair<geom::Vec2, geom::Vec2>> made;
  std::vector<std::vector<char>> used(roads.size());
  for (std::size_t r = 0; r < roads.size(); ++r) used[r].assign(roads[r].size(), 0);
  auto along = [&](std::size_t r) { return direction(roads[r].front(), roads[r].back()); };
  auto free_junction = [&](std::size_t r, std::size_t k) { return k > 0 && k + 1 < roads[r].size() && !used[r][k]; };
  auto crosses_made = [&](geom::Vec2 p, geom::Vec2 q) {
    for (const auto& [a, b] : made)
      if (cross_each_other(p, q, a, b)) return true;
    return false;
  };
  // The best junction of another road to join (r, k) to: the one whose connection's angle
  // to `reference` is nearest `wanted` (90: perpendicular, 0: parallel), within `slack`.
  auto best_connection = [&](std::size_t r, std::size_t k, geom::Vec2 reference, double wanted, double slack) {
    std::pair<std::size_t, std::size_t> best{roads.size(), 0};
    double best_off = slack;
    const geom::Vec2 p = roads[r][k];
    for (std::size_t o = 0; o < roads.size(); ++o) {
      if (o == r) continue;
      for (std::size_t m = 0; m < roads[o].size(); ++m) {
        if (!free_junction(o, m)) continue;
        const geom::Vec2 q = roads[o][m];
        if (p == q || crosses_made(p, q)) continue;
        // Not along either road: two roads of a cell can run nearly in line.
        const geom::Vec2 pq = direction(p, q);
        if (angle_between(pq, along(r)) < kAlongRoad || angle_between(pq, along(o)) < kAlongRoad) continue;
        const double off = std::abs(angle_between(direction(p, q), reference) - wanted);
        if (off < best_off) best_off = off, best = {o, m};
      }
    }
    return best;
  };
  std::vector<std::size_t> order(roads.size());
  for (std::size_t r = 0; r < roads.size(); ++r) order[r] = r;
  auto length = [&](std::size_t r) {
    return std::hypot(roads[r].back().x - roads[r].front().x, roads[r].back().y - roads[r].front().y);
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return length(a) > length(b); });
  for (std::size_t r : order) {
    std::size_t k = 1;
    while (k + 1 < roads[r].size() && !free_junction(r, k)) ++k;
    if (k + 1 >= roads[r].size()) continue;
    auto [o, m] = best_connection(r, k, along(r), 90, kPerpendicular);
    if (o == roads.size()) continue;
    const geom::Vec2 first = direction(roads[r][k], roads[o][m]);
    made.push_back({roads[r][k], roads[o][m]});
    used[r][k] = used[o][m] = 1;
    for (std::size_t j = k + 1; j + 1 < roads[r].size(); ++j) {
      if (!free_junction(r, j)) continue;
      auto [o2, m2] = best_connection(r, j, first, 0, kParallel);
      if (o2 == roads.size()) continue;
      made.push_back({roads[r][j], roads[o2][m2]});
      used[r][j] = used[o2][m2] = 1;
    }
  }
  return made;
}

}  // namespace exacity
