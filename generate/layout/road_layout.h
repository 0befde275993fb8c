// Road layouts (docs/design.md, Road layouts): a layout plans the roads of
// one region, a set of connected faces of zones laid out alike; the roads stage
// (road_network.cpp) alone puts plans into the map. Seed 000's growth (growth.h) is not a
// RoadLayout yet: it grows every region a level at a time and looks each level's seeds up in
// the map.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "generate/layout/grammar.h"
#include "generate/city/random.h"
#include "generate/city/sketch.h"
#include "geom/cell.h"

namespace exacity {

struct Region {
  geom::Cell cell;
  // Its boundary edges along a sketch road's surface: the road there is the sketch's.
  std::vector<std::pair<geom::Vec2, geom::Vec2>> along_sketch_roads;
};

struct PlannedRoad {
  geom::Polyline line;  // centre line, in doubles on the grid
  double width = 0;
  RoadClass road_class = RoadClass::Local;
};

// Land a layout gave a use: a grammar's terminals.
struct PlannedUse {
  geom::Ring ring;
  Terminal use;
};

struct RoadPlan {
  std::vector<PlannedRoad> roads;
  std::vector<PlannedUse> uses;
  double join = 0;  // m: road ends this near another road are joined to it (generate/layout/street_graph.h)
};

class RoadLayout {
 public:
  virtual ~RoadLayout() = default;
  virtual RoadPlan plan(const Region& region, Random& random) const = 0;
};

// The layout a zone type's settings name ("grammar", "voronoi" or "streets"; growth has none).
std::unique_ptr<RoadLayout> make_road_layout(const ZoneParams& params, ZoneType type);

// One per file.
std::unique_ptr<RoadLayout> make_grammar_layout(const ZoneParams& params, ZoneType type);
std::unique_ptr<RoadLayout> make_streets_layout();
std::unique_ptr<RoadLayout> make_voronoi_layout(const ZoneParams& params);

}  // namespace exacity
