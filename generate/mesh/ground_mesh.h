// Surfaces on the ground that follow the terrain (a road draped only at its corners would sink: a road
// triangulated only at its corners cuts through the hills between them). Edges are split
// every half pixel and the pixel centres inside become vertices, so every surface bends
// with the heightmap; roads are lifted a little above it.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "generate/placement/obj_file.h"
#include "generate/city/terrain.h"
#include "geom/plain.h"

namespace exacity {

// The origin the 3D outputs and the renderer count from, so single floats keep
// millimetres across a large city: the whole metre nearest the centre of the city's
// ground (CityJSON's integer frame is its own: the `transform` the format defines).
inline geom::Vec2 local_origin(const geom::Box& ground) {
  return {std::round((ground.min_x + ground.max_x) / 2), std::round((ground.min_y + ground.max_y) / 2)};
}

struct GroundMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from above
};

// The polygon triangulated at terrain height + lift; flat at `lift` without terrain.
// Appends to `out`.
void drape(const geom::Polygon& polygon, const Terrain* terrain, double lift, GroundMesh& out);
// The polygon triangulated flat at height z (its corners only). Appends to `out`.
void drape_flat(const geom::Polygon& polygon, double z, GroundMesh& out);

// A wall along each edge of the ring, from height from(p) to height to(p) at its corners:
// a bank from the land down to a bed, a deck's side. Appends to `out`.
template <typename From, typename To>
void add_wall(const geom::Ring& ring, const From& from, const To& to, GroundMesh& out) {
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const geom::Vec2 a = ring[j], b = ring[i];
    const int first = static_cast<int>(out.vertices.size());
    out.vertices.push_back({a.x, a.y, from(a)});
    out.vertices.push_back({b.x, b.y, from(b)});
    out.vertices.push_back({b.x, b.y, to(b)});
    out.vertices.push_back({a.x, a.y, to(a)});
    out.triangles.push_back({first, first + 1, first + 2});
    out.triangles.push_back({first, first + 2, first + 3});
  }
}

// The terrain over `box` as a regular grid of at most `max_cells` cells a side (flat:
// two triangles).
GroundMesh terrain_tin(const Terrain* terrain, const geom::Box& box, int max_cells);

// How far water lies under the lowest ground along its outline, in metres: a bank edge
// shows between them.
constexpr double kWaterBelowBank = 0.8;
// Water lies level kWaterBelowBank under its shore: the lowest terrain along its outline (0
// without terrain), so it neither climbs its banks nor spills over them (docs/design.md,
// Ground meshes).
double water_level(const geom::Polygon& water, const Terrain* terrain);
// How far a riverbed lies at least under its water's surface, in metres.
constexpr double kBedDepth = 0.5;
// A bank on a heightmap falls this many metres a metre (1 in 2) from the land at the
// water's outline to the bed, or more steeply where the water is narrow.
constexpr double kBankSlope = 0.5;
// The bed under water of level `level` at p: the terrain, at least kBedDepth under it.
double bed_height(const Terrain* terrain, geom::Vec2 p, double level);

// The ground over `box` (grown by a cell, so water on its edge stays inside), conforming
// to the water outlines: the land, triangulated along every water ring so a bank follows
// the water's outline exactly; each bank sloping inside it from the land down to the bed,
// kBedDepth under the water's level (kBankSlope, or steeper where the water is narrow);
// the bed under the water. Over `detail` the cells are the
// heightmap's pixels, or coarser so that at most `max_cells` span its side; past it,
// coarser so that about 128 more span the rest of the box. Without terrain the land is flat
// at 0 (the box grown by a metre, triangulated around the water) and each bank is a wall
// from it down to the bed.
GroundMesh terrain_mesh(const Terrain* terrain, const geom::Box& box, const geom::Box& detail,
                        const std::vector<geom::Polygon>& water, int max_cells);

}  // namespace exacity
