// Validation's map of every written polygon, built tile by tile (docs/design.md, Validation
// by tiles): each tile's map holds what can change a winding number inside the tile, and
// only the faces inside it are checked.
#pragma once

#include <vector>

#include "geom/plain.h"

namespace exacity {

// An edge of a ring as a tile's map holds it: one of the ring's own, or a piece of a path
// that stands in for a run of the ring's edges outside the tile.
struct TileEdge {
  geom::Vec2 a, b;
  bool stand_in = false;
};

// The edges of `ring` a map needs for the winding numbers of the points of `tile` (a closed
// box): every edge whose box meets the tile, as it is, and for each run of the others (each
// outside the tile) a path from the run's first vertex to its last through the tile's
// corners that winds around the tile as the run does. A ring with no edge near the tile
// becomes the tile's outline, once for each time it winds around the tile (nothing for a
// ring beside it). So every point of the tile winds as often around the edges as around
// the ring, and every point of the ring in the tile lies on an edge of its own. The
// stand-ins lie outside the tile but for the outline's sides and corners. Appends to `out`.
void ring_near_tile(const geom::Ring& ring, const geom::Box& tile, std::vector<TileEdge>& out);

}  // namespace exacity
