// The outline of a heightmap's water (value 0 marks water), smooth where the
// pixels step: a contour of the water mask filtered at pixel scale (docs/design.md, Heightmap water).
#pragma once

#include <vector>

#include "geom/plain.h"

namespace exacity {

// `water` holds width x height flags, row 0 north, stretched over `bounds`. Returns closed
// rings with water on their left (outer rings counter-clockwise, holes clockwise), corners on
// the grid (geom/grid.h), each simple and none touching another; water at the map's edge
// runs along the bounds. Every water pixel's centre lies inside; where pixels are finer than
// a few grid steps they are taken in blocks, a block with any water being water.
std::vector<geom::Ring> water_outline(const std::vector<char>& water, int width, int height, const geom::Box& bounds);

}  // namespace exacity
