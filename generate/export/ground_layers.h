// The city's ground as the mesh exports carry it (city.glb, city.obj, city.ply): one list of
// layers that each export only writes out, so the three hold the same triangles
// (docs/design.md, Ground meshes).
#pragma once

#include <string>
#include <vector>

#include "generate/city/ground.h"
#include "generate/city/memo.h"
#include "generate/city/palette.h"
#include "generate/city/terrain.h"
#include "generate/mesh/ground_mesh.h"

namespace exacity {

enum class GroundKind { Terrain, Zone, Water, Road, Bridge };

struct GroundLayer {
  GroundKind kind;
  std::string name;  // its material's name in every export: terrain, ground_<zone>, water, road, bridge
  Colour colour;
  double roughness;  // glTF's: water is glossy
  GroundMesh mesh;
};

// The box the 3D exports frame the city in: the ground's bounds, a unit square when it has none.
geom::Box city_box(const Ground& ground);

// Layer over layer a few centimetres apart so none hides the next: the terrain over city_box
// (with the banks and the beds under the water), the zones draped over it (a layer per zone
// type, by name), the water level at its shore height, the road surfaces (bridge decks
// level among them) and the bridges' decks' sides and undersides and their piers. Layers
// without a triangle are left out. With a memo (whose context holds the terrain), each
// zone's, water's and road area's polygon is draped once while it stays the same (a build
// drapes the ground twice, for the 3D exports and the tiles).
std::vector<GroundLayer> ground_layers(const Ground& ground, const Terrain* terrain, Memo<GroundMesh>* pieces = nullptr);

// The mesh of the layer of that kind (the first), null where there is none.
const GroundMesh* layer_mesh(const std::vector<GroundLayer>& layers, GroundKind kind);

}  // namespace exacity
