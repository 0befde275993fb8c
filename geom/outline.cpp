#include "geom/outline.h"

#include <algorithm>

#include "geom/grid.h"
#include "geom/planar_map.h"
#include "geom/polygon_check.h"

namespace geom {

std::vector<Polygon> union_of_triangles(const std::vector<std::array<Vec2, 3>>& triangles) {
  std::vector<Ring> rings;
  for (const auto& t : triangles) {
    Ring r{snap(t[0]), snap(t[1]), snap(t[2])};
    int o = ring_orientation(r);
    if (o == 0) continue;
    if (o < 0) std::swap(r[1], r[2]);
    rings.push_back(std::move(r));
  }
  // Meshes repeat triangles (doubled faces, both sides of a thin wall): one ring each.
  auto less = [](const Ring& a, const Ring& b) {
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(),
                                        [](Vec2 p, Vec2 q) { return p.x < q.x || (p.x == q.x && p.y < q.y); });
  };
  for (Ring& r : rings) std::rotate(r.begin(), std::min_element(r.begin(), r.end(), [](Vec2 p, Vec2 q) {
                                      return p.x < q.x || (p.x == q.x && p.y < q.y);
                                    }), r.end());
  std::sort(rings.begin(), rings.end(), less);
  rings.erase(std::unique(rings.begin(), rings.end()), rings.end());

  PlanarMap map;
  for (const Ring& r : rings) map.add_ring(r, 0);
  map.insert_batch();
  map.label_faces([](const Windings& w) { return winding_of(w, 0) != 0 ? 1 : 0; });
  std::vector<Polygon> result;
  auto groups = map.dissolve({-1, 0}, 1);
  for (Dissolved& d : groups[0]) result.push_back(std::move(d.polygon));
  return result;
}

}  // namespace geom
