// Lots inside blocks (seed 000, 3.2.2; seed 003's split), exact and in the same planar map.
// Lot corners are computed in doubles and rounded to the grid, so every lot edge is a grid
// line; a lot is labelled only on faces of its own block, so where it would cross a road it
// is cut back exactly there, and where lots overlap the first one listed owns the overlap.
#pragma once

#include <vector>

#include "generate/blocks.h"
#include "generate/sketch.h"
#include "generate/zone_map.h"

namespace exacity {

struct Lot {
  int block = -1;
  ZoneType zone = ZoneType::Residential;
  bool frontage = false;  // must touch a road area (split lots)
  geom::Ring ring;        // grid points, counter-clockwise (allocated lots) ...
  geom::Cell cell;        // ... or an exact part of the block (split lots, whole-block lots)
};

// The lots of every block that is not green space, block by block in parallel.
std::vector<Lot> plan_lots(const std::vector<Block>& blocks, const Sketch& sketch);

// The lots and their blocks into the map in one batch; faces then know their lot.
void insert_lots(ZoneMap& zone_map, const std::vector<Block>& blocks, const std::vector<Lot>& lots,
                 const Sketch& sketch);

// Seed 000's weighted centre of a block's corners: each weighted by 1 + cos of its angle.
geom::Vec2 weighted_centre(const std::vector<geom::Vec2>& corners);

// Seed 000's residential lots at corner v1 (between v0 and v2) of a block with this
// centre: a corner lot and an inside lot, or, where a projection misses, the seed's two
// special cases; none where both miss. Not yet on the grid.
std::vector<geom::Ring> corner_lots(geom::Vec2 v0, geom::Vec2 v1, geom::Vec2 v2, geom::Vec2 centre);

// corner_lots at every corner of a block (corners counter-clockwise).
std::vector<geom::Ring> residential_lots(const std::vector<geom::Vec2>& corners, geom::Vec2 centre);

}  // namespace exacity
