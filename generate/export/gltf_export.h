// OUT/city.glb: glTF 2.0 binary, y up, metres. Positions are floats relative to a local
// origin near the city's centre, held in the root node's translation, so they keep
// millimetres across a large city. The ground is ground_layers' (terrain, zones, water,
// roads, bridges), as in city.obj and city.ply; extruded buildings are merged per
// material; each library model is stored once
// and every placement is a node referring to it (instancing), one mesh per colour variant
// sharing the same geometry.
#pragma once

#include <filesystem>
#include <vector>

#include "generate/mesh/building_mesh.h"
#include "generate/export/ground_layers.h"
#include "generate/export/meshed_city.h"
#include "generate/placement/model_library.h"
#include "generate/city/ground.h"
#include "generate/placement/buildings.h"

namespace exacity {

struct GltfCounts {
  std::size_t meshes = 0, instances = 0, triangles = 0;
};

// The ground's layers a primitive each of the mesh "ground"; the city's seed with each
// structure's stable id picks its facade and roof albedo (structure_albedos, a material
// each; the renderer still picks by the structure's index, so the two agree only where they
// are equal). The street clutter's models are instanced like the lots', sharing their
// geometry: a node each, in id order, under the root's child "clutter".
GltfCounts write_gltf(const MeshedCity& city, const std::filesystem::path& file);

// exacity serve's tiles (docs/design.md, Serving: tiles), in write_gltf's frame for the
// ground whose city_box is `city` (measured once for all tiles, as the whole ground is
// walked for it), so a tile's structures are city.glb's to the float.
// The structures given and their clutter, as write_gltf writes them, without the ground.
GltfCounts write_gltf_structures(const geom::Box& city, const std::vector<Building>& buildings,
                                 const std::vector<ModelInstance>& models, const std::vector<Mesh>& meshes,
                                 std::uint64_t seed, const ModelLibrary* library, const std::filesystem::path& file,
                                 const std::vector<ModelInstance>& clutter = {});
// Boxes standing for structures far away: a roof and four walls each, coloured as the
// structure whose stable id is `id` is (structure_albedos), or, for a box of several (id -1), in the mean of
// their zone's albedos.
struct StructureBox {
  geom::Box box;
  double bottom = 0, top = 0;
  ZoneType zone = ZoneType::Residential;
  int id = -1;
};
GltfCounts write_gltf_boxes(const geom::Box& city, const std::vector<StructureBox>& boxes, std::uint64_t seed,
                            const std::filesystem::path& file);

}  // namespace exacity
