// Lots inside blocks (seed 000, 3.2.2; seed 003's split), exact and in the same planar map.
// Lot corners are computed in doubles and rounded to the grid, so every lot edge is a grid
// line; a lot is labelled only on faces of its own block, so where it would cross a road it
// is cut back exactly there, and where lots overlap the first one listed owns the overlap.
#pragma once

#include <vector>

#include "generate/parcels/blocks.h"
#include "generate/city/random.h"
#include "generate/city/sketch.h"
#include "generate/city/city_map.h"

namespace exacity {

// A planned lot: a ring of grid points, counter-clockwise (allocated lots), or an exact part
// of the block (split lots).
struct PlannedLot {
  int block = -1;
  ZoneType zone = ZoneType::Residential;
  geom::Ring ring;
  geom::Cell cell;
};

// A lot as it ended up in the map: one piece of a planned lot, cut back at roads and at
// the lots planned before it, that touches a road area, is at least the zone's
// `min_lot_area` and keeps its depth over width within kLotShape. Its index in the city's
// lots is its id.
struct Lot {
  int block = -1;
  ZoneType zone = ZoneType::Residential;
  std::string density;     // its block's (a grammar's): "" for the zone's own
  geom::Cell cell;         // as written (doubles); edges along a road area have kind kLotRoadEdge, the others 0
  geom::Polygon polygon;   // the same, as a plain polygon
};
inline constexpr int kLotRoadEdge = 1;
inline constexpr Range kLotShape{0.5, 5};  // a lot's depth over its width (across and along its street)

// The lots of every block that is not green space, block by block in parallel.
std::vector<PlannedLot> plan_lots(const std::vector<Block>& blocks, const Sketch& sketch);

// Seed 000's lots measured from the street: along every run of road edges of the block
// (edge kind >= 0), lots side by side, about `lot_width` wide and `lot_depth` deep (at most
// half the way across the block), split at the run's corners along the corner's bisector;
// the block's middle is left open. Rings in doubles, not yet on the grid; each reaches a
// little past the block's edge, so the map cuts it back exactly there.
std::vector<geom::Ring> street_lots(const geom::Cell& block, const ZoneParams& p, Random& rng);

// The planned lots into the map in one batch; faces of a block then know the lot planned
// there that they lie in. Returns the lots as they ended up.
std::vector<Lot> insert_lots(CityMap& city_map, const std::vector<PlannedLot>& lots,
                             const Sketch& sketch);

}  // namespace exacity
