// OUT/city.glb: glTF 2.0 binary, y up, metres. Positions are floats relative to a local
// origin near the city's centre, held in the root node's translation, so they keep
// millimetres across a large city. The ground (terrain, zones, water, roads) follows the
// terrain; extruded buildings are merged per material; each library model is stored once
// and every placement is a node referring to it (seed 004), one mesh per colour variant
// sharing the same geometry.
#pragma once

#include <filesystem>
#include <vector>

#include "generate/export/building_mesh.h"
#include "generate/placement/model_library.h"
#include "generate/city/terrain.h"
#include "generate/city/ground.h"
#include "generate/placement/buildings.h"

namespace exacity {

struct GltfCounts {
  std::size_t meshes = 0, instances = 0, triangles = 0;
};

// meshes are structure_meshes(buildings, models, library), by id. The street clutter's
// models are instanced like the lots', sharing their geometry: a node each, in id order,
// under the root's child "clutter".
GltfCounts write_gltf(const Ground& ground, const std::vector<Building>& buildings,
                      const std::vector<ModelInstance>& models, const std::vector<Mesh>& meshes,
                      const ModelLibrary* library, const Terrain* terrain, const std::filesystem::path& file,
                      const std::vector<ModelInstance>& clutter = {});

}  // namespace exacity
