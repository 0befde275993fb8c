#include "generate/mesh/ground_mesh.h"

#include <algorithm>
#include <cmath>

#include "geom/measure.h"
#include "geom/triangulate.h"

namespace exacity {

namespace {

// The polygon triangulated with its edges split every half pixel and the pixel centres
// inside as vertices, each at height z(point).
template <typename Height>
void drape_with(const geom::Polygon& polygon, const Terrain* terrain, const Height& z, GroundMesh& out) {
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
    for (geom::Vec2 p : terrain->pixel_centres(box))
      if (geom::odd_crossings(polygon, p) && geom::distance_to_outline(polygon, p) > step / 2) inside.push_back(p);
  }
  std::vector<geom::Vec2> points(dense.outer);
  for (const auto& h : dense.holes) points.insert(points.end(), h.begin(), h.end());
  points.insert(points.end(), inside.begin(), inside.end());
  const int first = static_cast<int>(out.vertices.size());
  for (geom::Vec2 p : points) out.vertices.push_back({p.x, p.y, z(p)});
  for (const auto& t : geom::triangulate(dense, inside)) out.triangles.push_back({first + t[0], first + t[1], first + t[2]});
}

}  // namespace

void drape(const geom::Polygon& polygon, const Terrain* terrain, double lift, GroundMesh& out) {
  drape_with(polygon, terrain, [&](geom::Vec2 p) { return (terrain ? terrain->height_at(p) : 0) + lift; }, out);
}

void drape_flat(const geom::Polygon& polygon, double z, GroundMesh& out) {
  drape_with(polygon, nullptr, [&](geom::Vec2) { return z; }, out);
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

double water_level(const geom::Polygon& water, const Terrain* terrain) {
  if (!terrain) return 0;
  double level = INFINITY;
  auto visit = [&](const geom::Ring& r) {
    for (geom::Vec2 p : geom::densified(r, terrain->pixel_size() / 2)) level = std::min(level, terrain->height_at(p));
  };
  visit(water.outer);
  for (const auto& h : water.holes) visit(h);
  return std::isfinite(level) ? level : terrain->lowest();
}

double bed_height(const Terrain* terrain, geom::Vec2 p, double level) {
  return std::min(terrain ? terrain->height_at(p) : level, level - kBedDepth);
}

GroundMesh terrain_mesh(const Terrain* terrain, const geom::Box& box_in, const geom::Box& detail,
                        const std::vector<geom::Polygon>& water, int max_cells) {
  if (!terrain) return terrain_tin(nullptr, box_in, max_cells);
  // Grid lines through the pixel centres (extended past the map), or coarser ones; the box's
  // own edges, one cell out, close the grid.
  const geom::Box& map = terrain->bounds();
  const double pw = map.width() / terrain->width(), ph = map.height() / terrain->height();
  const double sx = std::max(pw, detail.width() / max_cells), sy = std::max(ph, detail.height() / max_cells);
  const double step = std::min(sx, sy);
  const geom::Box box{box_in.min_x - sx, box_in.min_y - sy, box_in.max_x + sx, box_in.max_y + sy};
  // Lines every `fine` over [dlo, dhi], every `coarse` (a multiple of it) elsewhere, all
  // through the pixel centres' lines; none nearer than a quarter of `fine` to the next.
  auto lines = [](double lo, double hi, double dlo, double dhi, double first, double fine, double coarse) {
    std::vector<double> at;
    for (double k = std::ceil((lo - first) / coarse); first + k * coarse < hi; ++k) at.push_back(first + k * coarse);
    for (double k = std::ceil((std::max(lo, dlo) - first) / fine); first + k * fine < std::min(hi, dhi); ++k)
      at.push_back(first + k * fine);
    std::sort(at.begin(), at.end());
    std::vector<double> kept{lo};
    for (double x : at)
      if (x - kept.back() >= fine / 4 && x <= hi - fine / 4) kept.push_back(x);
    kept.push_back(hi);
    return kept;
  };
  // Past the detailed box the cells grow so that about 128 more span the rest.
  auto coarse = [](double fine, double span) { return fine * std::max(1.0, std::ceil(span / 128 / fine)); };
  const std::vector<double> xs = lines(box.min_x, box.max_x, detail.min_x, detail.max_x, map.min_x + pw / 2, sx,
                                       coarse(sx, box.width() - detail.width()));
  const std::vector<double> ys = lines(box.min_y, box.max_y, detail.min_y, detail.max_y, map.min_y + ph / 2, sy,
                                       coarse(sy, box.height() - detail.height()));
  const int nx = static_cast<int>(xs.size()) - 1, ny = static_cast<int>(ys.size()) - 1;
  auto grid = [&](int i, int j) { return geom::Vec2{xs[i], ys[j]}; };

  geom::Polygon land;
  for (int i = 0; i < nx; ++i) land.outer.push_back(grid(i, 0));
  for (int j = 0; j < ny; ++j) land.outer.push_back(grid(nx, j));
  for (int i = nx; i > 0; --i) land.outer.push_back(grid(i, ny));
  for (int j = ny; j > 0; --j) land.outer.push_back(grid(0, j));
  // Every water ring, split as finely as the land beside it, is a hole of the land (an
  // island's ring, a hole in water, is then land again: inside is an odd count of rings).
  const double ring_step = std::min(step, terrain->pixel_size()) / 2;
  std::vector<double> levels;
  std::vector<std::pair<std::size_t, std::size_t>> ring_of_water;  // (first ring, ring count) in land.holes
  for (const geom::Polygon& w : water) {
    levels.push_back(water_level(w, terrain));
    ring_of_water.push_back({land.holes.size(), 1 + w.holes.size()});
    land.holes.push_back(geom::densified(w.outer, ring_step));
    for (const auto& h : w.holes) land.holes.push_back(geom::densified(h, ring_step));
  }

  // Grid points strictly inside the land, a quarter cell clear of every water ring.
  std::vector<char> keep(static_cast<std::size_t>(nx + 1) * (ny + 1), 1);
  auto at = [&](int i, int j) -> char& { return keep[static_cast<std::size_t>(j) * (nx + 1) + i]; };
  const double clear = step / 4;
  for (const geom::Ring& r : land.holes)
    for (std::size_t k = 0, l = r.size() - 1; k < r.size(); l = k++) {
      const geom::Vec2 a = r[l], b = r[k];
      auto first = [](const std::vector<double>& v, double x) {
        return static_cast<int>(std::lower_bound(v.begin(), v.end(), x) - v.begin());
      };
      auto last = [](const std::vector<double>& v, double x) {
        return static_cast<int>(std::upper_bound(v.begin(), v.end(), x) - v.begin()) - 1;
      };
      const int i0 = first(xs, std::min(a.x, b.x) - clear), i1 = last(xs, std::max(a.x, b.x) + clear);
      const int j0 = first(ys, std::min(a.y, b.y) - clear), j1 = last(ys, std::max(a.y, b.y) + clear);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i)
          if (geom::distance_to_segment(grid(i, j), a, b) <= clear) at(i, j) = 0;
    }
  std::vector<geom::Vec2> inside;
  for (int j = 1; j < ny; ++j) {
    // Where this row crosses the water rings: a point with an odd count of crossings west of
    // it is in water.
    const double y = grid(0, j).y;
    std::vector<double> crossings;
    for (const geom::Ring& r : land.holes)
      for (std::size_t k = 0, l = r.size() - 1; k < r.size(); l = k++)
        if ((r[l].y > y) != (r[k].y > y))
          crossings.push_back(r[l].x + (y - r[l].y) * (r[k].x - r[l].x) / (r[k].y - r[l].y));
    std::sort(crossings.begin(), crossings.end());
    std::size_t west = 0;
    for (int i = 1; i < nx; ++i) {
      const geom::Vec2 p = grid(i, j);
      while (west < crossings.size() && crossings[west] < p.x) ++west;
      if (at(i, j) && west % 2 == 0) inside.push_back(p);
    }
  }

  auto triangles = geom::triangulate(land, inside);
  if (triangles.empty()) return terrain_tin(terrain, box, max_cells);  // rings that cross: no banks
  GroundMesh m;
  auto height = [&](geom::Vec2 p) { return terrain->height_at(p); };
  for (geom::Vec2 p : land.outer) m.vertices.push_back({p.x, p.y, height(p)});
  for (const auto& h : land.holes)
    for (geom::Vec2 p : h) m.vertices.push_back({p.x, p.y, height(p)});
  for (geom::Vec2 p : inside) m.vertices.push_back({p.x, p.y, height(p)});
  m.triangles = std::move(triangles);

  // Banks: from the land's edge down to the bed, along the same split rings.
  for (std::size_t w = 0; w < water.size(); ++w) {
    const double bottom = levels[w] - kBedDepth;
    for (std::size_t k = 0; k < ring_of_water[w].second; ++k) {
      const geom::Ring& r = land.holes[ring_of_water[w].first + k];
      add_wall(r, height, [&](geom::Vec2) { return bottom; }, m);
    }
    drape_with(water[w], terrain, [&](geom::Vec2 p) { return bed_height(terrain, p, levels[w]); }, m);
  }
  return m;
}

}  // namespace exacity
