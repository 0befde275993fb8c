#include "geom/filled_outline.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

#include <map>

#include "geom/grid.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"

namespace geom {
namespace {

// Doubles in, predicates only: exact on the rounded points (as in polygon_check.cpp).
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

bool covered(const std::vector<Ring>& rings, Vec2 p) {
  for (const Ring& r : rings) {
    std::vector<K::Point_2> pts;
    for (Vec2 v : r) pts.emplace_back(v.x, v.y);
    if (CGAL::bounded_side_2(pts.begin(), pts.end(), K::Point_2(p.x, p.y), K()) != CGAL::ON_UNBOUNDED_SIDE) return true;
  }
  return false;
}

}  // namespace

std::optional<std::vector<Ring>> filled_outline(const std::vector<std::array<Vec2, 3>>& shadows,
                                                const std::vector<std::pair<Vec2, Vec2>>& section,
                                                const std::vector<Vec2>& must_cover) {
  PlanarMap map;
  for (const auto& t : shadows) {
    Ring r{snap(t[0]), snap(t[1]), snap(t[2])};
    const int o = ring_orientation(r);
    if (o == 0) continue;
    if (o < 0) std::swap(r[1], r[2]);
    map.add_ring(r, 0);
  }
  // A section winds consistently only when every rounded point is left as often as reached.
  auto key = [](Vec2 p) { return std::pair{p.x, p.y}; };
  std::map<std::pair<double, double>, int> balance;
  for (auto [a, b] : section) {
    const Vec2 p = snap(a), q = snap(b);
    if (p == q) continue;
    ++balance[key(p)], --balance[key(q)];
    map.add_edge(p, q, 1);
  }
  for (const auto& [point, out_less_in] : balance)
    if (out_less_in != 0) return std::nullopt;
  map.insert_batch();
  map.label_faces([](const Windings& w) { return winding_of(w, 0) != 0 || winding_of(w, 1) != 0 ? 1 : 0; });
  std::vector<Ring> rings;
  std::vector<std::vector<Dissolved>> pieces = map.dissolve({-1, 0}, 1);
  for (Dissolved& d : pieces[0]) rings.push_back(std::move(d.polygon.outer));
  for (Vec2 p : must_cover)
    if (!covered(rings, snap(p))) return std::nullopt;
  return rings;
}

}  // namespace geom
