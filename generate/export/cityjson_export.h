// OUT/city.city.json: CityJSON 2.0. Buildings as LOD1 and LOD2 solids (LOD2 with
// GroundSurface, WallSurface and RoofSurface semantics), roads, land use and water as LOD1
// surfaces, a TINRelief under the city; vertices quantised to millimetres by `transform`.
#pragma once

#include <filesystem>
#include <vector>

#include "generate/mesh/building_mesh.h"
#include "generate/export/ground_layers.h"
#include "generate/placement/clutter.h"
#include "generate/city/ground.h"
#include "generate/city/terrain.h"

namespace exacity {

// meshes are structure_meshes(buildings, models, ...), by id; ground_layers are
// ground_layers(ground, terrain), whose terrain and bridges CityJSON writes as they are. Placed models are instances of templates,
// one per library model; on terrain, ground surfaces are draped over it. Models' textures
// are written once each into `textures/` beside the file, which the appearance names.
void write_cityjson(const Ground& ground, const std::vector<Building>& buildings,
                    const std::vector<ModelInstance>& models, const std::vector<Mesh>& meshes,
                    const ModelLibrary* library, const Terrain* terrain, const std::vector<GroundLayer>& ground_layers,
                    const nlohmann::ordered_json& crs, const std::filesystem::path& file, const std::vector<Clutter>& clutter = {});

}  // namespace exacity
