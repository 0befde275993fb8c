// Building meshes to files at full double precision, x east, y north, z up, in metres:
// OUT/city.obj with city.mtl (shortest round-trip decimals; one material per zone and
// surface class) and OUT/city.ply (doubles, with each face's surface class).
#pragma once

#include <filesystem>
#include <vector>

#include "generate/export/building_mesh.h"

namespace exacity {

struct MeshCounts {
  std::size_t vertices = 0, faces = 0;
};

// Writes both files; meshes are structure_meshes(buildings, models, ...), by id. The counts
// are of the whole city.
MeshCounts write_meshes(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                        const std::vector<Mesh>& meshes, const std::filesystem::path& obj_file,
                        const std::filesystem::path& ply_file);

}  // namespace exacity
