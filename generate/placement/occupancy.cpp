#include "generate/placement/occupancy.h"

#include <algorithm>
#include <cmath>

#include "geom/polygon_check.h"

namespace exacity {

Frontage principal_frontage(const geom::Cell& piece, int road_kind) {
  auto edges = piece.edges_of_kind(road_kind);
  std::vector<geom::Vec2> corners = piece.corners();
  Frontage f;
  f.on_road = !edges.empty();
  if (edges.empty())
    for (std::size_t i = 0; i < corners.size(); ++i) edges.push_back({corners[i], corners[(i + 1) % corners.size()]});
  double longest = 0;
  for (auto [a, b] : edges) {
    double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len > longest) longest = len, f.a = a, f.u = geom::unit_along(a, b);
  }
  if (longest == 0) return f;
  f.n = {-f.u.y, f.u.x};  // the piece lies on each boundary edge's left
  f.t0 = INFINITY, f.t1 = -INFINITY;
  for (geom::Vec2 c : corners) {
    double t = (c.x - f.a.x) * f.u.x + (c.y - f.a.y) * f.u.y, d = (c.x - f.a.x) * f.n.x + (c.y - f.a.y) * f.n.y;
    f.t0 = std::min(f.t0, t), f.t1 = std::max(f.t1, t), f.depth = std::max(f.depth, d);
  }
  return f;
}

bool Occupancy::inside(const geom::Ring& ring) const {
  return geom::ring_orientation(ring) == 1 && piece_.holds(ring);
}

bool Occupancy::free(const geom::Ring& ring, const std::vector<Slab>* slabs) const {
  if (!inside(ring) || !apart_from_standing(ring)) return false;
  const double floor = slabs && !taken_.empty() ? ground_under(ring).second : 0;
  return std::none_of(taken_.begin(), taken_.end(), [&](const Taken& t) {
    if (!geom::rings_meet(ring, t.ring)) return false;
    return !slabs || t.slabs.empty() || slabs_meet(*slabs, floor, t.slabs, t.floor);
  });
}

bool Occupancy::take(const geom::Ring& ring, const std::vector<Slab>* slabs) {
  if (!free(ring, slabs)) return false;
  taken_.push_back({ring, slabs ? *slabs : std::vector<Slab>{}, slabs ? ground_under(ring).second : 0});
  return true;
}

void Occupancy::stand(std::vector<geom::Ring> rings, double area_m2) {
  standing_ = std::move(rings);
  standing_m2_ = area_m2;
}

bool Occupancy::apart_from_standing(const geom::Ring& ring) const {
  return std::none_of(standing_.begin(), standing_.end(), [&](const geom::Ring& s) { return geom::rings_meet(ring, s); });
}

std::pair<double, double> Occupancy::ground_under(const geom::Ring& ring) const {
  return terrain_ ? terrain_->range_under(ring) : std::pair<double, double>{0, 0};
}

}  // namespace exacity
