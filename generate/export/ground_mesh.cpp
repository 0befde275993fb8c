#include "generate/export/ground_mesh.h"

#include <algorithm>
#include <cmath>

#include "geom/measure.h"
#include "geom/triangulate.h"

namespace exacity {

void drape(const geom::Polygon& polygon, const Terrain* terrain, double lift, GroundMesh& out) {
  geom::Polygon dense;
  std::vector<geom::Vec2> inside;
  if (!terrain) {
    dense = polygon;
  } else {
    const double step = terrain->pixel_size() / 2;
    dense.outer = geom::densified(polygon.outer, step);
    for (const auto& h : polygon.holes) dense.holes.push_back(geom::densified(h, step));
    // Pixel centres inside, kept a quarter pixel clear of the edges so no sliver forms.
    geom::Box box = geom::Box::none();
    for (geom::Vec2 p : polygon.outer) box.add(p);
    auto clear_inside = [&](geom::Vec2 p) {
      bool in = false;
      double nearest = INFINITY;
      auto visit = [&](const geom::Ring& r) {
        in ^= geom::odd_crossings(r, p);
        for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
          nearest = std::min(nearest, geom::distance_to_segment(p, r[j], r[i]));
      };
      visit(polygon.outer);
      for (const auto& h : polygon.holes) visit(h);
      return in && nearest > step / 2;
    };
    for (geom::Vec2 p : terrain->pixel_centres(box))
      if (clear_inside(p)) inside.push_back(p);
  }
  std::vector<geom::Vec2> points(dense.outer);
  for (const auto& h : dense.holes) points.insert(points.end(), h.begin(), h.end());
  points.insert(points.end(), inside.begin(), inside.end());
  const int first = static_cast<int>(out.vertices.size());
  for (geom::Vec2 p : points) out.vertices.push_back({p.x, p.y, (terrain ? terrain->height_at(p) : 0) + lift});
  for (const auto& t : geom::triangulate(dense, inside)) out.triangles.push_back({first + t[0], first + t[1], first + t[2]});
}

GroundMesh terrain_tin(const Terrain* terrain, const geom::Box& box, int max_cells) {
  GroundMesh m;
  int nx = 1, ny = 1;
  if (terrain) {
    const double px = terrain->pixel_size();
    nx = std::clamp(static_cast<int>(std::ceil(box.width() / px)), 1, max_cells);
    ny = std::clamp(static_cast<int>(std::ceil(box.height() / px)), 1, max_cells);
  }
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      geom::Vec2 p{box.min_x + box.width() * i / nx, box.min_y + box.height() * j / ny};
      m.vertices.push_back({p.x, p.y, terrain ? terrain->height_at(p) : 0});
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  return m;
}

}  // namespace exacity
