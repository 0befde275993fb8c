// Perimeter blocks (docs/design.md, Algorithms: extruded buildings): a lot's extruded
// building is the lot's land within a depth of its street frontages, so the lots round a
// block build one continuous frontage round a courtyard, as the centres of many European
// cities are built.
#pragma once

#include <vector>

#include "geom/cell.h"
#include "geom/plain.h"

namespace exacity {

// The lot's land from `setback` to `setback + depth` behind each edge of `road_kind` (and as
// far past the edge's ends), `clearance` inside the lot's edges: polygons on the grid,
// with holes where the land round a courtyard is all frontage. Proposals in doubles: the
// lot's Occupancy has the last word. None for a lot without frontage, or one too thin
// for the clearance.
std::vector<geom::Polygon> perimeter_footprints(const geom::Cell& lot, int road_kind, double setback, double depth,
                                                double clearance);

}  // namespace exacity
