#include "generate/export/ground_layers.h"

#include <map>

#include "generate/cancel.h"
#include "generate/mesh/bridges.h"

namespace exacity {

geom::Box city_box(const Ground& ground) {
  geom::Box box = ground.bounds();
  if (box.holds_nothing()) box = {0, 0, 1, 1};
  return box;
}

std::vector<GroundLayer> ground_layers(const Ground& ground, const Terrain* terrain) {
  const geom::Box box = city_box(ground);
  std::vector<GroundLayer> layers;
  layers.push_back(
      {GroundKind::Terrain, "terrain", kTerrainColour, 0.9, terrain_mesh(terrain, box, box, ground.water, 512)});
  std::map<std::string, GroundLayer> zones;  // by name: the layers' order
  const CancelCheck cancel;
  for (const ZoneArea& z : ground.zones) {
    cancel.check();
    const std::string material = "ground_" + std::string(name(z.type));
    auto [it, added] =
        zones.try_emplace(material, GroundLayer{GroundKind::Zone, material, ground_colour(z.type), 0.9, {}});
    drape(z.polygon, terrain, 0.05, it->second.mesh);
  }
  for (auto& [material, layer] : zones) layers.push_back(std::move(layer));
  // Water level at its shore height, bridges level between their ends, on piers
  // (docs/design.md, Ground meshes).
  GroundLayer water{GroundKind::Water, "water", ground_colour(ZoneType::Water), 0.1, {}};
  for (const geom::Polygon& w : ground.water) drape_flat(w, water_level(w, terrain) + 0.05, water.mesh);
  layers.push_back(std::move(water));
  const BridgeDecks decks = bridge_decks(ground, terrain);
  GroundLayer roads{GroundKind::Road, "road", kRoadColour, 0.9, {}};
  for (std::size_t i = 0; i < ground.road_areas.size(); ++i) {
    cancel.check();
    const RoadArea& a = ground.road_areas[i];
    if (a.bridge)
      drape_flat(a.polygon, decks.height[i], roads.mesh);
    else
      drape(a.polygon, terrain, kRoadOverTerrain, roads.mesh);
  }
  layers.push_back(std::move(roads));
  GroundLayer bridges{GroundKind::Bridge, "bridge", kBridgeColour, 0.9, {}};
  bridge_structure(ground, terrain, decks, bridges.mesh);
  layers.push_back(std::move(bridges));
  std::erase_if(layers, [](const GroundLayer& l) { return l.mesh.triangles.empty(); });
  return layers;
}

const GroundMesh* layer_mesh(const std::vector<GroundLayer>& layers, GroundKind kind) {
  for (const GroundLayer& l : layers)
    if (l.kind == kind) return &l.mesh;
  return nullptr;
}

}  // namespace exacity
