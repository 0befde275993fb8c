// What the files that build and query a RenderScene share (render/scene.h): the record a
// hit maps back through (Geometry), the materials of the palette, the tiles' bookkeeping,
// Embree's hit. One concept a file, as pbrt-v4 keeps its scene, aggregates and materials
// apart: scene.cpp (the device, the build's order, geometries), scene_materials.cpp (the
// palette and the models' materials), scene_ground.cpp (terrain, draped layers, markings,
// bridges), scene_tiles.cpp (tiles and levels of detail), scene_structures.cpp (buildings
// and model instances), scene_queries.cpp (Embree's ray queries), scene_shading.cpp (the
// surface at a hit: material, texture, pattern).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "generate/city/palette.h"
#include "render/scene.h"
#include "render/tile_culling.h"

namespace render {

inline V3 colour(const exacity::Colour& c) {
  return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

inline V3 colour(const exacity::Albedo& a) { return {a[0], a[1], a[2]}; }


// The materials of the ground and of buildings, as indices.
struct RenderScene::Palette {
  int sidewalk = 0, asphalt = 0, paint = 0, yellow = 0, water = 0;
  int mapped = 0, generated = 0;  // SceneOptions::mark_mapped's
  std::map<exacity::ZoneType, int> lot_ground;
  std::map<std::pair<exacity::ZoneType, int>, int> facade, roof;  // (zone, palette entry)
};

// What a geometry of the top scene holds, by its geomID: each triangle's material and
// entity, or an instance's.
struct RenderScene::Geometry {
  std::vector<int> material;          // per triangle; for instances, per model triangle
  const std::vector<int>* shared_material = nullptr;  // instances: their model's, instead of `material`
  int material_of(unsigned prim) const { return shared_material ? (*shared_material)[prim] : material[prim]; }
  int instance_override = -1;  // instances: every triangle's material instead, where not negative
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

// What Embree reports of a ray's nearest hit; geom is RTC_INVALID_GEOMETRY_ID on a miss.
struct RenderScene::Hit {
  unsigned geom, prim, inst;
  float t, u, v;
  V3 ng;
};

}  // namespace render
