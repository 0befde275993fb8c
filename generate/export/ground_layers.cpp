#include "generate/export/ground_layers.h"

#include <cmath>
#include <map>

#include "generate/cancel.h"
#include "generate/mesh/bridges.h"

namespace exacity {

geom::Box city_box(const Ground& ground) {
  geom::Box box = ground.bounds();
  if (box.holds_nothing()) box = {0, 0, 1, 1};
  return box;
}

namespace {

// Appends `polygon` draped at `lift` over the terrain, or flat at height `flat` when that is
// a number, as drape and drape_flat do: from the memo, its vertices counted from the mesh's.
void append_piece(const geom::Polygon& polygon, const Terrain* terrain, double lift, double flat,
                  Memo<GroundMesh>* memo, GroundMesh& out) {
  auto drape_it = [&](GroundMesh& mesh) {
    if (std::isnan(flat)) drape(polygon, terrain, lift, mesh);
    else drape_flat(polygon, flat, mesh);
  };
  if (!memo) return drape_it(out);
  std::string key = std::isnan(flat) ? "drape " : "flat ";
  append_key(key, std::isnan(flat) ? lift : flat);
  append_key(key, polygon);
  const GroundMesh piece = memo->get(key, [&] {
    GroundMesh mesh;
    drape_it(mesh);
    return mesh;
  });
  const int first = static_cast<int>(out.vertices.size());
  out.vertices.insert(out.vertices.end(), piece.vertices.begin(), piece.vertices.end());
  for (const auto& t : piece.triangles) out.triangles.push_back({first + t[0], first + t[1], first + t[2]});
}

}  // namespace

std::vector<GroundLayer> ground_layers(const Ground& ground, const Terrain* terrain, Memo<GroundMesh>* pieces) {
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
    append_piece(z.polygon, terrain, 0.05, NAN, pieces, it->second.mesh);
  }
  for (auto& [material, layer] : zones) layers.push_back(std::move(layer));
  // Water level at its shore height, bridges level between their ends, on piers
  // (docs/design.md, Ground meshes).
  GroundLayer water{GroundKind::Water, "water", ground_colour(ZoneType::Water), 0.1, {}};
  for (const geom::Polygon& w : ground.water) append_piece(w, nullptr, 0, water_level(w, terrain) + 0.05, pieces, water.mesh);
  layers.push_back(std::move(water));
  const BridgeDecks decks = bridge_decks(ground, terrain);
  GroundLayer roads{GroundKind::Road, "road", kRoadColour, 0.9, {}};
  for (std::size_t i = 0; i < ground.road_areas.size(); ++i) {
    cancel.check();
    const RoadArea& a = ground.road_areas[i];
    append_piece(a.polygon, terrain, kRoadOverTerrain, a.bridge ? decks.height[i] : NAN, pieces, roads.mesh);
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
