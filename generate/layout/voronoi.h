// Voronoi streets (docs/design.md, Algorithms): a Voronoi diagram's edges are the main roads, junctions at equal steps
// along them, and inside each cell inner roads joining junctions, the first closest to
// perpendicular to the cell's longest road, the rest most parallel to it. In doubles: the
// layout rounds what it keeps to the grid and the map inserts it exactly.
#pragma once

#include <vector>

#include "geom/plain.h"

namespace exacity {

// The Voronoi diagram of `sites` within `box`: each site's cell (convex, counter-clockwise)
// and, for each of its edges, the site across it (-1 for the box).
struct VoronoiCell {
  geom::Ring ring;
  std::vector<int> across;  // across[k]: the edge ring[k] -> ring[k + 1]
};
std::vector<VoronoiCell> voronoi_cells(const std::vector<geom::Vec2>& sites, const geom::Box& box, double spacing);

// One road around a cell: its points in order along the cell's boundary (counter-clockwise),
// the first and last the road's ends (the cell's corners), junctions between.
using CellRoad = std::vector<geom::Vec2>;

// Inner roads of one convex cell by the junction heuristic: roads are taken longest first; from
// the first free junction of a road, the connection to a junction of another road that is
// closest to perpendicular to it (within 30 degrees); from its other junctions, the
// connections most parallel to that inner road (within 15 degrees); no inner road crosses
// another or shares a junction. Returns pairs of junction points.
std::vector<std::pair<geom::Vec2, geom::Vec2>> inner_roads(const std::vector<CellRoad>& roads);

// Points at equal steps of about `spacing` strictly between a and b (none when the edge is
// shorter than 1.5 steps), rounded to the grid.
std::vector<geom::Vec2> junctions_along(geom::Vec2 a, geom::Vec2 b, double spacing);

}  // namespace exacity
