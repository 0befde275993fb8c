#include "geom/untangle.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "geom/measure.h"
#include "geom/polygon_check.h"
#include "geom/split_loops.h"

namespace geom {
namespace {

// Doubles in, predicates only: the filtered inexact kernel decides these exactly.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_2 point(Vec2 v) { return {v.x, v.y}; }

CGAL::Orientation turn(Vec2 a, Vec2 b, Vec2 c) { return CGAL::orientation(point(a), point(b), point(c)); }

struct Edge {
  Vec2 from, to;
};

struct PairHash {
  std::size_t operator()(const std::pair<Vec2, Vec2>& e) const { return Vec2Hash()(e.first) * 7 ^ Vec2Hash()(e.second); }
};

bool before(Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// The edges left when every edge run both ways cancels, in the order the rings give them.
std::vector<Edge> net_edges(const std::vector<Ring>& rings) {
  std::vector<Edge> all;
  std::unordered_map<std::pair<Vec2, Vec2>, int, PairHash> net;  // lower end first: +1 per edge that way
  for (const Ring& r : rings)
    for (std::size_t i = 0; i < r.size(); ++i) {
      Vec2 a = r[i], b = r[(i + 1) % r.size()];
      if (a == b) continue;
      all.push_back({a, b});
      net[before(a, b) ? std::pair(a, b) : std::pair(b, a)] += before(a, b) ? 1 : -1;
    }
  std::vector<Edge> kept;
  for (const Edge& e : all) {
    const bool forward = before(e.from, e.to);
    int& n = net[forward ? std::pair(e.from, e.to) : std::pair(e.to, e.from)];
    if (forward ? n > 0 : n < 0) kept.push_back(e), n += forward ? -1 : 1;
  }
  return kept;
}

// Clockwise angle from the direction v -> u to v -> w, as a rank and a tie-breaker: the
// next edge of a boundary arriving from u turns as tightly as possible, so the wedge of
// the region at v it bounds closes first.
bool turns_tighter(Vec2 u, Vec2 v, Vec2 a, Vec2 b) {
  auto rank = [&](Vec2 w) {
    CGAL::Orientation o = turn(v, u, w);
    if (o == CGAL::RIGHT_TURN) return 0;
    if (o == CGAL::LEFT_TURN) return 2;
    const bool back = (w.x - v.x) * (u.x - v.x) + (w.y - v.y) * (u.y - v.y) > 0;  // along v -> u
    return back ? 3 : 1;
  };
  const int ra = rank(a), rb = rank(b);
  if (ra != rb) return ra < rb;
  return ra % 2 == 0 && turn(v, a, b) == CGAL::RIGHT_TURN;  // same half-plane: b lies past a
}

int orientation(const Ring& r) {
  if (r.size() < 3) return 0;
  auto lowest = std::min_element(r.begin(), r.end(), [](Vec2 a, Vec2 b) { return a.y < b.y || (a.y == b.y && a.x < b.x); });
  const std::size_t i = static_cast<std::size_t>(lowest - r.begin()), n = r.size();
  return static_cast<int>(turn(r[(i + n - 1) % n], r[i], r[(i + 1) % n]));
}

}  // namespace

bool vertex_repeats(const std::vector<Ring>& rings) {
  std::unordered_set<Vec2, Vec2Hash> seen;
  for (const Ring& r : rings)
    for (Vec2 v : r)
      if (!seen.insert(v).second) return true;
  return false;
}

std::vector<Polygon> untangle(const std::vector<Ring>& rings) {
  bool short_ring = false;
  for (const Ring& r : rings) short_ring |= r.size() < 3;
  if (!short_ring && !rings.empty() && !vertex_repeats(rings)) return {Polygon{rings[0], std::vector<Ring>(rings.begin() + 1, rings.end())}};

  const std::vector<Edge> edges = net_edges(rings);
  std::unordered_map<Vec2, std::vector<std::size_t>, Vec2Hash> leaving;
  for (std::size_t i = 0; i < edges.size(); ++i) leaving[edges[i].from].push_back(i);
  std::vector<char> used(edges.size(), 0);
  std::vector<Ring> outers, holes;
  for (std::size_t first = 0; first < edges.size(); ++first) {
    if (used[first]) continue;
    Ring walk;
    for (std::size_t e = first; !used[e];) {
      used[e] = 1;
      walk.push_back(edges[e].from);
      const Vec2 u = edges[e].from, v = edges[e].to;
      const auto& out = leaving[v];
      e = *std::min_element(out.begin(), out.end(), [&](std::size_t a, std::size_t b) {
        return turns_tighter(u, v, edges[a].to, edges[b].to);
      });
    }
    for (Ring& loop : split_at_repeats<Vec2, Vec2Hash>(walk, [](Vec2 v) { return v; })) {
      const int o = orientation(loop);
      if (o > 0) outers.push_back(std::move(loop));
      else if (o < 0) holes.push_back(std::move(loop));
    }
  }
  std::vector<Polygon> polygons;
  for (Ring& o : outers) polygons.push_back({std::move(o), {}});
  for (Ring& h : holes) {
    Polygon* owner = nullptr;
    for (Polygon& p : polygons)
      if ((!owner || signed_area(p.outer) < signed_area(owner->outer)) && ring_within(h, p.outer)) owner = &p;
    if (owner) owner->holes.push_back(std::move(h));
  }
  return polygons;
}

}  // namespace geom
