// Surfaces on the ground that follow the terrain (seed 002's flaw avoided: a road
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

// The terrain over `box` as a regular grid of at most `max_cells` cells a side (flat:
// two triangles).
GroundMesh terrain_tin(const Terrain* terrain, const geom::Box& box, int max_cells);

}  // namespace exacity
