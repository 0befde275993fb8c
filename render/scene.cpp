#include "render/scene.h"

#include <cassert>
#include <cmath>
#include <map>
#include <stdexcept>

#include "generate/cancel.h"
#include "generate/mesh/building_mesh.h"
#include "generate/mesh/bridges.h"
#include "generate/mesh/ground_mesh.h"
#include "generate/city/palette.h"
#include "generate/city/random.h"
#include "render/noise.h"
#include "render/paving.h"

namespace render {

struct Plane {
  V3 n;
  float d;  // inside where dot(n, p) + d >= 0
};

// A box in scene coordinates.
struct Box3 {
  V3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  void add(V3 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)},
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void add(const Box3& b) { add(b.lo), add(b.hi); }
  bool outside(const Plane& p) const {
    V3 far{p.n.x >= 0 ? hi.x : lo.x, p.n.y >= 0 ? hi.y : lo.y, p.n.z >= 0 ? hi.z : lo.z};
    return dot(p.n, far) + p.d < 0;
  }
};

namespace {

using exacity::ZoneType;

V3 colour(const exacity::Colour& c) {
  return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

V3 colour(const exacity::Albedo& a) { return {a[0], a[1], a[2]}; }

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


// The four side planes of the camera's view, facing in.
std::vector<Plane> frustum(const Camera& c, float aspect) {
  const V3 f = c.forward(), r = c.right(), u = cross(r, f);
  std::vector<Plane> planes;
  auto add = [&](V3 n, V3 p) { planes.push_back({n, -dot(n, p)}); };
  if (c.orthographic) {
    const float hh = c.ortho_height / 2, hw = hh * aspect;
    add(r, c.from - r * hw), add(r * -1, c.from + r * hw), add(u, c.from - u * hh), add(u * -1, c.from + u * hh);
    return planes;
  }
  const float t = std::tan(c.fov_y * kPi / 360), ta = t * aspect;
  // A side plane holds the camera and the two corner directions on that side.
  const V3 tl = f + r * -ta + u * t, tr = f + r * ta + u * t, bl = f + r * -ta + u * -t, br = f + r * ta + u * -t;
  add(normalize(cross(bl, tl)), c.from), add(normalize(cross(tr, br)), c.from);
  add(normalize(cross(tl, tr)), c.from), add(normalize(cross(br, bl)), c.from);
  return planes;
}

// A bounding volume hierarchy over tile boxes, for the tiles a frustum can see.
class TileBvh {
 public:
  explicit TileBvh(const std::vector<Box3>& boxes) : boxes_(boxes) {
    std::vector<int> ids;
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
      if (boxes[i].lo.x <= boxes[i].hi.x) ids.push_back(i);
    if (!ids.empty()) build(ids, 0, static_cast<int>(ids.size()));
  }
  void visible(const std::vector<Plane>& planes, std::vector<bool>& seen) const {
    if (!nodes_.empty()) visit(0, planes, seen);
  }

 private:
  struct Node {
    Box3 box;
    int left = -1, right = -1, tile = -1;
  };
  int build(std::vector<int>& ids, int begin, int end) {
    Node node;
    for (int i = begin; i < end; ++i) node.box.add(boxes_[ids[i]]);
    const int at = static_cast<int>(nodes_.size());
    nodes_.push_back(node);
    if (end - begin == 1) {
      nodes_[at].tile = ids[begin];
      return at;
    }
    const V3 size = node.box.hi - node.box.lo;
    const int axis = size.x >= size.y ? 0 : 1;
    const int mid = (begin + end) / 2;
    std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end, [&](int a, int b) {
      return (boxes_[a].lo[axis] + boxes_[a].hi[axis]) < (boxes_[b].lo[axis] + boxes_[b].hi[axis]);
    });
    const int left = build(ids, begin, mid), right = build(ids, mid, end);
    nodes_[at].left = left, nodes_[at].right = right;
    return at;
  }
  void visit(int n, const std::vector<Plane>& planes, std::vector<bool>& seen) const {
    for (const Plane& p : planes)
      if (nodes_[n].box.outside(p)) return;
    if (nodes_[n].tile >= 0) {
      seen[nodes_[n].tile] = true;
      return;
    }
    visit(nodes_[n].left, planes, seen), visit(nodes_[n].right, planes, seen);
  }
  const std::vector<Box3>& boxes_;
  std::vector<Node> nodes_;
};

RTCRayHit ray_hit(V3 o, V3 d, float tmax) {
  RTCRayHit rh{};
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = 0, rh.ray.tfar = tmax, rh.ray.mask = 0xffffffff;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

const Noise& noise() {
  static const Noise n;
  return n;
}

}  // namespace

// The materials of the ground and of buildings, as indices.
struct RenderScene::Palette {
  int sidewalk = 0, asphalt = 0, paint = 0, yellow = 0, water = 0;
  std::map<ZoneType, int> lot_ground;
  std::map<std::pair<ZoneType, int>, int> facade, roof;  // (zone, palette entry)
};

struct RenderScene::Geometry {
  std::vector<int> material;          // per triangle; for instances, per model triangle
  std::vector<std::uint32_t> entity;  // per triangle; empty for instances
  // Instances: their entity, the offset into the materials of their colour variant, and
  // the turn that takes the model's normals into the city.
  bool instance = false;
  std::uint32_t instance_entity = 0;
  int material_base = 0;
  float cos_turn = 1, sin_turn = 0;
  // Instances of a textured model: its corners' texture coordinates, per model triangle.
  const std::vector<std::array<exacity::Uv, 3>>* uv = nullptr;
};

unsigned RenderScene::add_triangles(const std::vector<V3>& vertices, const std::vector<std::array<int, 3>>& tris,
                                    Geometry info) {
  RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      device_.new_buffer(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i)
    v[3 * i] = vertices[i].x, v[3 * i + 1] = vertices[i].y, v[3 * i + 2] = vertices[i].z;
  auto* t = static_cast<unsigned*>(
      device_.new_buffer(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) t[3 * i + k] = static_cast<unsigned>(tris[i][k]);
  rtcCommitGeometry(g);
  unsigned id = rtcAttachGeometry(scene_, g);
  rtcReleaseGeometry(g);
  device_.check("a mesh");
  if (geometries_.size() <= id) geometries_.resize(id + 1);
  geometries_[id] = std::move(info);
  triangles += tris.size();
  return id;
}

RenderScene::RenderScene(const std::vector<TriangleSoup>& soups, bool ground_plane)
    : scene_(rtcNewScene(device_.get())), ground_plane_(ground_plane) {
  bounds = geom::Box::none();
  for (const TriangleSoup& s : soups) {
    materials_.push_back(s.material);
    patterns_.push_back(Pattern::None);
    Geometry info;
    info.material.assign(s.triangles.size(), static_cast<int>(materials_.size()) - 1);
    info.entity.assign(s.triangles.size(), s.entity);
    for (V3 p : s.vertices) bounds.add(geom::Vec2{p.x, p.y}), top = std::max(top, p.z);
    add_triangles(s.vertices, s.triangles, std::move(info));
  }
  materials_.push_back({Material::Diffuse, colour(exacity::kGrassAlbedo)});
  patterns_.push_back(Pattern::Grass);
  grass_material_ = static_cast<int>(materials_.size()) - 1;
  rtcCommitScene(scene_);
  device_.check("the scene");
}

namespace {

// Embree's build of a large city's scene takes a while: its progress monitor stops it once
// the job is cancelled (generate/cancel.h), and the cancel is then thrown here.
void commit_cancellable(RTCScene scene) {
  exacity::CancelCheck cancel;
  rtcSetSceneProgressMonitorFunction(
      scene,
      [](void* check, double) {
        try {
          static_cast<const exacity::CancelCheck*>(check)->check();
          return true;
        } catch (const exacity::Cancelled&) {
          return false;
        }
      },
      &cancel);
  rtcCommitScene(scene);
  rtcSetSceneProgressMonitorFunction(scene, nullptr, nullptr);
  cancel.check();
}

}  // namespace

RenderScene::RenderScene(const exacity::City& city, V3 sun, const SceneOptions& options)
    : scene_(rtcNewScene(device_.get())), ground_plane_(options.ground_plane) {
  try {
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    build(city, sun, options);
    commit_cancellable(scene_);
    device_.check("the city's scene");
  } catch (...) {
    release();  // no destructor runs for a constructor that throws
    throw;
  }
}

RenderScene::~RenderScene() { release(); }

void RenderScene::release() {
  if (scene_) rtcReleaseScene(scene_);
  for (RTCScene s : model_scenes_)
    if (s) rtcReleaseScene(s);
  scene_ = nullptr, model_scenes_.clear();
}

void RenderScene::build(const exacity::City& city, V3 sun, const SceneOptions& options) {
  geom::Box world = city.ground.bounds();
  if (world.holds_nothing()) world = {0, 0, 1, 1};
  const geom::Vec2 origin = exacity::local_origin(world);
  origin_x = origin.x, origin_y = origin.y;
  bounds = {world.min_x - origin_x, world.min_y - origin_y, world.max_x - origin_x, world.max_y - origin_y};

  Palette palette;
  make_palette(palette);
  add_ground(city, world, palette);
  add_buildings(city, world, sun, options, palette);
}

int RenderScene::add_material(Material m, Pattern p) {
  materials_.push_back(m);
  patterns_.push_back(p);
  return static_cast<int>(materials_.size()) - 1;
}

void RenderScene::make_palette(Palette& p) {
  grass_material_ = add_material({Material::Diffuse, colour(exacity::kGrassAlbedo)}, Pattern::Grass);
  p.sidewalk = add_material({Material::Diffuse, colour(exacity::kSidewalkAlbedo)}, Pattern::Paving);
  p.asphalt = add_material({Material::Diffuse, colour(exacity::kAsphaltAlbedo)});
  p.paint = add_material({Material::Diffuse, colour(exacity::kPaintAlbedo)});
  p.yellow = add_material({Material::Diffuse, colour(exacity::kYellowPaintAlbedo)});
  p.water = add_material({Material::Glossy, colour(exacity::kWaterAlbedo), 0.02f, 1.33f});
  p.lot_ground = {{ZoneType::Residential, grass_material_},
                  {ZoneType::Commercial,
                   add_material({Material::Diffuse, colour(exacity::kCommercialLotAlbedo)}, Pattern::Paving)},
                  {ZoneType::Industrial, add_material({Material::Diffuse, colour(exacity::kIndustrialLotAlbedo)})}};
  for (ZoneType z : {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial}) {
    for (int i = 0; i < static_cast<int>(exacity::facade_albedos(z).size()); ++i)
      p.facade[{z, i}] = add_material({Material::Diffuse, colour(exacity::facade_albedos(z)[i])}, Pattern::Windows);
    for (int i = 0; i < static_cast<int>(exacity::roof_albedos(z).size()); ++i)
      p.roof[{z, i}] = add_material({Material::Diffuse, colour(exacity::roof_albedos(z)[i])}, Pattern::Roof);
  }
}

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
    const int material = a.surface == exacity::RoadSurface::Sidewalk ? palette.sidewalk : palette.asphalt;
    road_areas.push_back({&a.polygon, material, entity_id(Entity::Road, a.road >= 0 ? static_cast<std::size_t>(a.road) : 0),
                          exacity::kRoadOverTerrain, a.bridge ? decks.height[i] : NAN});
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
  ground = INFINITY;
  for (const V3& p : v) ground = std::min(ground, p.z);
  if (terrain) ground = static_cast<float>(terrain->lowest());  // the beds under water lie lower, unseen
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
      exacity::drape(*piece.polygon, terrain, piece.lift, g);
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

// Building and model tiles: each structure's tile (by id) and each tile's box.
struct RenderScene::StructureTiles {
  int nx = 1, ny = 1;
  std::vector<int> tile_of;
  std::vector<int> clutter_tile;  // by clutter id
  std::vector<Box3> boxes;
};

// Each tile's state in one view.
struct RenderScene::TileView {
  std::vector<bool> seen, detailed;
};

// Per library model: the first of its materials (its tints follow each other) and its
// triangles' material indices.
struct RenderScene::ModelMaterials {
  std::vector<int> base;
  std::vector<std::vector<int>> local;
};

namespace {

// Triangles gathered per tile before they become one Embree geometry each.
struct TileMeshes {
  std::vector<std::vector<V3>> vertices;
  std::vector<std::vector<std::array<int, 3>>> triangles;
};

// Shadows reach in from outside the view: grows each box towards the sun by its shadow.
void grow_towards_sun(std::vector<Box3>& boxes, V3 sun) {
  const float sun_run = sun.z > 0.05f ? std::min(600.0f, 1.0f / std::tan(std::asin(sun.z))) : 600.0f;
  for (Box3& b : boxes)
    if (b.lo.x <= b.hi.x) {
      const float reach = (b.hi.z - b.lo.z) * sun_run;
      b.add(b.lo + V3{sun.x, sun.y, 0} * reach), b.add(b.hi + V3{sun.x, sun.y, 0} * reach);
    }
}

}  // namespace

// Buildings by tile, culled and given their level.
void RenderScene::add_buildings(const exacity::City& city, const geom::Box& world, V3 sun, const SceneOptions& options,
                                const Palette& palette) {
  StructureTiles tiles = tile_structures(city, world, options.tile_size);
  grow_towards_sun(tiles.boxes, sun);
  const TileView view = view_tiles(tiles.boxes, options);
  const ModelMaterials model_materials = add_model_materials(city.model_library());

  TileMeshes meshes{std::vector<std::vector<V3>>(tiles.boxes.size()),
                    std::vector<std::vector<std::array<int, 3>>>(tiles.boxes.size())};
  std::vector<Geometry> tile_info(tiles.boxes.size());
  facades_.assign(city.buildings.size() + city.models.size(), FacadeStyle{});
  // `eaves`: where the walls end, from the ground (their windows end below).
  auto add_mesh = [&](int id, exacity::ZoneType zone, const exacity::Mesh& mesh, double floor, double eaves) {
    facades_[id] = facade_style(zone, city.settings.seed, id, static_cast<float>(floor), static_cast<float>(eaves));
    const int k = tiles.tile_of[id];
    exacity::Random pick(exacity::mix(city.settings.seed, static_cast<std::uint64_t>(id)));
    const int f = palette.facade.at({zone, static_cast<int>(pick.next() % exacity::facade_albedos(zone).size())});
    const int r = palette.roof.at({zone, static_cast<int>(pick.next() % exacity::roof_albedos(zone).size())});
    const exacity::MeshTriangles tris = exacity::mesh_triangles(mesh);
    const int first = static_cast<int>(meshes.vertices[k].size());
    for (const auto& p : tris.vertices) meshes.vertices[k].push_back(to_scene(p[0], p[1], p[2]));
    for (std::size_t j = 0; j < tris.triangles.size(); ++j) {
      const auto& t = tris.triangles[j];
      meshes.triangles[k].push_back({first + t[0], first + t[1], first + t[2]});
      tile_info[k].material.push_back(tris.surface[j] == exacity::Surface::Roof   ? r
                                      : tris.surface[j] == exacity::Surface::Wall ? f
                                                                                  : palette.sidewalk);
      tile_info[k].entity.push_back(entity_id(Entity::Building, static_cast<std::size_t>(id)));
    }
  };
  const exacity::CancelCheck cancel;
  exacity::for_each_by_id(
      city.buildings, city.models,
      [&](const exacity::Building& b) {
        cancel.check();
        const int k = tiles.tile_of[b.id];
        if (!view.seen[k]) return;
        if (view.detailed[k]) return add_mesh(b.id, b.zone, exacity::building_mesh(b), b.floor, b.floor + b.eaves);
        exacity::Building box = b;  // the simple level: the footprint extruded, no roof
        box.roof_faces.clear();
        box.eaves = box.height;
        add_mesh(b.id, b.zone, exacity::building_mesh(box), b.floor, b.floor + b.height);
      },
      [&](const exacity::ModelInstance& m) {
        cancel.check();
        const int k = tiles.tile_of[m.id];
        if (!view.seen[k]) return;
        if (!view.detailed[k] && m.kind != exacity::ModelKind::Building) return;
        add_instance(m, *city.model_library(), model_materials);
        // Its foundation, below its floor: no windows.
        if (m.floor > m.base) add_mesh(m.id, m.zone, exacity::model_mesh(m, nullptr), m.floor, m.floor);
      });
  // Street clutter, like lot furniture: an instance each in the detailed tiles seen.
  for (std::size_t i = 0; i < city.clutter.items.size(); ++i) {
    const int k = tiles.clutter_tile[i];
    if (view.seen[k] && view.detailed[k])
      add_instance(city.clutter.items[i].instance, *city.model_library(), model_materials, Entity::Clutter);
  }
  for (std::size_t k = 0; k < tiles.boxes.size(); ++k)
    if (!meshes.triangles[k].empty()) add_triangles(meshes.vertices[k], meshes.triangles[k], std::move(tile_info[k]));
}

RenderScene::StructureTiles RenderScene::tile_structures(const exacity::City& city, const geom::Box& world, float tile_size) {
  StructureTiles tiles;
  tiles.nx = std::max(1, static_cast<int>(std::ceil(world.width() / tile_size)));
  tiles.ny = std::max(1, static_cast<int>(std::ceil(world.height() / tile_size)));
  tiles.tile_of.resize(city.buildings.size() + city.models.size());
  tiles.boxes.resize(static_cast<std::size_t>(tiles.nx * tiles.ny));
  // The tile of a structure's polygon, which grows to hold it from base to top_z.
  auto place = [&](const geom::Polygon& polygon, double base, double top_z) {
    geom::Box fb = geom::Box::none();
    for (auto p : polygon.outer) fb.add(p);
    const double cx = (fb.min_x + fb.max_x) / 2, cy = (fb.min_y + fb.max_y) / 2;
    const int tx = std::clamp(static_cast<int>((cx - world.min_x) / tile_size), 0, tiles.nx - 1);
    const int ty = std::clamp(static_cast<int>((cy - world.min_y) / tile_size), 0, tiles.ny - 1);
    const int k = ty * tiles.nx + tx;
    tiles.boxes[k].add(to_scene(fb.min_x, fb.min_y, base));
    tiles.boxes[k].add(to_scene(fb.max_x, fb.max_y, top_z));
    top = std::max(top, static_cast<float>(top_z));
    return k;
  };
  exacity::for_each_by_id(
      city.buildings, city.models,
      [&](const exacity::Building& b) { tiles.tile_of[b.id] = place(b.polygon, b.base, b.floor + b.height); },
      [&](const exacity::ModelInstance& m) { tiles.tile_of[m.id] = place(m.polygon, m.base, m.floor + m.height); });
  for (const exacity::Clutter& c : city.clutter.items)
    tiles.clutter_tile.push_back(place(c.instance.polygon, c.instance.base, c.instance.floor + c.instance.height));
  return tiles;
}

// Which tiles the view sees and which are near enough to be detailed; each non-empty
// tile's level is recorded in `tiles`.
RenderScene::TileView RenderScene::view_tiles(const std::vector<Box3>& boxes, const SceneOptions& options) {
  TileView v{std::vector<bool>(boxes.size(), options.view == nullptr), std::vector<bool>(boxes.size(), true)};
  Camera view;
  if (options.view) {
    view = to_scene(*options.view);
    TileBvh(boxes).visible(frustum(view, options.aspect), v.seen);
  }
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    if (boxes[k].lo.x > boxes[k].hi.x) continue;  // empty
    if (options.view) {
      const V3 c = (boxes[k].lo + boxes[k].hi) * 0.5f;
      v.detailed[k] = length(c - view.from) <= options.detail_distance;
    }
    tiles.push_back({static_cast<int>(k), !v.seen[k] ? "culled" : v.detailed[k] ? "detailed" : "simple"});
  }
  return v;
}

RenderScene::ModelMaterials RenderScene::add_model_materials(const exacity::ModelLibrary* library) {
  ModelMaterials out;
  if (!library) return out;
  model_scenes_.assign(library->models.size(), nullptr);
  for (const auto& m : library->models) {
    out.base.push_back(static_cast<int>(materials_.size()));
    for (int tint = 0; tint < exacity::kTints; ++tint)
      for (const auto& mat : m.mesh.materials) {
        const bool glass = mat.name.find("glass") != std::string::npos || mat.name.find("window") != std::string::npos;
        const int index = add_material(
            {glass ? Material::Glossy : Material::Diffuse, colour(exacity::tinted(mat.colour, tint)), 0.05f, 1.5f});
        if (!mat.texture) continue;
        // The texture times the material's colour, as the MTL's map_Kd and Kd combine.
        std::unique_ptr<Texture>& texture = textures_[mat.texture.get()];
        if (!texture) texture = std::make_unique<Texture>(*mat.texture);
        material_textures_.resize(materials_.size());
        material_textures_[index] = {texture.get(), mat.clamp};
      }
    out.local.push_back(m.mesh.material);
  }
  return out;
}

// The model's own scene, made the first time it is placed.
RTCScene RenderScene::model_scene(const exacity::ModelLibrary& library, int model) {
  if (model_scenes_[model]) return model_scenes_[model];
  const exacity::TriangleMesh& mesh = library.models[model].mesh;
  RTCScene ms = model_scenes_[model] = rtcNewScene(device_.get());  // released with the others if this throws
  RTCGeometry g = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      device_.new_buffer(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
  for (std::size_t j = 0; j < mesh.vertices.size(); ++j)
    for (int c = 0; c < 3; ++c) v[3 * j + c] = static_cast<float>(mesh.vertices[j][c]);
  auto* t = static_cast<unsigned*>(
      device_.new_buffer(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
  for (std::size_t j = 0; j < mesh.triangles.size(); ++j)
    for (int c = 0; c < 3; ++c) t[3 * j + c] = static_cast<unsigned>(mesh.triangles[j][c]);
  rtcCommitGeometry(g);
  rtcAttachGeometry(ms, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(ms);
  device_.check("a model's scene");
  return ms;
}

// An instance of the model's scene in the top scene, turned, scaled and moved into place.
void RenderScene::add_instance(const exacity::ModelInstance& m, const exacity::ModelLibrary& library,
                               const ModelMaterials& materials, Entity entity) {
  const exacity::Model& model = library.models[m.placed.model];
  RTCGeometry inst = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(inst, model_scene(library, m.placed.model));
  const float c = std::cos(static_cast<float>(m.placed.angle)) * static_cast<float>(m.placed.scale);
  const float s = std::sin(static_cast<float>(m.placed.angle)) * static_cast<float>(m.placed.scale);
  const V3 at = to_scene(m.placed.position.x, m.placed.position.y, m.floor);
  const float sc = static_cast<float>(m.placed.scale);
  // Column-major 3x4: the turn and scale, then the translation.
  const float xfm[12] = {c, s, 0, -s, c, 0, 0, 0, sc, at.x, at.y, at.z};
  rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
  rtcCommitGeometry(inst);
  unsigned id = rtcAttachGeometry(scene_, inst);
  rtcReleaseGeometry(inst);
  device_.check("a model's instance");
  Geometry info;
  info.instance = true;
  info.instance_entity = entity_id(entity, static_cast<std::size_t>(m.id));
  info.material_base = materials.base[m.placed.model] + m.placed.tint * static_cast<int>(model.mesh.materials.size());
  info.material = materials.local[m.placed.model];
  info.cos_turn = std::cos(static_cast<float>(m.placed.angle)), info.sin_turn = std::sin(static_cast<float>(m.placed.angle));
  if (model.mesh.textured()) info.uv = &model.mesh.uv;
  if (geometries_.size() <= id) geometries_.resize(id + 1);
  geometries_[id] = std::move(info);
  ++instances;
}

bool RenderScene::raw_intersect(V3 o, V3 d) const {
  RTCRayHit rh = ray_hit(o, d, INFINITY);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene_, &context, &rh);
  return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

// What Embree reports of a ray's nearest hit; geom is RTC_INVALID_GEOMETRY_ID on a miss.
struct RenderScene::Hit {
  unsigned geom, prim, inst;
  float t, u, v;
  V3 ng;
};

bool RenderScene::intersect(V3 o, V3 d, float tmax, Surface& s) const {
  RTCRayHit rh = ray_hit(o, d, tmax);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene_, &context, &rh);
  const Hit hit{rh.hit.geomID, rh.hit.primID, rh.hit.instID[0], rh.ray.tfar, rh.hit.u, rh.hit.v,
                {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z}};
  return surface(o, d, tmax, hit, s);
}

void RenderScene::intersect_packet(const V3* o, const V3* d, int count, Surface* hits, bool* found) const {
  assert(count >= 0 && count <= kPacket);
  if (!device_.packets()) {
    for (int i = 0; i < count; ++i) found[i] = intersect(o[i], d[i], INFINITY, hits[i]);
    return;
  }
  alignas(64) int valid[kPacket];
  alignas(64) RTCRayHit16 rh{};
  for (int i = 0; i < kPacket; ++i) {
    valid[i] = i < count ? -1 : 0;
    const V3 oi = o[i < count ? i : 0], di = d[i < count ? i : 0];
    rh.ray.org_x[i] = oi.x, rh.ray.org_y[i] = oi.y, rh.ray.org_z[i] = oi.z;
    rh.ray.dir_x[i] = di.x, rh.ray.dir_y[i] = di.y, rh.ray.dir_z[i] = di.z;
    rh.ray.tnear[i] = 0, rh.ray.tfar[i] = INFINITY, rh.ray.mask[i] = 0xffffffff;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect16(valid, scene_, &context, &rh);
  for (int i = 0; i < count; ++i) {
    const Hit hit{rh.hit.geomID[i], rh.hit.primID[i], rh.hit.instID[0][i], rh.ray.tfar[i], rh.hit.u[i], rh.hit.v[i],
                  {rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]}};
    found[i] = surface(o[i], d[i], INFINITY, hit, hits[i]);
  }
}

// The surface a ray met, from Embree's hit, or the ground plane past the city.
bool RenderScene::surface(V3 o, V3 d, float tmax, const Hit& hit, Surface& s) const {
  int m;
  const std::array<exacity::Uv, 3>* textured = nullptr;  // the hit triangle's texture coordinates
  float hit_u = 0, hit_v = 0;                            // and its barycentric place in it
  if (hit.geom == RTC_INVALID_GEOMETRY_ID) {
    // The ground plane beyond the city.
    if (!ground_plane_ || d.z >= 0 || o.z <= ground) return false;
    const float t = (ground - o.z) / d.z;
    if (t > tmax) return false;
    s.distance = t;
    s.position = o + d * t;
    s.normal = {0, 0, 1};
    s.entity = entity_id(Entity::Terrain, 0);
    m = grass_material_;
  } else {
    s.distance = hit.t;
    s.position = o + d * hit.t;
    V3 n = hit.ng;
    if (hit.inst != RTC_INVALID_GEOMETRY_ID) {
      const Geometry& g = geometries_[hit.inst];
      n = {g.cos_turn * n.x - g.sin_turn * n.y, g.sin_turn * n.x + g.cos_turn * n.y, n.z};
      m = g.material_base + g.material[hit.prim];
      s.entity = g.instance_entity;
      if (g.uv) textured = &(*g.uv)[hit.prim], hit_u = hit.u, hit_v = hit.v;
    } else {
      const Geometry& g = geometries_[hit.geom];
      m = g.material[hit.prim];
      s.entity = g.entity[hit.prim];
    }
    s.normal = normalize(n);
    if (dot(s.normal, d) > 0) s.normal = s.normal * -1;
  }
  s.material = materials_[m];
  if (textured && static_cast<std::size_t>(m) < material_textures_.size() && material_textures_[m].texture) {
    // Embree's u and v weigh the triangle's second and third corners.
    const exacity::Uv& a = (*textured)[0];
    const exacity::Uv& b = (*textured)[1];
    const exacity::Uv& c = (*textured)[2];
    const float w = 1 - hit_u - hit_v;
    const float u = static_cast<float>(w * a[0] + hit_u * b[0] + hit_v * c[0]);
    const float v = static_cast<float>(w * a[1] + hit_u * b[1] + hit_v * c[1]);
    s.material.albedo = s.material.albedo * material_textures_[m].texture->sample(u, v, material_textures_[m].clamp);
  }
  switch (patterns_[m]) {
    case Pattern::Windows: {
      // The building's own rows and bays (render/facade.h); a soup's walls keep the default.
      const std::size_t id = s.entity & 0xffffff;
      const FacadeStyle style = id < facades_.size() ? facades_[id] : FacadeStyle{};
      s.material = facade_material(style, s.material, s.position, s.normal);
      break;
    }
    case Pattern::Roof:
      s.material = roof_material(s.material, s.position, s.normal);
      break;
    case Pattern::Paving:
      s.material = paving_material(s.material, s.position);
      break;
    case Pattern::Grass: {
      const float coarse = noise().fractal(s.position.x * 0.02f, s.position.y * 0.02f, 2);
      const float fine = noise()(s.position.x * 0.9f, s.position.y * 0.9f);
      const V3 lush = colour(exacity::kLushGrassAlbedo), dry = colour(exacity::kDryGrassAlbedo);
      const float t = std::clamp(0.5f + coarse * 1.2f, 0.0f, 1.0f);
      s.material.albedo = (lush * (1 - t) + dry * t) * (0.85f + 0.3f * fine);
      break;
    }
    case Pattern::None:
      break;
  }
  return true;
}

// The ground plane past the city blocks a ray that goes down to it within tmax.
bool RenderScene::meets_ground_plane(V3 o, V3 d, float tmax) const {
  return ground_plane_ && d.z < 0 && o.z > ground && (ground - o.z) / d.z < tmax;
}

void RenderScene::occluded_packet(const V3* o, const V3* d, int count, bool* blocked) const {
  assert(count >= 0 && count <= kPacket);
  if (count == 0) return;  // camera rays that met no surface the sun lights: no call to make
  if (!device_.packets()) {
    for (int i = 0; i < count; ++i) blocked[i] = occluded(o[i], d[i], INFINITY);
    return;
  }
  alignas(64) int valid[kPacket];
  alignas(64) RTCRay16 r{};
  for (int i = 0; i < kPacket; ++i) {
    const bool traced = i < count && !meets_ground_plane(o[i], d[i], INFINITY);
    valid[i] = traced ? -1 : 0;
    const V3 oi = o[i < count ? i : 0], di = d[i < count ? i : 0];
    r.org_x[i] = oi.x, r.org_y[i] = oi.y, r.org_z[i] = oi.z;
    r.dir_x[i] = di.x, r.dir_y[i] = di.y, r.dir_z[i] = di.z;
    r.tnear[i] = 0, r.tfar[i] = traced ? INFINITY : -INFINITY, r.mask[i] = 0xffffffff;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded16(valid, scene_, &context, &r);
  for (int i = 0; i < count; ++i) blocked[i] = r.tfar[i] < 0;  // Embree sets tfar to -inf on a hit
}

bool RenderScene::occluded(V3 o, V3 d, float tmax) const {
  if (meets_ground_plane(o, d, tmax)) return true;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r{};
  r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
  r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
  r.tnear = 0, r.tfar = tmax, r.mask = 0xffffffff;
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0;  // Embree sets tfar to -inf on a hit
}

}  // namespace render
