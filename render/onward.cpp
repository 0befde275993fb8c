#include "render/onward.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "geom/measure.h"

namespace render {

namespace {

// Whether p lies in any of the polygons, those whose boxes hold it tested ring by ring.
class Cover {
 public:
  void add(const geom::Polygon& p) {
    geom::Box b = geom::Box::none();
    for (geom::Vec2 v : p.outer) b.add(v);
    polygons_.push_back(&p), boxes_.push_back(b);
  }
  bool holds(geom::Vec2 p) const {
    for (std::size_t i = 0; i < polygons_.size(); ++i) {
      const geom::Box& b = boxes_[i];
      if (p.x >= b.min_x && p.x <= b.max_x && p.y >= b.min_y && p.y <= b.max_y && geom::odd_crossings(*polygons_[i], p))
        return true;
    }
    return false;
  }

 private:
  std::vector<const geom::Polygon*> polygons_;
  std::vector<geom::Box> boxes_;
};

}  // namespace

std::vector<RoadOnward> roads_onward(const exacity::Ground& ground) {
  // Centre lines are noded: a road going on from an end shares its point exactly.
  std::map<std::pair<double, double>, int> points;
  for (const exacity::RoadLine& r : ground.roads)
    for (geom::Vec2 p : r.line) ++points[{p.x, p.y}];
  Cover city;
  for (const auto& z : ground.zones) city.add(z.polygon);
  for (const auto& w : ground.water) city.add(w);
  for (const auto& a : ground.road_areas) city.add(a.polygon);
  const geom::Box city_box = ground.bounds();
  std::vector<RoadOnward> out;
  for (std::size_t id = 0; id < ground.roads.size(); ++id) {
    const exacity::RoadLine& r = ground.roads[id];
    if (r.sketch_road < 0 || r.bridge || r.line.size() < 2 || r.road_class == exacity::RoadClass::Local) continue;
    for (int end = 0; end < 2; ++end) {
      geom::Polyline line = r.line;
      if (end == 0) std::reverse(line.begin(), line.end());
      const geom::Vec2 e = line.back();
      if (points[{e.x, e.y}] != 1) continue;
      // The direction over the line's last 10 m or more, not a short last piece's.
      std::size_t k = line.size() - 2;
      while (k > 0 && geom::distance(line[k], e) < 10) --k;
      if (geom::distance(line[k], e) == 0) continue;
      const geom::Vec2 u = geom::unit_along(line[k], e);
      if (city.holds(e + u * 20)) continue;
      // Until it would come back onto the city's ground (a city curving round).
      double length = kOnward;
      for (double at = 25; at < length && city_box.meets({e.x + u.x * at, e.y + u.y * at, e.x + u.x * at, e.y + u.y * at});
           at += 5)
        if (city.holds(e + u * at)) length = at - 20;
      if (length < 50) continue;
      RoadOnward onward{id, r};
      onward.line.bridge = false;
      onward.line.line = {e, e + u * length};
      out.push_back(std::move(onward));
    }
  }
  return out;
}

WaterOnward water_onward(const std::vector<geom::Polygon>& water, const exacity::Terrain* terrain) {
  WaterOnward out;
  out.near = water;
  if (!terrain) return out;
  const geom::Box& b = terrain->bounds();
  const double fade = terrain->fade(), tolerance = 1e-9 * std::max(b.width(), b.height());
  auto on = [&](double v, double at) { return std::abs(v - at) <= tolerance; };
  // The bounds a point lies on, as bits: west, east, south, north.
  auto sides = [&](geom::Vec2 p) {
    return (on(p.x, b.min_x) ? 1 : 0) | (on(p.x, b.max_x) ? 2 : 0) | (on(p.y, b.min_y) ? 4 : 0) |
           (on(p.y, b.max_y) ? 8 : 0);
  };
  const std::array<geom::Vec2, 4> outward{{{-1, 0}, {1, 0}, {0, -1}, {0, 1}}};
  for (std::size_t w = 0; w < water.size(); ++w) {
    const geom::Ring& r = water[w].outer;
    geom::Ring ring;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const geom::Vec2 p = r[i], q = r[(i + 1) % r.size()];
      ring.push_back(p);
      const int sp = sides(p), sq = sides(q), shared = sp & sq;
      // A stretch along one bound, not from one of the map's corners (two stretches
      // pushed out from a corner would meet there).
      if (geom::distance(p, q) <= tolerance || (shared & (shared - 1)) || !shared || (sp & (sp - 1)) ||
          (sq & (sq - 1)))
        continue;
      const int side = shared == 1 ? 0 : shared == 2 ? 1 : shared == 4 ? 2 : 3;
      const geom::Vec2 n = outward[side];
      // The water lies on the stretch's left, the map's outside on its right: going out
      // along p's side and back along q's keeps the ring's turn.
      ring.push_back(p + n * fade), ring.push_back(q + n * fade);
      const double from = fade - WaterOnward::kOverlap;
      out.far.push_back({w, geom::Polygon{{p + n * from, p + n * kOnward, q + n * kOnward, q + n * from}, {}}});
    }
    out.near[w].outer = std::move(ring);
  }
  return out;
}

}  // namespace render
