// Triangles covering a polygon with holes, for roofs and ground surfaces.
#pragma once

#include <array>
#include <vector>

#include "geom/plain.h"

namespace geom {

// Triangles as indices into the polygon's vertices, numbered outer ring first, then each
// hole in turn; counter-clockwise. Constrained Delaunay, with exact predicates. None when
// the rings cross each other or every vertex lies on one line.
std::vector<std::array<int, 3>> triangulate(const Polygon& polygon);
// The same with extra vertices strictly inside, numbered after the rings' vertices.
std::vector<std::array<int, 3>> triangulate(const Polygon& polygon, const std::vector<Vec2>& inside);

}  // namespace geom
