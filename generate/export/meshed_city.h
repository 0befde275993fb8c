// The city as the 3D writers draw it: the typed city and what is made once for all of them
// (each structure's mesh, the ground's layers), so that no writer reads another's file back.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "generate/city/ground.h"
#include "generate/city/terrain.h"
#include "generate/export/ground_layers.h"
#include "generate/mesh/building_mesh.h"
#include "generate/placement/clutter.h"

namespace exacity {

struct MeshedCity {
  const Ground& ground;
  const std::vector<GroundLayer>& ground_layers;  // ground_layers(ground, terrain)
  const std::vector<Building>& buildings;
  const std::vector<ModelInstance>& models;
  const std::vector<Mesh>& meshes;  // structure_meshes(buildings, models, ...), by structure id
  const std::vector<Clutter>& clutter;
  const ModelLibrary* library = nullptr;
  const Terrain* terrain = nullptr;
  const nlohmann::ordered_json& crs;  // the sketch's, as its GeoJSON names it
  std::uint64_t seed = 0;  // the city's: with each structure's stable id, its facade and roof albedos in city.glb
};

}  // namespace exacity
