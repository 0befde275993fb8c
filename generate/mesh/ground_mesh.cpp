#include "generate/mesh/ground_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>

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
  if (!terrain) return -kWaterBelowBank;
  double level = INFINITY;
  auto visit = [&](const geom::Ring& r) {
    for (geom::Vec2 p : geom::densified(r, terrain->pixel_size() / 2)) level = std::min(level, terrain->height_at(p));
  };
  visit(water.outer);
  for (const auto& h : water.holes) visit(h);
  return (std::isfinite(level) ? level : terrain->lowest()) - kWaterBelowBank;
}

double bed_height(const Terrain* terrain, geom::Vec2 p, double level) {
  return std::min(terrain ? terrain->height_at(p) : level, level - kBedDepth);
}

namespace {

// The terrain mesh's grid: its lines, through the heightmap's pixel centres, fine over the
// detailed box and coarser past it, over the box grown by a cell.
struct TerrainGrid {
  geom::Box box;                // the grown box the lines span
  std::vector<double> xs, ys;  // the lines, ascending, the box's edges first and last
  double step = 0;             // the finer of the two fine spacings
  int nx() const { return static_cast<int>(xs.size()) - 1; }
  int ny() const { return static_cast<int>(ys.size()) - 1; }
  geom::Vec2 at(int i, int j) const { return {xs[i], ys[j]}; }
};

// Lines every `fine` over [dlo, dhi], every `coarse` (a multiple of it) elsewhere, all
// through the pixel centres' lines; none nearer than a quarter of `fine` to the next.
std::vector<double> grid_lines(double lo, double hi, double dlo, double dhi, double first, double fine, double coarse) {
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
}

// Without terrain: the box grown by a metre, no lines inside (the land is flat).
TerrainGrid flat_grid(const geom::Box& b) {
  TerrainGrid grid;
  grid.box = {b.min_x - 1, b.min_y - 1, b.max_x + 1, b.max_y + 1};
  grid.xs = {grid.box.min_x, grid.box.max_x};
  grid.ys = {grid.box.min_y, grid.box.max_y};
  grid.step = INFINITY;
  return grid;
}

// Grid lines through the pixel centres (extended past the map), or coarser ones; the box's
// own edges, one cell out, close the grid.
TerrainGrid terrain_grid(const Terrain& terrain, const geom::Box& box_in, const geom::Box& detail, int max_cells) {
  const geom::Box& map = terrain.bounds();
  const double pw = map.width() / terrain.width(), ph = map.height() / terrain.height();
  const double sx = std::max(pw, detail.width() / max_cells), sy = std::max(ph, detail.height() / max_cells);
  TerrainGrid grid;
  grid.step = std::min(sx, sy);
  grid.box = {box_in.min_x - sx, box_in.min_y - sy, box_in.max_x + sx, box_in.max_y + sy};
  const geom::Box& box = grid.box;
  // Past the detailed box the cells grow so that about 128 more span the rest.
  auto coarse = [](double fine, double span) { return fine * std::max(1.0, std::ceil(span / 128 / fine)); };
  grid.xs = grid_lines(box.min_x, box.max_x, detail.min_x, detail.max_x, map.min_x + pw / 2, sx,
                       coarse(sx, box.width() - detail.width()));
  grid.ys = grid_lines(box.min_y, box.max_y, detail.min_y, detail.max_y, map.min_y + ph / 2, sy,
                       coarse(sy, box.height() - detail.height()));
  return grid;
}

// The land: the grid's outline, with every water ring, split as finely as the land beside
// it, as a hole (an island's ring, a hole in water, is then land again: inside is an odd
// count of rings).
struct Land {
  geom::Polygon polygon;
  std::vector<double> levels;                                     // by water
  std::vector<std::pair<std::size_t, std::size_t>> water_rings;  // by water: (first ring, ring count) in the holes
};

Land land_around_water(const TerrainGrid& grid, const Terrain* terrain, const std::vector<geom::Polygon>& water) {
  Land land;
  geom::Ring& outer = land.polygon.outer;
  const int nx = grid.nx(), ny = grid.ny();
  for (int i = 0; i < nx; ++i) outer.push_back(grid.at(i, 0));
  for (int j = 0; j < ny; ++j) outer.push_back(grid.at(nx, j));
  for (int i = nx; i > 0; --i) outer.push_back(grid.at(i, ny));
  for (int j = ny; j > 0; --j) outer.push_back(grid.at(0, j));
  // Flat land needs no points along the rings but their corners.
  auto split = [&](const geom::Ring& r) {
    return terrain ? geom::densified(r, std::min(grid.step, terrain->pixel_size()) / 2) : r;
  };
  std::vector<geom::Ring>& holes = land.polygon.holes;
  for (const geom::Polygon& w : water) {
    land.levels.push_back(water_level(w, terrain));
    land.water_rings.push_back({holes.size(), 1 + w.holes.size()});
    holes.push_back(split(w.outer));
    for (const auto& h : w.holes) holes.push_back(split(h));
  }
  return land;
}

// The grid points strictly inside the land, a quarter cell clear of every water ring.
std::vector<geom::Vec2> grid_points_on_land(const TerrainGrid& grid, const std::vector<geom::Ring>& water_rings) {
  const int nx = grid.nx(), ny = grid.ny();
  const std::vector<double>& xs = grid.xs;
  const std::vector<double>& ys = grid.ys;
  std::vector<char> keep(static_cast<std::size_t>(nx + 1) * (ny + 1), 1);
  auto at = [&](int i, int j) -> char& { return keep[static_cast<std::size_t>(j) * (nx + 1) + i]; };
  const double clear = grid.step / 4;
  for (const geom::Ring& r : water_rings)
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
          if (geom::distance_to_segment(grid.at(i, j), a, b) <= clear) at(i, j) = 0;
    }
  std::vector<geom::Vec2> inside;
  for (int j = 1; j < ny; ++j) {
    // Where this row crosses the water rings: a point with an odd count of crossings west of
    // it is in water.
    const double y = grid.at(0, j).y;
    std::vector<double> crossings;
    for (const geom::Ring& r : water_rings)
      for (std::size_t k = 0, l = r.size() - 1; k < r.size(); l = k++)
        if ((r[l].y > y) != (r[k].y > y))
          crossings.push_back(r[l].x + (y - r[l].y) * (r[k].x - r[l].x) / (r[k].y - r[l].y));
    std::sort(crossings.begin(), crossings.end());
    std::size_t west = 0;
    for (int i = 1; i < nx; ++i) {
      const geom::Vec2 p = grid.at(i, j);
      while (west < crossings.size() && crossings[west] < p.x) ++west;
      if (at(i, j) && west % 2 == 0) inside.push_back(p);
    }
  }
  return inside;
}

// The inward normal at each corner of a ring with water on its left: the mean of its two
// edges' left normals.
std::vector<geom::Vec2> inward_normals(const geom::Ring& r) {
  std::vector<geom::Vec2> normals(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    const geom::Vec2 prev = r[(i + r.size() - 1) % r.size()], next = r[(i + 1) % r.size()];
    const geom::Vec2 n = geom::left_normal(prev, r[i]) + geom::left_normal(r[i], next);
    const double length = std::hypot(n.x, n.y);
    normals[i] = length > 0 ? n * (1 / length) : geom::left_normal(r[i], next);
  }
  return normals;
}

// The bank and bed under heightmap water of level `level`, its rings split as the land's
// (`rings`): from each point of the outline, at the land's height there, the bank runs
// down at kBankSlope until kBedDepth under the water, or steeper so that it gets there
// within a quarter of the water's width; the bed lies under it (bed_height). Points along
// each corner's inward normal at a third, two thirds and all of its bank's run, and the
// pixel centres inside, carry the slope; the land meets the bank at the outline without
// a wall.
void add_sloped_bank_and_bed(const geom::Polygon& water, const geom::Polygon& rings, double level,
                             const Terrain& terrain, GroundMesh& m) {
  const double bed = level - kBedDepth;
  const double reach = std::max(2 * geom::area(water) / geom::perimeter(water) / 4, 1e-3);
  auto run_from = [&](double drop) { return std::min(drop / kBankSlope, reach); };
  const double gap = terrain.pixel_size() / 8;
  std::vector<geom::Vec2> points;
  std::vector<double> heights;
  std::map<std::pair<long, long>, std::vector<std::size_t>> near;  // accepted points by cell of `gap`
  auto cell = [&](geom::Vec2 p) { return std::make_pair(std::lround(p.x / gap), std::lround(p.y / gap)); };
  auto add = [&](geom::Vec2 p, double z) {
    const auto [cx, cy] = cell(p);
    for (long dy = -1; dy <= 1; ++dy)
      for (long dx = -1; dx <= 1; ++dx)
        if (auto it = near.find({cx + dx, cy + dy}); it != near.end())
          for (std::size_t k : it->second)
            if (geom::distance(points[k], p) < gap) return;
    near[{cx, cy}].push_back(points.size());
    points.push_back(p), heights.push_back(z);
  };
  auto visit = [&](const geom::Ring& r) {
    const std::vector<geom::Vec2> normals = inward_normals(r);
    for (std::size_t i = 0; i < r.size(); ++i) {
      const double top = terrain.height_at(r[i]), drop = std::max(top - bed, 0.0), run = run_from(drop);
      for (double f : {1.0 / 3, 2.0 / 3, 1.0}) {
        const geom::Vec2 p = r[i] + normals[i] * (run * f);
        // Kept where the water is wider than the bank: not folded past the far side.
        if (geom::odd_crossings(rings, p) && geom::distance_to_outline(rings, p) > run * f * 0.9)
          add(p, std::max(top - drop * f, bed_height(&terrain, p, level)));
      }
    }
  };
  visit(rings.outer);
  for (const auto& h : rings.holes) visit(h);
  // The pixel centres inside, at the bank from the nearest point of the outline or on the bed.
  geom::Box box = geom::Box::none();
  for (geom::Vec2 p : rings.outer) box.add(p);
  for (geom::Vec2 p : terrain.pixel_centres(box)) {
    if (!geom::odd_crossings(rings, p)) continue;
    double d = INFINITY;
    geom::Vec2 nearest = p;
    auto closest = [&](const geom::Ring& r) {
      for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
        const geom::Vec2 q = geom::nearest_on_segment(p, r[j], r[i]);
        if (const double e = geom::distance(p, q); e < d) d = e, nearest = q;
      }
    };
    closest(rings.outer);
    for (const auto& h : rings.holes) closest(h);
    if (d < terrain.pixel_size() / 4) continue;  // no sliver along the outline
    const double top = terrain.height_at(nearest), drop = std::max(top - bed, 0.0), run = run_from(drop);
    add(p, std::max(run > 0 ? top - drop * d / run : bed, bed_height(&terrain, p, level)));
  }
  const int first = static_cast<int>(m.vertices.size());
  for (geom::Vec2 p : rings.outer) m.vertices.push_back({p.x, p.y, terrain.height_at(p)});
  for (const auto& h : rings.holes)
    for (geom::Vec2 p : h) m.vertices.push_back({p.x, p.y, terrain.height_at(p)});
  for (std::size_t k = 0; k < points.size(); ++k) m.vertices.push_back({points[k].x, points[k].y, heights[k]});
  for (const auto& t : geom::triangulate(rings, points)) m.triangles.push_back({first + t[0], first + t[1], first + t[2]});
}

// Banks and beds: with terrain each bank slopes from the land's edge down under the water
// (add_sloped_bank_and_bed); on flat land it is a wall from the land down to the bed, the
// bed flat under the water.
void add_banks_and_beds(const Land& land, const std::vector<geom::Polygon>& water, const Terrain* terrain,
                        GroundMesh& m) {
  for (std::size_t w = 0; w < water.size(); ++w) {
    const auto [first, count] = land.water_rings[w];
    geom::Polygon rings{land.polygon.holes[first], {}};
    for (std::size_t k = 1; k < count; ++k) rings.holes.push_back(land.polygon.holes[first + k]);
    if (terrain) {
      add_sloped_bank_and_bed(water[w], rings, land.levels[w], *terrain, m);
      continue;
    }
    const double bottom = land.levels[w] - kBedDepth;
    for (std::size_t k = 0; k < count; ++k)
      add_wall(land.polygon.holes[first + k], [](geom::Vec2) { return 0.0; }, [&](geom::Vec2) { return bottom; }, m);
    drape_flat(water[w], bottom, m);
  }
}

}  // namespace

GroundMesh terrain_mesh(const Terrain* terrain, const geom::Box& box, const geom::Box& detail,
                        const std::vector<geom::Polygon>& water, int max_cells) {
  const TerrainGrid grid = terrain ? terrain_grid(*terrain, box, detail, max_cells) : flat_grid(box);
  const Land land = land_around_water(grid, terrain, water);
  const std::vector<geom::Vec2> inside = grid_points_on_land(grid, land.polygon.holes);
  auto triangles = geom::triangulate(land.polygon, inside);
  if (triangles.empty()) return terrain_tin(terrain, grid.box, max_cells);  // rings that cross: no banks
  GroundMesh m;
  auto height = [&](geom::Vec2 p) { return terrain ? terrain->height_at(p) : 0.0; };
  for (geom::Vec2 p : land.polygon.outer) m.vertices.push_back({p.x, p.y, height(p)});
  for (const auto& h : land.polygon.holes)
    for (geom::Vec2 p : h) m.vertices.push_back({p.x, p.y, height(p)});
  for (geom::Vec2 p : inside) m.vertices.push_back({p.x, p.y, height(p)});
  m.triangles = std::move(triangles);
  add_banks_and_beds(land, water, terrain, m);
  return m;
}

}  // namespace exacity
