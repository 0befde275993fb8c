// Road layouts (docs/design.md, Road layouts): a layout plans the roads of one region, a set
// of connected faces of zones laid out alike, as exact centre lines on the grid; the roads
// stage (road_network.cpp) alone puts plans into the map. Growth (growth.cpp) grows its
// roads exactly; the other layouts draw lines in doubles that settle.h makes a network.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "generate/city/zone_settings.h"
#include "generate/layout/grammar.h"
#include "generate/layout/road_settings.h"
#include "geom/cell.h"

namespace exacity {

// The kind of a region's edge (its geom::Cell edge tag): the region's edge, a road grown in
// the same region, or the surface of a sketch road. A road that stops at a sketch road's
// surface runs on to its centre line.
struct GrowthEdge {
  static constexpr int kRegionEdge = 0, kGrownRoad = 1;
  static constexpr int sketch_road(int r) { return 2 + r; }
  // The sketch road whose surface an edge of this kind is, or -1.
  static constexpr int sketch_road_of(int kind) { return kind >= 2 ? kind - 2 : -1; }
};

// The sketch's roads, which planned roads run on to: centre lines and width.
struct SketchRoad {
  std::vector<geom::Path> lines;
  double width = 0;
};
using SketchLines = std::vector<SketchRoad>;

struct Region {
  geom::Cell cell;        // edges tagged by GrowthEdge kind
  std::uint64_t stream;   // the region's random stream
};

// A road of a plan, exact on the grid.
struct LaidRoad {
  geom::Path path;
  double width = 0;
  RoadClass road_class = RoadClass::Local;
  int level = 0;  // growth's level (0 for a region's first roads); main roads 0, others 1
  int piece = 0;  // roads of one piece meet, directly or through others
};

// A disc of road where roads meet, to join them cleanly: at a seed, where a layout's
// roads share a point, at a link's ends. `first_road` indexes the plan's (then the map's)
// roads: the disc takes that road's width and counter.
struct Junction {
  geom::Vec2 at;
  int first_road;
};

// Land a layout gave a use: a grammar's terminals.
struct PlannedUse {
  geom::Ring ring;
  Terminal use;
};

struct RoadPlan {
  std::vector<LaidRoad> roads;
  std::vector<char> piece_reaches_sketch;  // per piece: its roads run on to a sketch road
  std::vector<Junction> junctions;
  std::vector<PlannedUse> uses;
  int levels = 0;                // growth's levels
  int cells_without_access = 0;  // growth's cells left whole: none of their roads could reach a road
  int dropped_roads = 0;         // drawn roads left out: an end reached no road, sketch road or edge
};

class RoadLayout {
 public:
  virtual ~RoadLayout() = default;
  virtual RoadPlan plan(const Region& region) const = 0;
};

// The edges of a region, or of a cell of one, that its roads must reach: below the top
// level the region's grown roads, at the top the sketch roads it borders (none: it need
// reach nothing).
std::vector<std::pair<geom::Vec2, geom::Vec2>> edges_to_reach(const geom::Cell& cell, bool top);

// What a layout is made for: the city's settings, the zone type (for a layout spanning
// zone types, the zone at a point: ZoneAt, growth.h), and the sketch's roads.
struct LayoutSite {
  const CitySettings& city;
  ZoneType type;
  const SketchLines& sketch_roads;
  std::function<std::optional<ZoneType>(geom::Vec2)> zone_at;
  const RoadSettings& roads() const { return city.zone_settings.at(type).roads; }
};

}  // namespace exacity
