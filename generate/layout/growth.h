// Road growth (seed 000, 3.2.1) in exact vector form: from a seed point in each region,
// roads grow step by step until they meet a road or the region's edge; they split the
// region, and each part above its zone's block area is grown again, one level deeper.
#pragma once

#include <utility>
#include <vector>

#include "generate/city/city_map.h"
#include "generate/city/sketch.h"

namespace exacity {

// The kind of a growth cell's edge (its geom::Cell edge tag): the region's edge, a road
// grown in the same region, or the surface of a sketch road. A cell below the top level
// must reach a road of its region or a sketch road, so every region's road graph is
// connected and joins the sketch's roads; a road that stops at a sketch road's surface
// runs on to its centre line.
struct GrowthEdge {
  static constexpr int kRegionEdge = 0, kGrownRoad = 1;
  static constexpr int sketch_road(int r) { return 2 + r; }
  // The sketch road whose surface an edge of this kind is, or -1.
  static constexpr int sketch_road_of(int kind) { return kind >= 2 ? kind - 2 : -1; }
};

// The sketch's roads, which grown roads run on to: centre lines and width.
struct SketchRoad {
  std::vector<geom::Path> lines;
  double width = 0;
};
using SketchLines = std::vector<SketchRoad>;

// A disc of road where roads meet, to join them cleanly: at a seed, at a link's ends.
struct Junction {
  geom::Vec2 at;
  int first_road;
};
// What growing every region gave besides its roads, which are appended to the map's roads
// (not yet inserted).
struct GrownRegions {
  int regions = 0, levels = 0;
  int cells_without_access = 0;     // cells left whole: none of their roads could reach a road
  std::vector<char> joined;         // per region: its roads run on to a sketch road
  std::vector<Junction> junctions;  // where a seed's roads meet
};

// Grows the roads of every region of zones laid out by growth (and the water under them
// where the zone lets roads bridge it), all regions a level at a time. `kind` is each face
// label's GrowthEdge kind.
GrownRegions grow_regions(CityMap& city_map, const Sketch& sketch, const SketchLines& sketch_lines,
                          const std::vector<int>& kind);

// The edges a cell's roads must reach: below the top level its region's roads, at the top
// the sketch roads it borders (none: it need reach nothing).
std::vector<std::pair<geom::Vec2, geom::Vec2>> edges_to_reach(const geom::Cell& cell, bool top);

}  // namespace exacity
