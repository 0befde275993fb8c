// The city's meshes to files at full double precision, x east, y north, z up, in metres:
// OUT/city.obj with city.mtl (shortest round-trip decimals) and OUT/city.ply (doubles, with
// each face's surface class). Buildings and models first, an object each with a
// material per zone and surface class; then the ground's layers as city.glb has them
// (ground_layers: terrain, zones, water, roads, bridges), an object and a material each,
// named as city.glb names its materials.
#pragma once

#include <filesystem>
#include <vector>

#include "generate/mesh/building_mesh.h"
#include "generate/export/ground_layers.h"
#include "generate/export/meshed_city.h"

namespace exacity {

struct MeshCounts {
  std::size_t vertices = 0, faces = 0;
};

// Writes both files: the city's structures' meshes and its ground's layers. The counts are
// of the whole city, ground included.
MeshCounts write_meshes(const MeshedCity& city, const std::filesystem::path& obj_file,
                        const std::filesystem::path& ply_file);

}  // namespace exacity
