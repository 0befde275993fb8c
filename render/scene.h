// The Embree scene of a city, built from the city in memory: the terrain and the ground
// layers draped over it (zones as sidewalks, lots, water, roads with a centre stripe and
// lane markings), building meshes merged per city tile, and each placed model stored once
// as its own scene and placed by an instance in the top scene (Debian's Embree allows one
// instance level). Tiles outside the view frustum stay out (a BVH over tile boxes finds
// them); distant tiles get a simpler level. Every hit maps back to its city entity. Its
// parts live in render/scene*.cpp, one concept each (render/scene_build.h lists them), and
// render/tile_culling.h.
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "generate/city.h"
#include "generate/mesh/bridges.h"
#include "render/camera.h"
#include "render/embree_device.h"
#include "render/facade.h"
#include "render/landscape.h"
#include "render/onward.h"
#include "render/material.h"
#include "render/night.h"
#include "render/texture.h"

namespace render {

// The id layer: the entity kind in the top byte, its index (a building, lot, road or
// zone feature id) below.
enum class Entity : std::uint32_t {
  None = 0,
  Building = 1,
  Model = 2,
  Lot = 3,
  Road = 4,
  Zone = 5,
  Water = 6,
  Terrain = 7,
  Clutter = 8,  // street clutter, by its id in vector/clutter.geojson
  Landscape = 9  // the woods' and hedgerows' trees beyond the city (render/landscape.h), by their number
};
inline std::uint32_t entity_id(Entity kind, std::size_t index) {
  return static_cast<std::uint32_t>(kind) << 24 | static_cast<std::uint32_t>(index & 0xffffff);
}

struct Box3;
struct Plane;

// A surface's look before its pattern: windows on facades (render/facade.h), tiles or
// gravel on roofs, slabs where people walk (render/paving.h), grass on open ground.
enum class Pattern : std::uint8_t { None, Windows, Roof, Paving, Grass };

struct Surface {
  V3 position, normal;  // the normal faces the incoming ray
  Material material;
  // The light a diffusely scattered ray takes here: the material's emission, but on a wall
  // with lit windows their light spread over it (render/facade.h, spread_window_light).
  V3 spread_emission{0, 0, 0};
  std::uint32_t entity = 0;
  float distance = 0;
};

// A triangle soup with one material, for tests and simple scenes.
struct TriangleSoup {
  std::vector<V3> vertices;
  std::vector<std::array<int, 3>> triangles;
  Material material;
  std::uint32_t entity = 0;
};

struct SceneOptions {
  const Camera* view = nullptr;  // world coordinates; null: no culling, every tile detailed
  float aspect = 16.0f / 9;
  float detail_distance = 2500;  // m: tiles farther than this get extruded boxes, no roofs
  float tile_size = 400;         // m
  bool ground_plane = true;      // the infinite grass plane beyond the city
  bool landscape_trees = true;   // the woods and hedgerows beyond the city (render/landscape.h)
  // Buildings in two plain colours by where they come from: mapped (read from the sketch)
  // light grey, generated (extruded or placed models) orange; no windows.
  bool mark_mapped = false;
  // Night (render/night.h): the share of windows lit, their radiance, and the street
  // lamps' intensity (their point lights', down) and their heads' radiance; 0: day.
  float lit_windows = 0;
  V3 window_light{0, 0, 0};
  float lamp_intensity = 0, lamp_head_radiance = 0;
};

struct TileLevel {
  int tile;
  std::string level;  // "detailed", "simple" or "culled"
};

class RenderScene {
 public:
  RenderScene(const exacity::City& city, V3 sun_direction, const SceneOptions& options);
  explicit RenderScene(const std::vector<TriangleSoup>& soups, bool ground_plane = false);
  ~RenderScene();
  RenderScene(const RenderScene&) = delete;
  RenderScene& operator=(const RenderScene&) = delete;

  // The nearest surface along the ray (origin and direction in scene coordinates).
  bool intersect(V3 origin, V3 direction, float tmax, Surface& hit) const;
  bool occluded(V3 origin, V3 direction, float tmax) const;
  // Up to kPacket rays at once, each as intersect() and occluded() (tmax infinite) would
  // find it: Embree traces them as one packet, faster where they are coherent, as a
  // pixel's camera rays and their shadow rays to the sun are (one by one where this
  // Embree was built without packets).
  static constexpr int kPacket = 16;
  void intersect_packet(const V3* origins, const V3* directions, int count, Surface* hits, bool* found) const;
  void occluded_packet(const V3* origins, const V3* directions, int count, bool* blocked) const;
  // Raw Embree throughput, for the benchmark: rtcIntersect1 alone.
  bool raw_intersect(V3 origin, V3 direction) const;

  // Scene coordinates are city coordinates less this origin (floats keep millimetres).
  double origin_x = 0, origin_y = 0;
  V3 to_scene(double x, double y, double z) const {
    return {static_cast<float>(x - origin_x), static_cast<float>(y - origin_y), static_cast<float>(z)};
  }
  // A camera given in city coordinates, moved into the scene's.
  Camera to_scene(Camera c) const {
    c.from = to_scene(c.from.x, c.from.y, c.from.z), c.to = to_scene(c.to.x, c.to.y, c.to.z);
    return c;
  }
  geom::Box bounds;  // the city, in scene coordinates
  float ground = 0, top = 0;
  std::vector<TileLevel> tiles;
  std::size_t triangles = 0, instances = 0;
  std::size_t landscape_instances = 0;  // the trees beyond the city, apart from the city's instances
  // The street lamps' point lights, every lamp of the city's whether its tile is seen or
  // not, where SceneOptions::lamp_intensity is above 0.
  std::vector<Lamp> lamps;
  // The most memory Embree held at once, from its device's memory monitor.
  std::size_t embree_peak_bytes() const { return device_.peak_bytes(); }

 private:
  void release();
  struct Hit;
  bool surface(V3 origin, V3 direction, float tmax, const Hit& hit, Surface& s) const;
  bool meets_ground_plane(V3 origin, V3 direction, float tmax) const;
  struct Geometry;
  struct Palette;
  unsigned add_triangles(const std::vector<V3>& vertices, const std::vector<std::array<int, 3>>& tris, Geometry info);
  int add_material(Material m, Pattern p = Pattern::None);
  void build(const exacity::City& city, V3 sun, const SceneOptions& options);
  void make_palette(Palette& p);
  void add_ground(const exacity::City& city, const geom::Box& world, const Palette& palette);
  struct DrapedPiece {
    const geom::Polygon* polygon;
    int material;
    std::uint32_t entity;
    double lift;          // m above the terrain
    double level = NAN;   // flat at this height instead, where finite (water, bridge decks)
  };
  void add_terrain(const exacity::Terrain* terrain, const geom::Box& world, const std::vector<geom::Polygon>& water);
  void add_draped(const std::vector<DrapedPiece>& pieces, const exacity::Terrain* terrain);
  void add_road_markings(const exacity::Ground& ground, const exacity::BridgeDecks& decks,
                         const exacity::Terrain* terrain, const Palette& palette);
  void add_lines(const exacity::RoadLine& road, const exacity::Terrain* under, double lift, std::uint32_t entity,
                 const Palette& palette, std::vector<V3>& vertices, std::vector<std::array<int, 3>>& triangles,
                 Geometry& info);
  void add_onward(const exacity::Ground& ground, const exacity::Terrain* terrain, const geom::Box& drawn,
                  const WaterOnward& water, const Palette& palette);
  void add_crossings(const exacity::Ground& ground, const exacity::Terrain* terrain, const Palette& palette,
                     std::vector<V3>& vertices, std::vector<std::array<int, 3>>& triangles, Geometry& info);
  void add_landscape(const exacity::City& city, const geom::Box& world, const SceneOptions& options);
  void add_buildings(const exacity::City& city, const geom::Box& world, V3 sun, const SceneOptions& options,
                     const Palette& palette);
  struct StructureTiles;
  struct TileView;
  struct ModelMaterials;
  StructureTiles tile_structures(const exacity::City& city, const geom::Box& world, float tile_size);
  TileView view_tiles(const std::vector<Box3>& boxes, const SceneOptions& options);
  ModelMaterials add_model_materials(const exacity::ModelLibrary* library, float lamp_head_radiance);
  RTCScene model_scene(const exacity::ModelLibrary& library, int model);
  void fill_mesh_scene(RTCScene scene, const exacity::TriangleMesh& mesh);
  unsigned add_instance(const exacity::ModelInstance& m, const exacity::ModelLibrary& library,
                    const ModelMaterials& materials, Entity entity = Entity::Model);

  EmbreeDevice device_;  // declared first: released after the scenes
  RTCScene scene_ = nullptr;
  std::vector<RTCScene> model_scenes_;
  std::vector<Geometry> geometries_;  // by top-level geomID
  std::vector<Material> materials_;
  std::vector<Pattern> patterns_;  // by material
  // Model textures, one per image, and each textured material's (by material index; a
  // null texture where the material has none).
  struct MaterialTexture {
    const Texture* texture = nullptr;
    bool clamp = false;
  };
  std::map<const exacity::TextureImage*, std::unique_ptr<Texture>> textures_;
  std::vector<MaterialTexture> material_textures_;
  std::vector<FacadeStyle> facades_;  // by building id: its windows' rows and bays
  bool ground_plane_ = true;
  int grass_material_ = -1;
  // The land beyond the city (null for a scene of triangle soups) and its trees' meshes,
  // which their instances' materials point into.
  std::unique_ptr<Landscape> landscape_;
  std::vector<Corridor> corridors_;  // the roads and rivers carried on through it (render/onward.h)
  std::vector<exacity::TriangleMesh> landscape_trees_;
};

// Every lamp of the city's, placed or street clutter, as a point light under its head
// (render/night.h) of `intensity` times its model's scale squared, in city coordinates
// less the origin (a scene's: RenderScene::lamps; the Cycles comparison's lamps: 0, 0).
std::vector<Lamp> city_lamps(const exacity::City& city, float intensity, double origin_x = 0, double origin_y = 0);

}  // namespace render
