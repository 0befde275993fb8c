// The outline of a set of triangles seen from above: a model's footprint on the ground.
#pragma once

#include <array>
#include <vector>

#include "geom/plain.h"

namespace geom {

// The union of the triangles, their corners first rounded to the grid (triangles that
// round flat are dropped), as polygons with holes: exact, simple, counter-clockwise.
std::vector<Polygon> union_of_triangles(const std::vector<std::array<Vec2, 3>>& triangles);

}  // namespace geom
