#include "generate/mesh/bridges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>

#include "geom/measure.h"
#include "geom/triangulate.h"

namespace exacity {

namespace {

int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The sides of a block from z0 up to z1 over the four corners (counter-clockwise), and
// its top when `top`.
void add_block(const std::array<geom::Vec2, 4>& corners, double z0, double z1, bool top, GroundMesh& out) {
  const int first = static_cast<int>(out.vertices.size());
  for (double z : {z0, z1})
    for (geom::Vec2 p : corners) out.vertices.push_back({p.x, p.y, z});
  for (int k = 0; k < 4; ++k) {
    const int a = first + k, b = first + (k + 1) % 4;
    out.triangles.push_back({a, b, b + 4});
    out.triangles.push_back({a, b + 4, a + 4});
  }
  if (top) {
    out.triangles.push_back({first + 4, first + 5, first + 6});
    out.triangles.push_back({first + 4, first + 6, first + 7});
  }
}

// A pier from z0 up to z1 around c, its sides `half` from c, turned to run along `along`.
void add_pier(geom::Vec2 c, geom::Vec2 along, double half, double z0, double z1, GroundMesh& out) {
  const geom::Vec2 across = geom::left_normal({0, 0}, along);
  add_block({c + (along + across) * half, c + (across - along) * half, c - (along + across) * half,
             c + (along - across) * half},
            z0, z1, false, out);
}

// The index of the water polygon under the polygon (at the centroid of its first
// triangle), -1 if none.
int water_under(const Ground& ground, const geom::Polygon& p) {
  const auto triangles = geom::triangulate(p);
  if (triangles.empty()) return -1;
  std::vector<geom::Vec2> points(p.outer);
  for (const auto& h : p.holes) points.insert(points.end(), h.begin(), h.end());
  const auto& t = triangles.front();
  const geom::Vec2 c = (points[t[0]] + points[t[1]] + points[t[2]]) * (1.0 / 3);
  for (std::size_t w = 0; w < ground.water.size(); ++w)
    if (geom::odd_crossings(ground.water[w], c)) return static_cast<int>(w);
  return -1;
}

// Parapets along the deck's sides over water: an edge whose outside, just past it, is
// water that no bridge surface covers. Inside the deck's edge, so the road on the deck
// runs to it.
void add_parapets(const Ground& ground, const BridgeDecks& decks, const geom::Polygon& deck, double top,
                  GroundMesh& out) {
  constexpr double kProbe = 0.05;
  auto visit = [&](const geom::Ring& r) {
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      const geom::Vec2 a = r[j], b = r[i];
      if (geom::distance(a, b) < kProbe) continue;
      const geom::Vec2 inward = geom::left_normal(a, b);  // the deck lies left of its rings' edges
      const geom::Vec2 past = geom::lerp(a, b, 0.5) - inward * kProbe;
      if (decks.area_at(ground, past) >= 0) continue;
      if (std::none_of(ground.water.begin(), ground.water.end(),
                       [&](const geom::Polygon& w) { return geom::odd_crossings(w, past); }))
        continue;
      add_block({a, b, b + inward * kParapetThickness, a + inward * kParapetThickness}, top, top + kParapetHeight,
                true, out);
    }
  };
  visit(deck.outer);
  for (const auto& h : deck.holes) visit(h);
}

}  // namespace

BridgeDecks bridge_decks(const Ground& ground, const Terrain* terrain) {
  const auto& areas = ground.road_areas;
  BridgeDecks decks;
  decks.height.assign(areas.size(), NAN);
  // Bridge surfaces that share a corner are one bridge (carriageway, sidewalks, junctions).
  std::vector<int> parent(areas.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::map<std::pair<double, double>, int> corner_of;
  for (std::size_t i = 0; i < areas.size(); ++i) {
    if (!areas[i].bridge) continue;
    auto visit = [&](const geom::Ring& r) {
      for (geom::Vec2 p : r) {
        auto [it, added] = corner_of.emplace(std::make_pair(p.x, p.y), static_cast<int>(i));
        if (!added) parent[find(parent, static_cast<int>(i))] = find(parent, it->second);
      }
    };
    visit(areas[i].polygon.outer);
    for (const auto& h : areas[i].polygon.holes) visit(h);
  }
  std::vector<double> highest(areas.size(), terrain ? -INFINITY : 0);
  if (terrain)
    for (std::size_t i = 0; i < areas.size(); ++i) {
      if (!areas[i].bridge) continue;
      double& h = highest[find(parent, static_cast<int>(i))];
      for (geom::Vec2 p : geom::densified(areas[i].polygon.outer, terrain->pixel_size() / 2))
        h = std::max(h, terrain->height_at(p));
    }
  for (std::size_t i = 0; i < areas.size(); ++i)
    if (areas[i].bridge) decks.height[i] = highest[find(parent, static_cast<int>(i))] + kRoadOverTerrain;
  // The highest water under each bridge.
  std::vector<double> water_levels;
  for (const geom::Polygon& w : ground.water) water_levels.push_back(water_level(w, terrain));
  std::vector<double> water(areas.size(), -INFINITY);
  for (std::size_t i = 0; i < areas.size(); ++i)
    if (areas[i].bridge)
      if (const int w = water_under(ground, areas[i].polygon); w >= 0) {
        double& level = water[find(parent, static_cast<int>(i))];
        level = std::max(level, water_levels[w]);
      }
  decks.thickness.assign(areas.size(), NAN);
  for (std::size_t i = 0; i < areas.size(); ++i)
    if (areas[i].bridge) {
      const double over = decks.height[i] - water[find(parent, static_cast<int>(i))];
      decks.thickness[i] = std::clamp(over / 3, kThinnestDeck, kDeckThickness);
    }
  return decks;
}

int BridgeDecks::area_at(const Ground& ground, geom::Vec2 p) const {
  for (std::size_t i = 0; i < ground.road_areas.size(); ++i)
    if (ground.road_areas[i].bridge && geom::odd_crossings(ground.road_areas[i].polygon, p)) return static_cast<int>(i);
  return -1;
}

double BridgeDecks::at(const Ground& ground, geom::Vec2 p) const {
  const int i = area_at(ground, p);
  return i >= 0 ? height[i] : NAN;
}

void bridge_structure(const Ground& ground, const Terrain* terrain, const BridgeDecks& decks, GroundMesh& out,
                      std::vector<int>* area) {
  auto belongs = [&](int i) {
    if (area) area->resize(out.triangles.size(), i);
  };
  for (std::size_t i = 0; i < ground.road_areas.size(); ++i) {
    if (!ground.road_areas[i].bridge) continue;
    const geom::Polygon& p = ground.road_areas[i].polygon;
    const double top = decks.height[i], bottom = top - decks.thickness[i];
    drape_flat(p, bottom, out);
    auto at = [](double z) { return [z](geom::Vec2) { return z; }; };
    add_wall(p.outer, at(bottom), at(top), out);
    for (const auto& h : p.holes) add_wall(h, at(bottom), at(top), out);
    add_parapets(ground, decks, p, top, out);
    belongs(static_cast<int>(i));
  }
  std::vector<double> levels;
  for (const geom::Polygon& w : ground.water) levels.push_back(water_level(w, terrain));
  for (const RoadLine& r : ground.roads) {
    if (!r.bridge || r.line.size() < 2) continue;
    double length = 0;
    for (std::size_t k = 1; k < r.line.size(); ++k) length += geom::distance(r.line[k - 1], r.line[k]);
    const int piers = static_cast<int>(std::floor(length / kPierSpacing));
    const double half = std::min(kPierWidth, r.width / 4) / 2;
    for (int n = 1; n <= piers; ++n) {
      // The point n/(piers + 1) of the way along the line, and the line's direction there.
      double left = length * n / (piers + 1);
      std::size_t k = 1;
      while (k + 1 < r.line.size() && left > geom::distance(r.line[k - 1], r.line[k]))
        left -= geom::distance(r.line[k - 1], r.line[k]), ++k;
      const geom::Vec2 along = geom::unit_along(r.line[k - 1], r.line[k]);
      const geom::Vec2 c = r.line[k - 1] + along * left;
      const int under = decks.area_at(ground, c);
      if (under < 0) continue;
      const double underside = decks.height[under] - decks.thickness[under];
      double bed = terrain ? terrain->height_at(c) : 0;
      for (std::size_t w = 0; w < ground.water.size(); ++w)
        if (geom::odd_crossings(ground.water[w], c)) bed = bed_height(terrain, c, levels[w]);
      if (bed < underside) add_pier(c, along, half, bed, underside, out);
      belongs(under);
    }
  }
}

}  // namespace exacity
