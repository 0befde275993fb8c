// Pitched roofs over a footprint, as planar faces in 3D (counter-clockwise seen from above
// and outside). The straight skeleton is not exact (docs/design.md, Exactness rule 3): it is used here only
// for roof shapes, never for the planar map, and checked.
#pragma once

#include <array>
#include <vector>

#include "geom/plain.h"
#include "geom/vec3.h"

namespace geom {

using Face3 = std::vector<Vec3>;

// One face per footprint edge, rising with `slope` (rise over run) from eaves at height
// `eaves`: CGAL's interior straight skeleton, each node lifted by its offset time. Empty
// when the skeleton fails or leaves the footprint.
std::vector<Face3> hipped_roof(const Polygon& footprint, double eaves, double slope);

// For a footprint of four corners without holes: two slopes meeting at a ridge along the
// longer sides, and the two gable triangles. Empty for other footprints.
std::vector<Face3> gabled_roof(const Polygon& footprint, double eaves, double slope);

// The highest point of faces (0 when there are none).
double roof_top(const std::vector<Face3>& faces);

}  // namespace geom
