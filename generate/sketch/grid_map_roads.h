// A grid map's cells and roads (docs/design.md, The sketch; docs/sketch.md, Grid maps), shared by the map's
// reader (grid_map.cpp) and its roads (grid_map_roads.cpp): a road down the middle of each
// straight band of road cells.
#pragma once

#include <vector>

#include "geom/plain.h"

namespace exacity::grid_map {

// What a cell holds (a planned map grid's lot statuses; `.` is an empty lot, residential land).
enum class Status : unsigned char { Residential, Commercial, Industrial, Water, Park, Road, Blocked };

struct GridMap {
  double cell = 0;     // m, a multiple of 1/512 m so that half a cell lies on Exacity's grid
  geom::Vec2 origin;   // the south-west corner, on the grid
  int width = 0, height = 0;
  std::vector<Status> cells;  // row after row, the northernmost first
  std::vector<int> lines;     // each row's line in the file, 1-based

  // A point `hx` half cells east and `hy` half cells north of the south-west corner:
  // every one a point of the grid, computed one way, so equal points are equal doubles.
  geom::Vec2 point(long long hx, long long hy) const {
    const double half = cell / 2;
    return {origin.x + static_cast<double>(hx) * half, origin.y + static_cast<double>(hy) * half};
  }
};

// A point in half cells: x east from the map's west edge, y south from its north edge (rows
// count from the north).
struct Half {
  int x = 0, y = 0;
  friend auto operator<=>(const Half&, const Half&) = default;
};

// A road on the map: a polyline of axis-parallel segments through half-cell points, its
// width in cells, and the cell that names it.
struct RoadPath {
  std::vector<Half> points;
  int cells_across = 1;
  int row = 0, column = 0;
  bool straight = true;  // a band's road, along one line; false for a connector
};

// The map's roads: one down the middle of each straight band of road cells, and connectors
// where road cells join pieces of roads that do not meet.
std::vector<RoadPath> road_paths(const GridMap& map);

}  // namespace exacity::grid_map
