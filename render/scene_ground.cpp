// The scene's ground: the terrain, the ground layers draped over it, the road markings
// and the bridges' structure.
#include <algorithm>
#include <cmath>
#include <map>

#include "generate/cancel.h"
#include "generate/mesh/bridges.h"
#include "generate/mesh/ground_mesh.h"
#include "geom/measure.h"
#include "render/scene_build.h"

namespace render {

using exacity::ZoneType;

namespace {

constexpr double kKerb = 0.12;  // m: a sidewalk's height over the carriageway
constexpr double kMarkingLift = 0.12;  // m over the terrain: 2 cm over a road

// How far a marking's sides reach down from its top: 1 cm under the road it lies 2 cm over.
constexpr double kMarkingSides = 0.03;

// A ribbon of `width` along a ground path, its corners draped over the terrain, in pieces
// no longer than half a pixel; dashes where `dash` > 0 (dash on, gap off, metres). Each
// piece has sides down to under the road: without them a camera at eye height saw, just
// short of a marking, the road under it in its shadow (a one-pixel black line under every
// zebra stripe 20 m off), as it saw the ground under a road's edge (add_sides).
void ribbon(const geom::Polyline& line, double offset, double width, double dash, double gap,
            const exacity::Terrain* terrain, double lift, std::vector<V3>& verts, std::vector<std::array<int, 3>>& tris,
            const RenderScene& s) {
  const double step = terrain ? terrain->pixel_size() / 2 : 1e9;
  double along = 0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    geom::Vec2 a = line[i], b = line[i + 1];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len == 0) continue;
    const geom::Vec2 u = geom::unit_along(a, b), n = geom::left_normal(a, b);
    const double ux = u.x, uy = u.y, nx = n.x, ny = n.y;
    double t = 0;
    while (t < len) {
      double end = len;
      bool on = true;
      if (dash > 0) {
        const double phase = std::fmod(along + t, dash + gap);
        on = phase < dash;
        end = std::min(len, t + (on ? dash - phase : dash + gap - phase));
      }
      end = std::min(end, t + step);
      if (on) {
        auto corner = [&](double at, double side, double drop) {
          double x = a.x + ux * at + nx * (offset + side), y = a.y + uy * at + ny * (offset + side);
          double z = (terrain ? terrain->height_at({x, y}) : 0) + lift - drop;
          return s.to_scene(x, y, z);
        };
        const int first = static_cast<int>(verts.size());
        for (const double drop : {0.0, kMarkingSides})
          verts.insert(verts.end(), {corner(t, -width / 2, drop), corner(end, -width / 2, drop),
                                     corner(end, width / 2, drop), corner(t, width / 2, drop)});
        tris.push_back({first, first + 1, first + 2});
        tris.push_back({first, first + 2, first + 3});
        for (int k = 0; k < 4; ++k) {  // the top's edge k and the one under it
          const int top0 = first + k, top1 = first + (k + 1) % 4;
          tris.push_back({top0, top1 + 4, top1});
          tris.push_back({top0, top0 + 4, top1 + 4});
        }
      }
      t = end + 1e-9;
    }
    along += len;
  }
}

// A draped piece's sides, from its lifted edge to a little under the terrain, its edges
// split as drape splits them: without them a camera looking across a raised edge (a road
// 10 cm up beside grass 3 cm up) sees through the gap under it the ground beneath the
// piece, in the piece's shadow: a black sliver along the edge.
void add_sides(const geom::Polygon& polygon, const exacity::Terrain* terrain, double lift, exacity::GroundMesh& g) {
  auto ground = [&](geom::Vec2 p) { return terrain ? terrain->height_at(p) : 0.0; };
  auto side = [&](const geom::Ring& r) {
    exacity::add_wall(terrain ? geom::densified(r, terrain->pixel_size() / 2) : r,
                      [&](geom::Vec2 p) { return ground(p) + lift; }, [&](geom::Vec2 p) { return ground(p) - 0.05; }, g);
  };
  side(polygon.outer);
  for (const geom::Ring& h : polygon.holes) side(h);
}

// Where add_terrain draws the ground: without a heightmap the city's box; with one, a
// city's size past the city on every side and the map's fade() past the map.
geom::Box terrain_box(const exacity::Terrain* terrain, const geom::Box& world) {
  if (!terrain) return world;
  geom::Box wide{world.min_x - world.width(), world.min_y - world.height(), world.max_x + world.width(),
                 world.max_y + world.height()};
  const geom::Box& b = terrain->bounds();
  const double f = terrain->fade();
  wide.add(geom::Box{b.min_x - f, b.min_y - f, b.max_x + f, b.max_y + f});
  return wide;
}

// The roads' segments by a 50 m grid.
struct SegmentGrid {
  static constexpr double kCell = 50;
  std::map<std::pair<long, long>, std::vector<std::pair<int, int>>> cells;  // (road, segment)
  static std::pair<long, long> cell(geom::Vec2 p) {
    return {static_cast<long>(std::floor(p.x / kCell)), static_cast<long>(std::floor(p.y / kCell))};
  }
};

// Where a road's end point p meets another road: the distance back from p to the
// crossing road's edge (and a metre), NaN where no other road crosses there.
double crossing_edge(const std::vector<exacity::RoadLine>& roads, const SegmentGrid& grid, int road, geom::Vec2 p) {
  double edge = NAN;
  std::vector<int> met;
  const auto [cx, cy] = SegmentGrid::cell(p);
  for (long i = cx - 1; i <= cx + 1; ++i)
    for (long j = cy - 1; j <= cy + 1; ++j) {
      const auto it = grid.cells.find({i, j});
      if (it == grid.cells.end()) continue;
      for (const auto& [other, k] : it->second) {
        if (other == road) continue;
        const exacity::RoadLine& o = roads[other];
        if (geom::distance_to_segment(p, o.line[k], o.line[k + 1]) > o.width / 2 + 0.5) continue;
        const double back = o.width / 2 + 1;
        if (!(back <= edge)) edge = back;
        if (std::find(met.begin(), met.end(), other) == met.end()) met.push_back(other);
      }
    }
  // One other road that ends there too carries this one on: a bend, not a junction.
  if (met.size() == 1) {
    const geom::Polyline& o = roads[met[0]].line;
    if (geom::distance(o.front(), p) < 0.5 || geom::distance(o.back(), p) < 0.5) return NAN;
  }
  return edge;
}

}  // namespace

// The ground: terrain, then layers a few centimetres above each other; water level at its
// shore height, bridges level between their ends (docs/design.md, Ground meshes).
void RenderScene::add_ground(const exacity::City& city, const geom::Box& world, const Palette& palette) {
  const exacity::Ground& g = city.ground;
  const exacity::Terrain* terrain = city.heightmap();
  const WaterOnward onward = water_onward(g.water, terrain);
  add_terrain(terrain, world, onward.near);
  const exacity::BridgeDecks decks = exacity::bridge_decks(g, terrain);
  std::vector<DrapedPiece> zones, lots, water, road_areas;
  // Zone land no lot covers is gardens, verges and parks: grass. Paving is where people
  // walk, the sidewalks of the road areas.
  for (std::size_t id = 0; id < g.zones.size(); ++id)
    zones.push_back({&g.zones[id].polygon, grass_material_, entity_id(Entity::Zone, id), 0.03});
  for (std::size_t id = 0; id < g.lots.size(); ++id) {
    const ZoneType zone = g.lots[id].zone;
    const int m = palette.lot_ground.count(zone) ? palette.lot_ground.at(zone) : palette.sidewalk;
    lots.push_back({&g.lots[id].polygon, m, entity_id(Entity::Lot, id), 0.06});
  }
  for (std::size_t id = 0; id < g.water.size(); ++id)
    water.push_back({&onward.near[id], palette.water, entity_id(Entity::Water, id), 0.05,
                     exacity::water_level(g.water[id], terrain) + 0.05});
  for (std::size_t i = 0; i < g.road_areas.size(); ++i) {
    const exacity::RoadArea& a = g.road_areas[i];
    // A road surface names the centre line it belongs to; its id is the road's entity.
    // Sidewalks stand a kerb over the carriageway (off bridges), their sides its face.
    const bool sidewalk = a.surface == exacity::RoadSurface::Sidewalk;
    road_areas.push_back({&a.polygon, sidewalk ? palette.sidewalk : palette.asphalt,
                          entity_id(Entity::Road, a.road >= 0 ? static_cast<std::size_t>(a.road) : 0),
                          exacity::kRoadOverTerrain + (sidewalk ? kKerb : 0), a.bridge ? decks.height[i] : NAN});
  }
  for (const auto* pieces : {&zones, &lots, &water, &road_areas}) add_draped(*pieces, terrain);
  add_road_markings(g, decks, terrain, palette);
  add_onward(g, terrain, terrain_box(terrain, world), onward, palette);
  // The decks' sides and undersides and their piers, in the road's asphalt grey.
  exacity::GroundMesh structure;
  std::vector<int> area;
  exacity::bridge_structure(g, terrain, decks, structure, &area);
  if (!structure.triangles.empty()) {
    std::vector<V3> v;
    for (const auto& p : structure.vertices) v.push_back(to_scene(p[0], p[1], p[2]));
    Geometry info;
    info.material.assign(structure.triangles.size(), palette.sidewalk);
    for (int a : area) {
      const int road = g.road_areas[a].road;
      info.entity.push_back(entity_id(Entity::Road, road >= 0 ? static_cast<std::size_t>(road) : 0));
    }
    add_triangles(v, structure.triangles, std::move(info));
  }
}

// The ground reaches a city's size past the city on every side, and past the heightmap
// as far as the terrain takes to sink to its lowest height (Terrain::height_at), so it
// meets the plane beyond, at that height, without a step.
void RenderScene::add_terrain(const exacity::Terrain* terrain, const geom::Box& world,
                              const std::vector<geom::Polygon>& water) {
  const geom::Box near{world.min_x - world.width(), world.min_y - world.height(), world.max_x + world.width(),
                       world.max_y + world.height()};
  // Pixel-sized cells near the city, coarser past it.
  exacity::GroundMesh g = exacity::terrain_mesh(terrain, terrain_box(terrain, world), near, water, 768);
  std::vector<V3> v;
  for (const auto& p : g.vertices) v.push_back(to_scene(p[0], p[1], p[2]));
  Geometry info;
  info.material.assign(g.triangles.size(), grass_material_);
  info.entity.assign(g.triangles.size(), entity_id(Entity::Terrain, 0));
  add_triangles(v, g.triangles, std::move(info));
  // The plane beyond lies at the land's lowest height; the beds under water lie lower, unseen.
  ground = static_cast<float>(terrain ? terrain->lowest() : 0);
}

// The pieces draped over the terrain, as one geometry.
void RenderScene::add_draped(const std::vector<DrapedPiece>& pieces, const exacity::Terrain* terrain) {
  exacity::GroundMesh g;
  Geometry info;
  const exacity::CancelCheck cancel;
  for (const DrapedPiece& piece : pieces) {
    cancel.check();
    if (std::isfinite(piece.level))
      exacity::drape_flat(*piece.polygon, piece.level, g);
    else
      exacity::drape(*piece.polygon, terrain, piece.lift, g), add_sides(*piece.polygon, terrain, piece.lift, g);
    info.material.resize(g.triangles.size(), piece.material);
    info.entity.resize(g.triangles.size(), piece.entity);
  }
  std::vector<V3> v;
  for (const auto& p : g.vertices) v.push_back(to_scene(p[0], p[1], p[2]));
  if (!g.triangles.empty()) add_triangles(v, g.triangles, std::move(info));
}

// A road's centre stripe (solid yellow on highways, dashed white elsewhere) and dashed
// lane lines, `lift` over `under` (flat at `lift` where null).
void RenderScene::add_lines(const exacity::RoadLine& r, const exacity::Terrain* under, double lift,
                            std::uint32_t entity, const Palette& palette, std::vector<V3>& v,
                            std::vector<std::array<int, 3>>& t, Geometry& info) {
  const bool highway = r.road_class == exacity::RoadClass::Highway;
  ribbon(r.line, 0, 0.15, highway ? 0 : 3, 5, under, lift, v, t, *this);
  info.material.resize(t.size(), highway ? palette.yellow : palette.paint);
  if (highway && r.width >= 14)
    for (double side : {-r.width / 4, r.width / 4}) ribbon(r.line, side, 0.12, 3, 6, under, lift, v, t, *this);
  info.material.resize(t.size(), palette.paint);
  info.entity.resize(t.size(), entity);
}

// Every road's lines, on its bridge's deck where it has one, and the crossings.
void RenderScene::add_road_markings(const exacity::Ground& ground, const exacity::BridgeDecks& decks,
                                    const exacity::Terrain* terrain, const Palette& palette) {
  const std::vector<exacity::RoadLine>& roads = ground.roads;
  std::vector<V3> v;
  std::vector<std::array<int, 3>> t;
  Geometry info;
  for (std::size_t id = 0; id < roads.size(); ++id) {
    const exacity::RoadLine& r = roads[id];
    double lift = kMarkingLift;
    const exacity::Terrain* under = terrain;
    if (r.bridge && r.line.size() >= 2) {
      // On its deck: flat, just over the deck's surface.
      const double deck = decks.at(ground, geom::lerp(r.line[0], r.line[1], 0.5));
      if (std::isfinite(deck)) under = nullptr, lift = deck + 0.02;
    }
    add_lines(r, under, lift, entity_id(Entity::Road, id), palette, v, t, info);
  }
  add_crossings(ground, terrain, palette, v, t, info);
  if (!t.empty()) add_triangles(v, t, std::move(info));
}

// Roads and rivers carried on past the city (render/onward.h). A road is draped as the
// city's roads are, in pieces no longer than kPiece over the drawn terrain and one flat
// piece over the plane past it, with sides and lines; the far water lies flat over the
// plane at its water's level, or the plane's where that is higher (the land where the near
// water ends lies there), rising to it from the near water.
void RenderScene::add_onward(const exacity::Ground& ground, const exacity::Terrain* terrain,
                             const geom::Box& drawn, const WaterOnward& water, const Palette& palette) {
  constexpr double kPiece = 250;
  const double plane = terrain ? terrain->lowest() : 0;
  auto inside = [&](geom::Vec2 p) {
    return p.x >= drawn.min_x && p.x <= drawn.max_x && p.y >= drawn.min_y && p.y <= drawn.max_y;
  };
  exacity::GroundMesh g;
  Geometry info;
  std::vector<V3> lines;
  std::vector<std::array<int, 3>> line_triangles;
  Geometry line_info;
  for (const RoadOnward& onward : roads_onward(ground)) {
    const exacity::RoadLine& r = onward.line;
    const geom::Vec2 from = r.line.front(), to = r.line.back();
    const geom::Vec2 u = geom::unit_along(from, to), n = geom::left_normal(from, to);
    const double half = r.width / 2, length = geom::distance(from, to);
    corridors_.push_back({from - geom::Vec2{origin_x, origin_y}, to - geom::Vec2{origin_x, origin_y}, half});
    const std::uint32_t entity = entity_id(Entity::Road, onward.road);
    auto piece = [&](double a, double b) {
      return geom::Polygon{{from + u * a - n * half, from + u * b - n * half, from + u * b + n * half, from + u * a + n * half}, {}};
    };
    // Over the terrain while it is drawn, then flat over the plane.
    double at = 0;
    while (terrain && at < length && inside(from + u * at)) {
      const double end = std::min(at + kPiece, length);
      const geom::Polygon p = piece(at, end);
      exacity::drape(p, terrain, exacity::kRoadOverTerrain, g), add_sides(p, terrain, exacity::kRoadOverTerrain, g);
      exacity::RoadLine stretch = r;
      stretch.line = {from + u * at, from + u * end};
      add_lines(stretch, terrain, kMarkingLift, entity, palette, lines, line_triangles, line_info);
      at = end;
    }
    if (at < length) {
      const geom::Polygon p = piece(at, length);
      const double top = plane + exacity::kRoadOverTerrain;
      exacity::drape_flat(p, top, g);
      exacity::add_wall(p.outer, [&](geom::Vec2) { return top; }, [&](geom::Vec2) { return plane - 0.05; }, g);
      exacity::RoadLine stretch = r;
      stretch.line = {from + u * at, to};
      add_lines(stretch, nullptr, plane + kMarkingLift, entity, palette, lines, line_triangles, line_info);
    }
    info.material.resize(g.triangles.size(), palette.asphalt);
    info.entity.resize(g.triangles.size(), entity);
  }
  for (const auto& [w, p] : water.far) {
    const double level = exacity::water_level(ground.water[w], terrain) + 0.05, top = std::max(level, plane + 0.05);
    exacity::drape_flat(p, top, g);
    if (top > level) {
      // A ramp of kRamp up to it from the near water, which the land where that ends lies
      // under: a step, or a weir, showed as a dark line across the river.
      constexpr double kRamp = 50;
      const geom::Vec2 out = geom::unit_along(p.outer[0], p.outer[1]);
      const geom::Vec2 a = p.outer[0], b = p.outer[3];
      const int first = static_cast<int>(g.vertices.size());
      g.vertices.insert(g.vertices.end(), {{a.x - out.x * kRamp, a.y - out.y * kRamp, level}, {a.x, a.y, top},
                                           {b.x, b.y, top}, {b.x - out.x * kRamp, b.y - out.y * kRamp, level}});
      g.triangles.push_back({first, first + 1, first + 2});
      g.triangles.push_back({first, first + 2, first + 3});
    }
    info.material.resize(g.triangles.size(), palette.water);
    info.entity.resize(g.triangles.size(), entity_id(Entity::Water, w));
    // The corridor from the map's bound, where the near water leaves it.
    const geom::Vec2 out = geom::unit_along(p.outer[0], p.outer[1]);
    const geom::Vec2 a = geom::lerp(p.outer[0], p.outer[3], 0.5) - out * (terrain ? terrain->fade() - WaterOnward::kOverlap : 0);
    const geom::Vec2 b = geom::lerp(p.outer[1], p.outer[2], 0.5);
    corridors_.push_back({a - geom::Vec2{origin_x, origin_y}, b - geom::Vec2{origin_x, origin_y},
                          geom::distance(p.outer[0], p.outer[3]) / 2});
  }
  if (!g.triangles.empty()) {
    std::vector<V3> v;
    for (const auto& p : g.vertices) v.push_back(to_scene(p[0], p[1], p[2]));
    add_triangles(v, g.triangles, std::move(info));
  }
  if (!line_triangles.empty()) add_triangles(lines, line_triangles, std::move(line_info));
}

}  // namespace render

namespace render {

// At every end of a street that meets another road (not on highways or bridges): a zebra
// crossing of 0.5 m stripes 1 m apart, 3 m long, from 1 m back from the crossing road's
// edge, and behind it a 0.4 m stop line across the lane coming in (traffic on the right).
void RenderScene::add_crossings(const exacity::Ground& ground, const exacity::Terrain* terrain, const Palette& palette,
                                std::vector<V3>& v, std::vector<std::array<int, 3>>& t, Geometry& info) {
  const std::vector<exacity::RoadLine>& roads = ground.roads;
  SegmentGrid grid;
  for (std::size_t r = 0; r < roads.size(); ++r)
    for (std::size_t k = 0; k + 1 < roads[r].line.size(); ++k) {
      const geom::Vec2 a = roads[r].line[k], b = roads[r].line[k + 1];
      const auto [x0, y0] = SegmentGrid::cell({std::min(a.x, b.x), std::min(a.y, b.y)});
      const auto [x1, y1] = SegmentGrid::cell({std::max(a.x, b.x), std::max(a.y, b.y)});
      for (long i = x0; i <= x1; ++i)
        for (long j = y0; j <= y1; ++j) grid.cells[{i, j}].push_back({static_cast<int>(r), static_cast<int>(k)});
    }
  constexpr double kLift = 0.12, kZebra = 3, kStop = 0.4;
  for (std::size_t id = 0; id < roads.size(); ++id) {
    const exacity::RoadLine& r = roads[id];
    if (r.road_class == exacity::RoadClass::Highway || r.bridge || r.line.size() < 2 || r.width < 5) continue;
    for (int end = 0; end < 2; ++end) {
      // The line from this end inwards, and its length.
      geom::Polyline from_end = r.line;
      if (end == 1) std::reverse(from_end.begin(), from_end.end());
      double length = 0;
      for (std::size_t k = 0; k + 1 < from_end.size(); ++k) length += geom::distance(from_end[k], from_end[k + 1]);
      const double back = crossing_edge(roads, grid, static_cast<int>(id), from_end[0]);
      if (!std::isfinite(back) || length < back + kZebra + 3) continue;
      // The point `along` the line from the end, `across` to its left there.
      auto at = [&](double along, double across) {
        std::size_t k = 0;
        double a = geom::distance(from_end[0], from_end[1]);
        while (along > a && k + 2 < from_end.size()) along -= a, ++k, a = geom::distance(from_end[k], from_end[k + 1]);
        const geom::Vec2 u = geom::unit_along(from_end[k], from_end[k + 1]), n = geom::left_normal(from_end[k], from_end[k + 1]);
        return geom::Vec2{from_end[k].x + u.x * along + n.x * across, from_end[k].y + u.y * along + n.y * across};
      };
      const double half = r.width / 2 - 0.3;
      for (double across = -half + 0.25; across <= half - 0.25; across += 1)
        ribbon({at(back, across), at(back + kZebra, across)}, 0, 0.5, 0, 0, terrain, kLift, v, t, *this);
      // Coming in towards this end, the right-hand lane is on this direction's left.
      ribbon({at(back + kZebra + 1, 0.1), at(back + kZebra + 1, half)}, 0, kStop, 0, 0, terrain, kLift, v, t, *this);
    }
    info.material.resize(t.size(), palette.paint);
    info.entity.resize(t.size(), entity_id(Entity::Road, id));
  }
}

}  // namespace render
