// The scene's ground: the terrain, the ground layers draped over it, the road markings
// and the bridges' structure.
#include <cmath>

#include "generate/cancel.h"
#include "generate/mesh/bridges.h"
#include "generate/mesh/ground_mesh.h"
#include "geom/measure.h"
#include "render/scene_build.h"

namespace render {

using exacity::ZoneType;

namespace {

constexpr double kKerb = 0.12;  // m: a sidewalk's height over the carriageway

// A ribbon of `width` along a ground path, its corners draped over the terrain, in pieces
// no longer than half a pixel; dashes where `dash` > 0 (dash on, gap off, metres).
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
        auto corner = [&](double at, double side) {
          double x = a.x + ux * at + nx * (offset + side), y = a.y + uy * at + ny * (offset + side);
          double z = (terrain ? terrain->height_at({x, y}) : 0) + lift;
          return s.to_scene(x, y, z);
        };
        const int first = static_cast<int>(verts.size());
        verts.insert(verts.end(),
                     {corner(t, -width / 2), corner(end, -width / 2), corner(end, width / 2), corner(t, width / 2)});
        tris.push_back({first, first + 1, first + 2});
        tris.push_back({first, first + 2, first + 3});
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

}  // namespace

// The ground: terrain, then layers a few centimetres above each other; water level at its
// shore height, bridges level between their ends (docs/design.md, Ground meshes).
void RenderScene::add_ground(const exacity::City& city, const geom::Box& world, const Palette& palette) {
  const exacity::Ground& g = city.ground;
  const exacity::Terrain* terrain = city.heightmap();
  add_terrain(terrain, world, g.water);
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
    water.push_back({&g.water[id], palette.water, entity_id(Entity::Water, id), 0.05,
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
  geom::Box wide = near;
  if (terrain) {
    const geom::Box& b = terrain->bounds();
    const double f = terrain->fade();
    wide.add(geom::Box{b.min_x - f, b.min_y - f, b.max_x + f, b.max_y + f});
  }
  // Pixel-sized cells near the city, coarser past it.
  exacity::GroundMesh g = exacity::terrain_mesh(terrain, terrain ? wide : world, near, water, 768);
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

// Centre stripes (solid yellow on highways, dashed white elsewhere) and dashed lane lines.
void RenderScene::add_road_markings(const exacity::Ground& ground, const exacity::BridgeDecks& decks,
                                    const exacity::Terrain* terrain, const Palette& palette) {
  const std::vector<exacity::RoadLine>& roads = ground.roads;
  std::vector<V3> v;
  std::vector<std::array<int, 3>> t;
  Geometry info;
  for (std::size_t id = 0; id < roads.size(); ++id) {
    const exacity::RoadLine& r = roads[id];
    const bool highway = r.road_class == exacity::RoadClass::Highway;
    const double width = r.width;
    double lift = 0.12;
    const exacity::Terrain* under = terrain;
    if (r.bridge && r.line.size() >= 2) {
      // On its deck: flat, just over the deck's surface.
      const double deck = decks.at(ground, geom::lerp(r.line[0], r.line[1], 0.5));
      if (std::isfinite(deck)) under = nullptr, lift = deck + 0.02;
    }
    ribbon(r.line, 0, 0.15, highway ? 0 : 3, 5, under, lift, v, t, *this);
    info.material.resize(t.size(), highway ? palette.yellow : palette.paint);
    if (highway && width >= 14)
      for (double side : {-width / 4, width / 4}) ribbon(r.line, side, 0.12, 3, 6, under, lift, v, t, *this);
    info.material.resize(t.size(), palette.paint);
    info.entity.resize(t.size(), entity_id(Entity::Road, id));
  }
  if (!t.empty()) add_triangles(v, t, std::move(info));
}

}  // namespace render
